// The plan file (JSON; docs/plan-format.md) of the integrated planner: the plan tree, branching on
// sensing, with the geometry of every action — certified paths per robot, grasps and releases —
// the scene's initial geometric state, the statistics of thesis Table 6.7 and the verification.
// What the executor, the viewer and the Python API read.
#pragma once

#include <nlohmann/json.hpp>

#include "kaboum/tamp/solver.hpp"

namespace kaboum::tamp {

// Names the files the plan was solved from (as given).
struct PlanSources {
  std::string domain;
  std::string problem;
  std::string scene;
};

// The plan file of `result`, solved by `solver`.
nlohmann::json planFileJson(Solver& solver, const SolveResult& result, const PlanSources& sources);

// The statistics of `result` (Table 6.7's rows): times, search, attachment calls, geometry; and
// how `world` answered the collision queries (its ε, bounded or exact predicates).
nlohmann::json statisticsJson(const World& world, const SolveResult& result);

}  // namespace kaboum::tamp
