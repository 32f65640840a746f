// `kaboum plan DOMAIN PROBLEM`: classical planning with semantic attachments (symbolic core).
#include <fstream>
#include <iostream>
#include <memory>

#include "kaboum/core/error.hpp"
#include "kaboum/core/planner_status.hpp"
#include "kaboum/io/json_symbolic.hpp"
#include "kaboum/symbolic/heuristic.hpp"
#include "kaboum/symbolic/planner.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::symbolic;

namespace {

struct PlanOptions {
  std::string domain;
  std::string problem;
  std::string planOut;
  double memoryLimitMb = 0.0;
  bool json = false;
  bool quiet = false;
  bool noPreferred = false;
  symbolic::SearchOptions search;
};

int runPlan(const PlanOptions& options) {
  symbolic::SearchOptions search = options.search;
  search.preferredOperators = !options.noPreferred;
  if (options.memoryLimitMb > 0) {
    search.limits.memoryBytes = static_cast<std::size_t>(options.memoryLimitMb * 1024 * 1024);
  }
  const symbolic::PlanReport report =
      symbolic::planFiles(options.domain, options.problem, symbolic::ProcedureRegistry{}, search);
  printWarnings(report.warnings);
  const bool solved = report.search.status == PlannerStatus::Solved;
  if (solved && !options.planOut.empty()) {
    std::ofstream out(options.planOut);
    if (!out) throw InputError(locate(options.planOut, "cannot write plan file"));
    for (const std::string& step : report.plan) out << step << "\n";
    out << "; cost = " << report.plan.size() << " (unit cost)\n";
  }
  if (options.json) {
    std::cout << io::toJson(report).dump(2) << "\n";
  } else {
    if (solved && options.planOut.empty()) {
      for (const std::string& step : report.plan) std::cout << step << "\n";
    }
    if (!options.quiet) {
      const auto& stats = report.search.statistics;
      std::cerr << "kaboum plan: " << toString(report.search.status);
      if (solved) std::cerr << ", " << report.plan.size() << " step(s)";
      std::cerr << "; " << stats.expanded << " expanded, " << stats.generated << " generated; "
                << report.grounding.operators << " operators; parse " << report.parseSeconds
                << " s, ground " << report.groundSeconds << " s, search " << stats.seconds
                << " s\n";
      for (const auto& module : report.modules) {
        std::cerr << "  module " << module.name << ": " << module.calls << " calls, "
                  << module.cacheHits << " cache hits, " << module.seconds << " s\n";
      }
    }
  }
  return solved ? 0 : 1;
}

VerbRunner setupPlan(CLI::App& command) {
  auto options = std::make_shared<PlanOptions>();
  command.add_option("domain", options->domain, "PDDL domain file")->required();
  command.add_option("problem", options->problem, "PDDL problem file")->required();
  command.add_option("--search", options->search.mode, "Search mode")
      ->check(CLI::IsMember(symbolic::searchModes()))
      ->capture_default_str();
  command.add_option("--heuristic", options->search.heuristic, "Heuristic for gbfs and astar")
      ->check(CLI::IsMember(symbolic::heuristicNames()))
      ->capture_default_str();
  command.add_flag("--lazy,!--eager", options->search.lazy,
                   "gbfs: evaluate states when expanded (default) or when generated (--eager)");
  command.add_flag("--landmarks,!--no-landmarks", options->search.landmarks,
                   "gbfs: alternate with the landmark-count heuristic, LAMA-style (default)");
  command.add_flag("--no-preferred", options->noPreferred, "gbfs: ignore preferred operators");
  command.add_option("--time-limit", options->search.limits.seconds, "Search time limit (s)")
      ->check(CLI::PositiveNumber);
  command.add_option("--memory-limit", options->memoryLimitMb, "Search memory limit (MiB)")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--node-limit", options->search.limits.expansions,
                  "Maximum number of expanded states")
      ->check(CLI::PositiveNumber);
  command.add_option("--plan-out", options->planOut, "Write the plan (IPC format) to FILE");
  command.add_flag("--json", options->json, "Print statistics and plan as JSON");
  command.add_flag("--quiet", options->quiet, "No summary on stderr");
  return [options] { return runPlan(*options); };
}

const VerbRegistration registration{
    "plan", "Find a plan for a PDDL domain and problem (exit 0 solved, 1 not solved)", setupPlan};

}  // namespace
}  // namespace kaboum::cli
