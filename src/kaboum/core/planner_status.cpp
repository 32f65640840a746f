#include "kaboum/core/planner_status.hpp"

namespace kaboum {

std::string toString(PlannerStatus status) {
  switch (status) {
    case PlannerStatus::Solved:
      return "solved";
    case PlannerStatus::Unsolvable:
      return "unsolvable";
    case PlannerStatus::TimeLimit:
      return "time-limit";
    case PlannerStatus::MemoryLimit:
      return "memory-limit";
    case PlannerStatus::NodeLimit:
      return "node-limit";
    case PlannerStatus::Cancelled:
      return "cancelled";
    case PlannerStatus::InvalidStart:
      return "invalid-start";
    case PlannerStatus::InvalidGoal:
      return "invalid-goal";
  }
  return "unknown";
}

}  // namespace kaboum
