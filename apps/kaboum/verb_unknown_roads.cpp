// `kaboum unknown-roads N`: writes a navigation domain and problem with N independent unknown
// roads (docs/contingent.md, "Knowledge representations").
#include "kaboum/scenarios/unknown_roads.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {
namespace {

VerbRunner setupUnknownRoads(CLI::App& command) {
  return setupPddlGeneratorVerb(command,
                                {"unknown-roads",
                                 "Number of legs, each with one unknown road "
                                 "(at least 1)",
                                 scenarios::unknownRoadsDomain, scenarios::unknownRoadsProblem});
}

const VerbRegistration registration{
    "unknown-roads",
    "Write a contingent navigation domain and problem with n independent unknown roads",
    setupUnknownRoads};

}  // namespace
}  // namespace kaboum::cli
