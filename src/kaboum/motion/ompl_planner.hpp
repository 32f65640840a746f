// The sampling-based stage of planMotion: one of OMPL's geometric planners on the motion group's
// joint space (bounded by the joint limits), with kaboum's state checker as OMPL's state validity
// checker and the swept-volume validator as OMPL's motion validator, sampling from a generator
// seeded by the query's seed so that the same seed gives the same path.
#pragma once

#include <span>

#include "kaboum/motion/motion_planner.hpp"

namespace kaboum::motion {

struct SamplingResult {
  PlannerStatus status = PlannerStatus::TimeLimit;
  Waypoints path;  // start ... goal when solved
};

// Plans within `seconds`. Throws std::invalid_argument for an unknown planner name.
SamplingResult planWithOmpl(const MotionGroup& group, StateValidityChecker& states,
                            MotionValidator& motions, std::span<const double> start,
                            std::span<const double> goal, const MotionOptions& options,
                            double seconds);

}  // namespace kaboum::motion
