// Forward state-space search over a ground task (thesis §3.2 and §6.2, Tables 6.2/6.4/6.7): the
// thesis's depth-first, breadth-first and iterative-deepening searches, plus greedy best-first
// (with preferred operators, eager or lazy evaluation) and A*. Duplicate states are detected by
// hashing packed states. Every run reports statistics and stops cleanly at its limits.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "kaboum/core/deadline.hpp"
#include "kaboum/core/planner_status.hpp"
#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

struct SearchOptions {
  std::string mode = "gbfs";     // one of searchModes()
  std::string heuristic = "ff";  // one of heuristicNames(); ignored by dfs, bfs, ids
  bool preferredOperators = true;
  bool lazy = true;  // gbfs: evaluate states when expanded, not when generated
  // gbfs: alternate open lists for `heuristic` and the landmark-count heuristic (LAMA-style)
  bool landmarks = true;
  PlannerLimits limits;
};

struct SearchStatistics {
  std::size_t expanded = 0;
  std::size_t generated = 0;
  std::size_t evaluated = 0;  // heuristic evaluations
  std::size_t reopened = 0;
  std::size_t deadEnds = 0;
  std::size_t storedStates = 0;
  std::size_t memoryBytes = 0;  // states, search nodes and open lists at the end
  std::size_t iterations = 0;   // ids: depth bounds tried
  double seconds = 0.0;
};

struct SearchResult {
  PlannerStatus status = PlannerStatus::Unsolvable;
  std::vector<int> plan;  // operator indices
  SearchStatistics statistics;
};

// Names accepted by SearchOptions::mode: "dfs", "bfs", "ids", "gbfs", "astar".
const std::vector<std::string>& searchModes();

// Throws InputError for an unknown mode or heuristic.
SearchResult search(const GroundTask& task, AttachmentRuntime& attachments,
                    const SearchOptions& options);

// Renders a plan in IPC format, one "(action args)" per line.
std::string formatPlan(const GroundTask& task, const std::vector<int>& plan);

}  // namespace kaboum::symbolic
