#include "kaboum/exec/schedule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "kaboum/core/error.hpp"

namespace kaboum::exec {

using tamp::GeometricStep;

std::vector<JointLimits> jointLimits(const world::World& world, const TrajectoryOptions& options) {
  std::vector<JointLimits> limits;
  for (const world::RobotSpec& robot : world.description().robots) {
    JointLimits& joints = limits.emplace_back();
    for (const world::JointSpec& joint : robot.joints) {
      joints.velocity.push_back(joint.maxVelocity.value_or(options.defaultVelocity));
      joints.acceleration.push_back(joint.maxAcceleration.value_or(options.defaultAcceleration));
    }
  }
  return limits;
}

Schedule::Schedule(std::vector<std::vector<double>> initial, std::vector<JointLimits> limits,
                   Profile profile)
    : initial_(std::move(initial)),
      limits_(std::move(limits)),
      profile_(profile),
      robotMotions_(initial_.size()) {
  if (limits_.size() != initial_.size()) {
    throw std::invalid_argument("joint limits for another number of robots");
  }
}

void Schedule::append(std::size_t node, const std::string& name,
                      const std::vector<tamp::ActionGeometry>& geometry) {
  TimedAction action{node, name, duration_, duration_};
  std::size_t index = 0;
  for (const tamp::ActionGeometry& effect : geometry) {
    for (const GeometricStep& step : effect.steps) {
      if (step.robot >= initial_.size()) throw std::invalid_argument("no such robot");
      if (step.kind == GeometricStep::Kind::Join) {
        // Not a gripper event: the parts are joined where the insertion put them.
      } else if (step.path.empty()) {
        events_.push_back(
            {node, action.end, step.kind, step.robot, step.tool, step.object, step.pose});
      } else {
        if (step.path.front().size() != initial_[step.robot].size()) {
          throw std::invalid_argument("a path of another robot's size");
        }
        TimedPath path(step.path, limits_[step.robot], profile_);
        const double length = path.duration();
        robotMotions_[step.robot].push_back(motions_.size());
        motions_.push_back({node, index, step.kind, step.robot, action.end, std::move(path)});
        action.end += length;
      }
      ++index;
    }
  }
  duration_ = action.end;
  actions_.push_back(std::move(action));
}

void Schedule::sample(double t, std::size_t robot, std::span<double> q, std::span<double> qd,
                      std::span<double> qdd) const {
  const std::vector<std::size_t>& own = robotMotions_[robot];
  // The robot's last motion starting at or before t.
  const auto after = std::upper_bound(own.begin(), own.end(), t, [&](double time, std::size_t m) {
    return time < motions_[m].start;
  });
  if (after == own.begin()) {
    std::copy(initial_[robot].begin(), initial_[robot].end(), q.begin());
    std::fill(qd.begin(), qd.end(), 0.0);
    std::fill(qdd.begin(), qdd.end(), 0.0);
    return;
  }
  const TimedMotion& motion = motions_[*(after - 1)];
  motion.path.sample(t - motion.start, q, qd, qdd);
  if (t - motion.start >= motion.path.duration()) {
    std::fill(qd.begin(), qd.end(), 0.0);
    std::fill(qdd.begin(), qdd.end(), 0.0);
  }
}

std::vector<double> sampleTimes(double duration, double rate) {
  if (!(rate > 0) || !std::isfinite(rate)) throw std::invalid_argument("rate must be positive");
  const auto ticks = static_cast<std::size_t>(std::floor(duration * rate));
  std::vector<double> times;
  times.reserve(ticks + 2);
  for (std::size_t k = 0; k <= ticks; ++k) times.push_back(static_cast<double>(k) / rate);
  if (times.back() < duration) times.push_back(duration);
  return times;
}

RobotSamples sampleRobot(const Schedule& schedule, std::size_t robot, double rate) {
  RobotSamples out;
  out.robot = robot;
  out.dof = schedule.dof(robot);
  out.times = sampleTimes(schedule.duration(), rate);
  const std::size_t values = out.times.size() * out.dof;
  out.positions.resize(values);
  out.velocities.resize(values);
  out.accelerations.resize(values);
  for (std::size_t k = 0; k < out.times.size(); ++k) {
    const std::size_t at = k * out.dof;
    schedule.sample(out.times[k], robot, std::span(out.positions).subspan(at, out.dof),
                    std::span(out.velocities).subspan(at, out.dof),
                    std::span(out.accelerations).subspan(at, out.dof));
  }
  return out;
}

std::string actionName(const symbolic::KnowledgeTask& task, const symbolic::PlanTree::Node& node) {
  return "(" + task.task().operators[static_cast<std::size_t>(node.op)].name + ")";
}

std::vector<BranchTiming> branchTimings(const tamp::PlanFileContents& plan,
                                        const symbolic::KnowledgeTask& task,
                                        const std::vector<JointLimits>& limits, Profile profile) {
  using Node = symbolic::PlanTree::Node;
  // Each action's duration once: the sum of its motions' (gripper events take no time).
  std::map<std::size_t, double> seconds;
  const auto actionSeconds = [&](std::size_t n) {
    const auto [found, inserted] = seconds.emplace(n, 0.0);
    if (inserted) {
      for (const tamp::ActionGeometry& effect : plan.geometry[n]) {
        for (const GeometricStep& step : effect.steps) {
          if (!step.path.empty()) {
            found->second += TimedPath(step.path, limits[step.robot], profile).duration();
          }
        }
      }
    }
    return found->second;
  };
  std::vector<BranchTiming> out;
  // Depth first, true before false; each entry a node and the way to it.
  std::vector<std::pair<int, BranchTiming>> open{{plan.plan.root, {}}};
  while (!open.empty()) {
    auto [n, way] = std::move(open.back());
    open.pop_back();
    if (n < 0) continue;
    if (way.actions.size() + way.outcomes.size() > plan.plan.nodes.size()) {
      throw InputError(fmt::format("nodes[{}]: the plan does not reach a goal node (a cycle)", n));
    }
    const Node& node = plan.plan.nodes[static_cast<std::size_t>(n)];
    if (node.kind == Node::Kind::Goal) {
      out.push_back(std::move(way));
    } else if (node.kind == Node::Kind::Branch) {
      const std::string test = symbolic::branchTest(task, node);
      BranchTiming onFalse = way;
      onFalse.outcomes.push_back(test + " false");
      way.outcomes.push_back(test + " true");
      open.emplace_back(node.onFalse, std::move(onFalse));
      open.emplace_back(node.next, std::move(way));
    } else {
      way.actions.push_back(actionName(task, node));
      way.seconds += actionSeconds(static_cast<std::size_t>(n));
      open.emplace_back(node.next, std::move(way));
    }
  }
  return out;
}

}  // namespace kaboum::exec
