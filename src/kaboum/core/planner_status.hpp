// How a planner run ended (thesis §3.2 and §6.2: every search stops with a status, never a crash),
// one vocabulary for the symbolic, contingent, motion and integrated planners and the executor, in
// the spirit of OMPL's PlannerStatus.
#pragma once

#include <string>

namespace kaboum {

enum class PlannerStatus {
  Solved,        // a plan was found
  Unsolvable,    // the search space is exhausted: no plan exists
  TimeLimit,     // the wall-clock time limit was reached
  MemoryLimit,   // the memory limit was reached, or an allocation failed
  NodeLimit,     // the expansion limit was reached
  Cancelled,     // the cancel flag was set
  InvalidStart,  // the start state is in collision or outside the joint limits (motion planning)
  InvalidGoal,   // the goal is in collision, outside the limits or has no IK solution
};

// The status as the CLI prints it and writes it in JSON: "solved", "unsolvable", "time-limit",
// "memory-limit", "node-limit", "cancelled",
// "invalid-start", "invalid-goal".
std::string toString(PlannerStatus status);

}  // namespace kaboum
