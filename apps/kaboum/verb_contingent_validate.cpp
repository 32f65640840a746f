// `kaboum contingent-validate DOMAIN PROBLEM PLAN`: checks every branch of a branched plan and,
// with --hidden, executes it against true initial states (thesis §3.3.3 execution of branches).
#include <iostream>
#include <memory>
#include <utility>

#include "kaboum/core/error.hpp"
#include "kaboum/io/json_symbolic.hpp"
#include "kaboum/scenarios/toy_geometry.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::symbolic;
using namespace kaboum::scenarios;

namespace {

struct ValidateOptions {
  std::string domain;
  std::string problem;
  std::string plan;
  std::string hidden;
  std::uint64_t seed = 0;
  std::string knowledge = "auto";
  bool json = false;
  bool toyGeometry = false;
};

int runValidate(const ValidateOptions& options) {
  const symbolic::ContingentProblem contingent =
      symbolic::loadContingent(options.domain, options.problem);
  printWarnings(contingent.domain.warnings);
  printWarnings(contingent.problem.warnings);
  const symbolic::ProcedureRegistry procedures =
      options.toyGeometry ? scenarios::toyGeometryProcedures() : symbolic::ProcedureRegistry{};
  symbolic::KnowledgeTask task(contingent, procedures, std::size_t{1} << 18,
                               symbolic::parseKnowledgeRepresentation(options.knowledge));
  const symbolic::PlanTree plan =
      symbolic::parsePlanTree(symbolic::readTextFile(options.plan), options.plan, task);
  const symbolic::TreeValidation validation = symbolic::validatePlanTree(task, plan, options.plan);
  nlohmann::json executions = nlohmann::json::array();
  bool allExecuted = true;
  if (!options.hidden.empty()) {
    const auto hidden =
        symbolic::parseHidden(symbolic::readTextFile(options.hidden), options.hidden, contingent);
    for (const symbolic::HiddenState& state : hidden) {
      const std::uint32_t world = task.hiddenWorld(state, options.hidden);
      task.seedOutcomes(options.seed);
      const symbolic::Execution run = symbolic::executePlanTree(task, plan, world);
      allExecuted = allExecuted && run.reachedGoal;
      nlohmann::json execution = io::toJson(run);
      execution["line"] = state.pos.line;
      executions.push_back(std::move(execution));
    }
  }
  const bool ok = validation.valid && allExecuted;
  if (options.json) {
    nlohmann::json out = io::toJson(validation);
    out["executions"] = executions;
    std::cout << out.dump(2) << "\n";
  } else {
    if (validation.valid) {
      std::cout << "valid: every branch reaches the goal (" << validation.metrics.leaves
                << " branch(es), depth " << validation.metrics.depth << ")\n";
    } else {
      std::cout << "invalid: " << validation.message << "\n";
    }
    for (const auto& run : executions) {
      std::cout << "hidden state (line " << run["line"].get<long>() << "): "
                << (run["reached_goal"].get<bool>() ? "goal reached after " : "failed after ")
                << run["steps"].size() << " step(s)";
      if (!run["message"].get<std::string>().empty()) {
        std::cout << ": " << run["message"].get<std::string>();
      }
      std::cout << "\n";
    }
  }
  return ok ? 0 : 1;
}

VerbRunner setupValidate(CLI::App& command) {
  auto options = std::make_shared<ValidateOptions>();
  command.add_option("domain", options->domain, "Contingent PDDL domain file")->required();
  command.add_option("problem", options->problem, "Contingent PDDL problem file")->required();
  command.add_option("plan", options->plan, "Plan tree written by `kaboum contingent`")->required();
  command.add_option("--hidden", options->hidden,
                     "File of (:hidden atoms…) true initial states to execute the plan in");
  command
      .add_option("--seed", options->seed,
                  "Seed of nature's choices of non-deterministic effects in those executions")
      ->capture_default_str();
  command
      .add_option("--knowledge", options->knowledge,
                  "Knowledge states: auto, explicit or factored (docs/contingent.md)")
      ->check(CLI::IsMember({"auto", "explicit", "factored"}))
      ->capture_default_str();
  command.add_flag("--toy-geometry", options->toyGeometry,
                   "Register the toy `reaches` attachment of the scenarios");
  command.add_flag("--json", options->json, "Print the result as JSON");
  return [options] { return runValidate(*options); };
}

const VerbRegistration registration{
    "contingent-validate",
    "Check every branch of a branched plan, optionally executing it against hidden states "
    "(exit 0 valid, 1 invalid)",
    setupValidate};

}  // namespace
}  // namespace kaboum::cli
