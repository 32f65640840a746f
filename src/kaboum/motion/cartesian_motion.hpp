// Straight tool motions (thesis §6.1.2: approach and retreat along the gripper axis, insertion
// in assembly): the tool centre point moves on the line between two poses (orientation by slerp)
// by IK along the line, with a bounded deviation, and every segment certified by swept volumes.
#pragma once

#include <numbers>
#include <span>

#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/motion/tool_kinematics.hpp"

namespace kaboum::motion {

struct CartesianOptions {
  double linearStep = 0.005;                        // metres of tool motion between IK waypoints
  double angularStep = 2 * std::numbers::pi / 180;  // radians of tool rotation between them
  double maxDeviation = 0.001;  // metres: TCP off the line at the middle of a joint-space segment
  double maxJointStep = 10 * std::numbers::pi / 180;  // radians: larger means a configuration flip
  int maxRefinements = 6;  // bisections of a segment that deviates too far
};

// Moves the tool of `group` (whose one robot is tool.robot()) from its pose at `start` to
// `target` (TCP in the world frame). Solved: the waypoints, each within limits and every segment
// certified at sweepEpsilonForEnds of the line's ends. InvalidStart: the start is outside the
// limits or collides. InvalidGoal: no IK along the line, a configuration flip (a joint step above
// maxJointStep) or a deviation that refinement does not bring under maxDeviation, naming where
// along the line. Unsolvable: the line collides, naming what.
MotionResult planCartesian(const MotionGroup& group, ToolKinematics& tool,
                           std::span<const double> start, const Pose& target,
                           const MotionOptions& options = {},
                           const CartesianOptions& cartesian = {});

}  // namespace kaboum::motion
