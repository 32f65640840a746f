// `kaboum contingent DOMAIN PROBLEM`: knowledge-level planning with sensing; prints a branched
// plan (thesis §3.3.1, Figure 3.2) as an indented tree or JSON.
#include <fstream>
#include <iostream>
#include <memory>

#include "kaboum/core/error.hpp"
#include "kaboum/core/planner_status.hpp"
#include "kaboum/io/json_symbolic.hpp"
#include "kaboum/scenarios/toy_geometry.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/symbolic/heuristic.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::symbolic;
using namespace kaboum::scenarios;

namespace {

struct ContingentCliOptions {
  std::string domain;
  std::string problem;
  std::string planOut;
  std::size_t maxWorlds = std::size_t{1} << 18;
  std::string knowledge = "auto";
  bool json = false;
  bool quiet = false;
  bool toyGeometry = false;
  symbolic::ContingentOptions search;
};

int runContingent(const ContingentCliOptions& options) {
  const symbolic::ContingentProblem contingent =
      symbolic::loadContingent(options.domain, options.problem);
  printWarnings(contingent.domain.warnings);
  printWarnings(contingent.problem.warnings);
  const symbolic::ProcedureRegistry procedures =
      options.toyGeometry ? scenarios::toyGeometryProcedures() : symbolic::ProcedureRegistry{};
  symbolic::KnowledgeTask task(contingent, procedures, options.maxWorlds,
                               symbolic::parseKnowledgeRepresentation(options.knowledge));
  const symbolic::ContingentResult result = symbolic::solveContingent(task, options.search);
  const bool solved = result.status == PlannerStatus::Solved;
  const symbolic::TreeMetrics metrics = symbolic::measure(result.plan);
  const std::string tree = solved ? symbolic::formatPlanTree(task, result.plan) : "";
  if (solved && !options.planOut.empty()) {
    std::ofstream out(options.planOut);
    if (!out || !(out << tree)) throw InputError(locate(options.planOut, "cannot write plan file"));
  }
  const auto& stats = result.statistics;
  if (options.json) {
    nlohmann::json report = io::toJson(task, result);
    report["search"] = options.search.mode;
    std::cout << report.dump(2) << "\n";
  } else {
    if (solved && options.planOut.empty()) std::cout << tree;
    if (!options.quiet) {
      std::cerr << "kaboum contingent: " << toString(result.status);
      if (solved) {
        std::cerr << ", " << metrics.actions << " action(s) in the tree, " << metrics.leaves
                  << " leaf/leaves, depth " << metrics.depth << ", " << metrics.dagNodes
                  << " distinct node(s)";
      }
      std::cerr << "; " << task.possibleWorlds(task.initialBelief()) << " initial world(s) ("
                << (task.factored() ? std::to_string(task.componentCount()) + " components"
                                    : std::string("explicit"))
                << "), " << stats.expanded << " expanded, " << stats.beliefs
                << " knowledge states; search " << stats.seconds << " s\n";
    }
  }
  return solved ? 0 : 1;
}

VerbRunner setupContingent(CLI::App& command) {
  auto options = std::make_shared<ContingentCliOptions>();
  command.add_option("domain", options->domain, "Contingent PDDL domain file")->required();
  command.add_option("problem", options->problem, "Contingent PDDL problem file")->required();
  command
      .add_option("--search", options->search.mode,
                  "OR search between branch points: gbfs (greedy best-first), astar, bfs, dfs, ids "
                  "(iterative deepening)")
      ->check(CLI::IsMember(symbolic::contingentSearchModes()))
      ->capture_default_str();
  command
      .add_option("--heuristic", options->search.heuristic,
                  "Heuristic, evaluated in every world (maximum); ignored by bfs and dfs")
      ->check(CLI::IsMember(symbolic::heuristicNames()))
      ->capture_default_str();
  command.add_option("--time-limit", options->search.limits.seconds, "Search time limit (s)")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--node-limit", options->search.limits.expansions,
                  "Maximum number of expanded knowledge states")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--max-worlds", options->maxWorlds, "Maximum number of possible initial worlds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--knowledge", options->knowledge,
                  "Knowledge states: auto (factored when exact and there are independent "
                  "unknowns), explicit (sets of worlds) or factored (docs/contingent.md)")
      ->check(CLI::IsMember({"auto", "explicit", "factored"}))
      ->capture_default_str();
  command.add_flag("--toy-geometry", options->toyGeometry,
                   "Register the toy `reaches` attachment of the Bartender and Bimanual Assembly "
                   "scenarios");
  command.add_option("--plan-out", options->planOut, "Write the plan tree to FILE");
  command.add_flag("--json", options->json, "Print status, plan DAG and statistics as JSON");
  command.add_flag("--quiet", options->quiet, "No summary on stderr");
  return [options] { return runContingent(*options); };
}

const VerbRegistration registration{
    "contingent",
    "Find a branched plan for a contingent (sensing) problem (exit 0 solved, 1 not solved)",
    setupContingent};

}  // namespace
}  // namespace kaboum::cli
