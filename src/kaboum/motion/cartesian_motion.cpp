#include "kaboum/motion/cartesian_motion.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "kaboum/motion/world_checkers.hpp"

namespace kaboum::motion {

namespace {

// The waypoints of a tool line: IK solutions at line parameters s in [0, 1].
class LineFollower {
 public:
  LineFollower(ToolKinematics& tool, const Pose& from, const Pose& to,
               const CartesianOptions& options)
      : tool_(tool),
        from_(from),
        to_(to),
        r0_(from.rotation()),
        r1_(to.rotation()),
        options_(options) {}

  [[nodiscard]] Pose poseAt(double s) const {
    Pose pose = Pose::Identity();
    pose.linear() = r0_.slerp(s, r1_).toRotationMatrix();
    pose.translation() = from_.translation() + s * (to_.translation() - from_.translation());
    return pose;
  }

  // Appends the waypoints from the last one (at line parameter `sa`) to `sb`, refining segments
  // whose middle strays from the line; the reason when it cannot.
  std::optional<std::string> extend(Waypoints& path, std::vector<double>& parameters, double sb,
                                    int depth = 0) {
    const double sa = parameters.back();
    const std::vector<double> qa = path.back();
    std::optional<std::vector<double>> qb = tool_.solveNear(poseAt(sb), qa);
    if (!qb) return fmt::format("no IK solution at {:.0f}% of the line", 100 * sb);
    double step = 0;
    std::vector<double> middle(qa.size());
    for (std::size_t i = 0; i < qa.size(); ++i) {
      step = std::max(step, std::abs((*qb)[i] - qa[i]));
      middle[i] = 0.5 * (qa[i] + (*qb)[i]);
    }
    if (step > options_.maxJointStep) {
      return fmt::format(
          "the arm changes configuration at {:.0f}% of the line (a joint step of "
          "{:.1f} deg)",
          100 * sb, step * 180 / std::numbers::pi);
    }
    const double deviation =
        (tool_.tcpPose(middle).translation() - poseAt(0.5 * (sa + sb)).translation()).norm();
    if (deviation > options_.maxDeviation) {
      if (depth == options_.maxRefinements) {
        return fmt::format("the tool strays {:.2f} mm from the line at {:.0f}%", 1000 * deviation,
                           50 * (sa + sb));
      }
      if (auto failure = extend(path, parameters, 0.5 * (sa + sb), depth + 1)) return failure;
      return extend(path, parameters, sb, depth + 1);
    }
    path.push_back(std::move(*qb));
    parameters.push_back(sb);
    return std::nullopt;
  }

 private:
  ToolKinematics& tool_;
  Pose from_, to_;
  Eigen::Quaterniond r0_, r1_;
  const CartesianOptions& options_;
};

}  // namespace

MotionResult planCartesian(const MotionGroup& group, ToolKinematics& tool,
                           std::span<const double> start, const Pose& target,
                           const MotionOptions& options, const CartesianOptions& cartesian) {
  MotionQuery query;
  if (group.robots().size() != 1 || group.robots().front() != tool.robot()) {
    throw std::invalid_argument("a Cartesian motion moves the tool's robot alone");
  }
  if (start.size() != group.dimension()) {
    throw std::invalid_argument("the start needs " + std::to_string(group.dimension()) +
                                " joint values");
  }
  MotionResult& result = query.result;
  MotionStatistics& statistics = result.statistics;
  if (const auto problem = configurationProblem(group, start, 0.0)) {
    return query.finish(PlannerStatus::InvalidStart, "start: " + *problem);
  }
  const Pose from = tool.tcpPose(start);
  const double length = (target.translation() - from.translation()).norm();
  const double angle =
      Eigen::Quaterniond(from.rotation()).angularDistance(Eigen::Quaterniond(target.rotation()));
  const int steps = std::max({1, static_cast<int>(std::ceil(length / cartesian.linearStep)),
                              static_cast<int>(std::ceil(angle / cartesian.angularStep))});
  LineFollower line(tool, from, target, cartesian);
  result.path = {{start.begin(), start.end()}};
  std::vector<double> parameters{0.0};
  for (int i = 1; i <= steps; ++i) {
    if (auto failure = line.extend(result.path, parameters, static_cast<double>(i) / steps)) {
      return query.finish(PlannerStatus::InvalidGoal, *failure);
    }
  }
  const QueryEpsilon ends = sweepEpsilonForEnds(group, start, result.path.back(), options);
  if (ends.status != PlannerStatus::Solved) return query.finish(ends.status, ends.problem);
  statistics.sweepEpsilon = ends.epsilon;
  WorldStateChecker states(group, ends.epsilon, &statistics.checks);
  const std::unique_ptr<MotionValidator> motions =
      motionValidator(group, ends.epsilon, &statistics.checks);
  for (std::size_t i = 1; i < result.path.size(); ++i) {
    if (const auto collision = states.firstCollision(result.path[i])) {
      return query.finish(PlannerStatus::Unsolvable,
                          fmt::format("at {:.0f}% of the line: {}", 100 * parameters[i],
                                      group.world().describe(*collision)));
    }
    if (!motions->isValid(result.path[i - 1], result.path[i])) {
      return query.finish(PlannerStatus::Unsolvable,
                          fmt::format("the motion between {:.0f}% and {:.0f}% of the line collides",
                                      100 * parameters[i - 1], 100 * parameters[i]));
    }
  }
  statistics.plannedWaypoints = result.path.size();
  statistics.plannedLength = statistics.length = pathLength(result.path);
  return query.finish(PlannerStatus::Solved);
}

}  // namespace kaboum::motion
