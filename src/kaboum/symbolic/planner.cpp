#include "kaboum/symbolic/planner.hpp"

#include <chrono>

namespace kaboum::symbolic {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

PlanReport plan(const Domain& domain, const Problem& problem, const ProcedureRegistry& procedures,
                const SearchOptions& options) {
  PlanReport report;
  const auto groundStart = std::chrono::steady_clock::now();
  AttachmentRuntime attachments(domain, problem, procedures);
  const GroundTask task = ground(domain, problem);
  report.groundSeconds = secondsSince(groundStart);
  report.grounding = task.statistics;
  report.search = search(task, attachments, options);
  for (const int op : report.search.plan)
    report.plan.push_back("(" + task.operators[op].name + ")");
  report.modules = attachments.statistics();
  return report;
}

PlanReport planFiles(const std::string& domainPath, const std::string& problemPath,
                     const ProcedureRegistry& procedures, const SearchOptions& options) {
  const auto parseStart = std::chrono::steady_clock::now();
  const Domain domain = loadDomain(domainPath);
  const Problem problem = loadProblem(problemPath, domain);
  const double parseSeconds = secondsSince(parseStart);
  PlanReport report = plan(domain, problem, procedures, options);
  report.parseSeconds = parseSeconds;
  report.warnings = domain.warnings;
  report.warnings.insert(report.warnings.end(), problem.warnings.begin(), problem.warnings.end());
  return report;
}

}  // namespace kaboum::symbolic
