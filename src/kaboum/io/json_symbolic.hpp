// JSON of symbolic planning results: planner status, search and grounding statistics, plans and
// their validation, and the branched plans of contingent planning with their statistics. Times
// are in seconds.
#pragma once

#include <nlohmann/json.hpp>

#include "kaboum/core/planner_status.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/symbolic/planner.hpp"
#include "kaboum/symbolic/validator.hpp"

namespace kaboum::io {

using namespace kaboum::symbolic;

// The status as a string: "solved", "unsolvable", "time-limit", "memory-limit", "node-limit",
// "cancelled".
nlohmann::json toJson(PlannerStatus status);

// expanded, generated, evaluated, reopened, dead_ends, stored_states, memory_bytes, iterations
// (the search time is the PlanReport's time.search).
nlohmann::json toJson(const SearchStatistics& statistics);

// atoms (reachable), operators, fixpoint_passes.
nlohmann::json toJson(const GroundingStatistics& statistics);

// module, calls, cache_hits, seconds.
nlohmann::json toJson(const ModuleStatistics& statistics);

// status, plan_length (null unless solved), plan ["(action args)", ...], the search statistics,
// grounding, time {parse, ground, search, total}, attachments [module statistics].
nlohmann::json toJson(const PlanReport& report);

// valid, failed_step (1-based; 0 when every step applied), message.
nlohmann::json toJson(const ValidationResult& result);

// The plan DAG: root (null when there is no plan), nodes [{id, kind "goal"}, {id, kind "action",
// action, next}, {id, kind "branch", atom, on_true, on_false}], the nodes reachable from the root.
nlohmann::json toJson(const KnowledgeTask& task, const PlanTree& plan);

// actions, branches, leaves, depth, dag_nodes.
nlohmann::json toJson(const TreeMetrics& metrics);

// expanded, generated, evaluated, dead_ends, reused, knowledge_states, worlds, seconds.
nlohmann::json toJson(const ContingentStatistics& statistics);

// status, plan (the DAG), tree (its metrics), initial_worlds, operators, and the statistics.
nlohmann::json toJson(const KnowledgeTask& task, const ContingentResult& result);

// valid, message, actions, leaves, depth.
nlohmann::json toJson(const TreeValidation& validation);

// reached_goal, steps ["(action args)" or "branch (p) -> true|false", ...], message.
nlohmann::json toJson(const Execution& execution);

}  // namespace kaboum::io
