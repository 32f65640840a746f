// `kaboum bartender N`: writes the Bartender scenario's symbolic domain and problem for N bottles
// (thesis §6.2.1; docs/contingent.md, "Scenarios").
#include "kaboum/scenarios/bartender.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {
namespace {

VerbRunner setupBartender(CLI::App& command) {
  return setupPddlGeneratorVerb(command,
                                {"bartender", "Number of bottles of unknown emptiness (at least 1)",
                                 scenarios::bartenderDomain, scenarios::bartenderProblem});
}

const VerbRegistration registration{
    "bartender",
    "Write the Bartender's symbolic contingent domain and problem for n bottles (plan them with "
    "`kaboum contingent … --toy-geometry`)",
    setupBartender};

}  // namespace
}  // namespace kaboum::cli
