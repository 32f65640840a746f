// `kaboum stacked N [--scene]`: writes the Stacked n Objects domain and problem (thesis Table 6.3),
// or with --scene the scenario with geometry (a mobile manipulator at three stands, §6.2.2).
#include "kaboum/scenarios/stacked_objects.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {

using namespace kaboum::scenarios;

namespace {

VerbRunner setupStacked(CLI::App& command) {
  return setupPddlGeneratorVerb(
      command,
      {"stacked", "Number of objects (at least 2)", scenarios::stackedObjectsDomain,
       scenarios::stackedObjectsProblem},
      SceneGenerator{"stacked-geometry", scenarios::stackedObjectsGeometryDomain,
                     scenarios::stackedObjectsGeometryProblem, scenarios::stackedObjectsScene,
                     "examples/robots/mobile-5axis.urdf"});
}

const VerbRegistration registration{
    "stacked",
    "Write the Stacked n Objects PDDL domain and problem (thesis Table 6.3), or with --scene the "
    "scenario with geometry for kaboum solve",
    setupStacked};

}  // namespace
}  // namespace kaboum::cli
