// `kaboum force-sensing N`: writes the Force Sensing domain and problem (thesis Table 3.1).
#include "kaboum/scenarios/force_sensing.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {

using namespace kaboum::scenarios;

namespace {

VerbRunner setupForceSensing(CLI::App& command) {
  return setupPddlGeneratorVerb(
      command, {"force-sensing", "Number of containers (at least 1)", scenarios::forceSensingDomain,
                scenarios::forceSensingProblem});
}

const VerbRegistration registration{
    "force-sensing",
    "Write the Force Sensing contingent domain and problem for n containers (thesis Table 3.1)",
    setupForceSensing};

}  // namespace
}  // namespace kaboum::cli
