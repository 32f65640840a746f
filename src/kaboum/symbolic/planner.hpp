// The symbolic planning pipeline as one call: parse -> ground -> search, timing each stage and
// collecting the statistics the CLI, tests and benchmarks report.
#pragma once

#include <string>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/symbolic/search.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

struct PlanReport {
  SearchResult search;
  std::vector<std::string> plan;  // "(action args)" per step
  GroundingStatistics grounding;
  std::vector<ModuleStatistics> modules;
  double parseSeconds = 0.0;
  double groundSeconds = 0.0;
  std::vector<std::string> warnings;  // of the domain and problem files (planFiles)
};

// Plans for the PDDL files; attachments come from `procedures` and from libraries the domain
// names. Throws InputError for bad input.
PlanReport planFiles(const std::string& domainPath, const std::string& problemPath,
                     const ProcedureRegistry& procedures, const SearchOptions& options);
// Same for an already parsed domain and problem.
PlanReport plan(const Domain& domain, const Problem& problem, const ProcedureRegistry& procedures,
                const SearchOptions& options);

}  // namespace kaboum::symbolic
