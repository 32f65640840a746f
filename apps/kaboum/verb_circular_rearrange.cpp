// `kaboum circular-rearrange N`: writes the Bimanual Circular Rearrange domain (and its variant
// with handover), problem and scene for n bottles (thesis §6.2.1, Table 6.1).
#include "kaboum/scenarios/circular_rearrange.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {

using namespace kaboum::scenarios;

namespace {

VerbRunner setupCircularRearrange(CLI::App& command) {
  PddlGenerator generator{
      "circular-rearrange",
      "Number of bottles (2 to " + std::to_string(kCircularRearrangeMaxObjects) + ")",
      [] { return circularRearrangeDomain(); }, circularRearrangeProblem};
  generator.more = {{[](int) { return std::string("circular-rearrange-handover-domain.pddl"); },
                     [](int) { return circularRearrangeDomain(true); }},
                    {[](int n) { return "circular-rearrange-" + std::to_string(n) + ".yaml"; },
                     circularRearrangeScene}};
  return setupPddlGeneratorVerb(command, std::move(generator));
}

const VerbRegistration registration{
    "circular-rearrange",
    "Write the Bimanual Circular Rearrange domain, problem and scene for n bottles (thesis Table "
    "6.1)",
    setupCircularRearrange};

}  // namespace
}  // namespace kaboum::cli
