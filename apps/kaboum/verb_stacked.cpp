// `kaboum stacked N`: writes the Stacked n Objects domain and problem (thesis Table 6.3).
#include "kaboum/scenarios/stacked_objects.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {

using namespace kaboum::scenarios;

namespace {

VerbRunner setupStacked(CLI::App& command) {
  return setupPddlGeneratorVerb(
      command, {"stacked", "Number of objects (at least 2)", scenarios::stackedObjectsDomain,
                scenarios::stackedObjectsProblem});
}

const VerbRegistration registration{
    "stacked", "Write the Stacked n Objects PDDL domain and problem (thesis Table 6.3)",
    setupStacked};

}  // namespace
}  // namespace kaboum::cli
