#include "kaboum/motion/world_checkers.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace kaboum::motion {

namespace {

// Adds the seconds and the count of one check to `statistics` (when given) on destruction.
class CheckTimer {
 public:
  CheckTimer(CheckStatistics* statistics, std::size_t CheckStatistics::*count,
             std::size_t CheckStatistics::*positives, double CheckStatistics::*seconds)
      : statistics_(statistics), count_(count), positives_(positives), seconds_(seconds) {
    if (statistics_ != nullptr) start_ = std::chrono::steady_clock::now();
  }
  CheckTimer(const CheckTimer&) = delete;
  CheckTimer& operator=(const CheckTimer&) = delete;
  // The check's verdict: whether it found a collision. Returns `valid`.
  bool verdict(bool valid) {
    positive_ = !valid;
    return valid;
  }
  ~CheckTimer() {
    if (statistics_ == nullptr) return;
    ++(statistics_->*count_);
    if (positive_) ++(statistics_->*positives_);
    statistics_->*seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  CheckStatistics* statistics_;
  std::size_t CheckStatistics::*count_;
  std::size_t CheckStatistics::*positives_;
  bool positive_ = false;
  double CheckStatistics::*seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

WorldStateChecker::WorldStateChecker(const MotionGroup& group, double clearance,
                                     CheckStatistics* statistics)
    : group_(group),
      clearance_(clearance),
      statistics_(statistics),
      state_(group.context()),
      scratch_(group.world().scratch()) {
  group_.world().computeLinkPoses(state_, scratch_);
  const std::size_t robots = group.world().robots().size();
  const std::vector<std::size_t>& moving = group.robots();
  for (std::size_t k = 0; k < moving.size(); ++k) {
    // Against every fixed robot and the moving robots after this one.
    std::vector<std::uint8_t> against(robots, 1);
    for (std::size_t before = 0; before <= k; ++before) against[moving[before]] = 0;
    against_.push_back(std::move(against));
  }
}

bool WorldStateChecker::isValid(std::span<const double> q) {
  return !firstCollision(q);
}

std::optional<Collision> WorldStateChecker::firstCollision(std::span<const double> q) {
  CheckTimer timer(statistics_, &CheckStatistics::stateChecks, &CheckStatistics::statePositives,
                   &CheckStatistics::stateSeconds);
  const World& world = group_.world();
  group_.assign(q, state_);
  for (const std::size_t r : group_.robots()) {
    world.robots()[r].collision.model().linkPoses(state_.robots[r].configuration,
                                                  scratch_.linkPoses[r]);
  }
  for (std::size_t k = 0; k < group_.robots().size(); ++k) {
    if (auto collision = world.firstCollisionOfRobot(state_, scratch_, group_.robots()[k],
                                                     against_[k], clearance_)) {
      timer.verdict(false);
      return collision;
    }
  }
  return std::nullopt;
}

SweptMotionValidator::SweptMotionValidator(const MotionGroup& group, double sweepEpsilon,
                                           CheckStatistics* statistics)
    : group_(group),
      epsilon_(sweepEpsilon),
      statistics_(statistics),
      samples_(group, 0.0),
      sample_(group.dimension()) {
  const World& world = group.world();
  movingIndex_.assign(world.robots().size(), -1);
  for (std::size_t k = 0; k < group.robots().size(); ++k) {
    movingIndex_[group.robots()[k]] = static_cast<int>(k);
  }
  for (const WorldRobot& robot : world.robots()) {
    sweeps_.push_back(std::make_unique<RobotSweep>(robot.collision));
  }
}

bool SweptMotionValidator::isValid(std::span<const double> from, std::span<const double> to) {
  CheckTimer timer(statistics_, &CheckStatistics::motionChecks, &CheckStatistics::motionPositives,
                   &CheckStatistics::motionSeconds);
  return timer.verdict(certify(from, to));
}

bool SweptMotionValidator::certify(std::span<const double> from, std::span<const double> to) {
  // One direction for both (lexicographically smaller end first), so that the verdict on a
  // segment does not depend on the direction a planner checks it in.
  if (std::lexicographical_compare(to.begin(), to.end(), from.begin(), from.end())) {
    std::swap(from, to);
  }
  // Colliding samples reject most colliding motions for a fraction of a sweep's cost; a collision
  // at a sample is one the swept volume contains, so this never rejects a certifiable motion.
  for (const double t : kPrefilterSamples) {
    for (std::size_t i = 0; i < sample_.size(); ++i) sample_[i] = from[i] + t * (to[i] - from[i]);
    if (!samples_.isValid(sample_)) return false;
  }
  const World& world = group_.world();
  const GeometricState& context = group_.context();
  const std::vector<std::size_t>& moving = group_.robots();
  // Scene objects first (the most common obstacle), then self-collision, then other robots.
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t r = moving[k];
    if (sweeps_[r]->firstSceneCollision(group_.robotPart(from, k), group_.robotPart(to, k),
                                        context.robots[r].held, world.scene(), context.placements,
                                        0.0, epsilon_)) {
      return false;
    }
  }
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t r = moving[k];
    if (sweeps_[r]->selfCollides(group_.robotPart(from, k), group_.robotPart(to, k),
                                 context.robots[r].held, 0.0, epsilon_)) {
      return false;
    }
  }
  // Each moving robot against every fixed robot and the moving robots after it.
  const auto motionOf = [&](std::size_t r, std::span<const double> q) {
    const int k = movingIndex_[r];
    return k < 0 ? std::span<const double>(context.robots[r].configuration)
                 : group_.robotPart(q, static_cast<std::size_t>(k));
  };
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const std::size_t a = moving[k];
    for (std::size_t b = 0; b < world.robots().size(); ++b) {
      if (b == a || (movingIndex_[b] >= 0 && movingIndex_[b] <= static_cast<int>(k))) continue;
      if (sweptVolumesCollide(*sweeps_[a], motionOf(a, from), motionOf(a, to),
                              context.robots[a].held, *sweeps_[b], motionOf(b, from),
                              motionOf(b, to), context.robots[b].held, 0.0, epsilon_)) {
        return false;
      }
    }
  }
  return true;
}

DiscreteMotionValidator::DiscreteMotionValidator(const MotionGroup& group, double jointStep,
                                                 double prismaticStep, CheckStatistics* statistics)
    : statistics_(statistics), samples_(group, 0.0), sample_(group.dimension()) {
  if (!(jointStep > 0) || !(prismaticStep > 0)) {
    throw std::invalid_argument("the steps of a discrete motion check must be positive");
  }
  for (std::size_t i = 0; i < group.dimension(); ++i) {
    const MotionGroup::Coordinate coordinate = group.coordinate(i);
    const Joint& joint = group.world().robots()[coordinate.robot].collision.model().variableJoint(
        coordinate.variable);
    steps_.push_back(joint.type == JointType::Prismatic ? prismaticStep : jointStep);
  }
}

bool DiscreteMotionValidator::isValid(std::span<const double> from, std::span<const double> to) {
  CheckTimer timer(statistics_, &CheckStatistics::motionChecks, &CheckStatistics::motionPositives,
                   &CheckStatistics::motionSeconds);
  // The same samples in either direction (lexicographically smaller end first).
  if (std::lexicographical_compare(to.begin(), to.end(), from.begin(), from.end())) {
    std::swap(from, to);
  }
  double intervals = 1;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    intervals = std::max(intervals, std::ceil(std::abs(to[i] - from[i]) / steps_[i]));
  }
  const auto count = static_cast<std::size_t>(intervals);
  for (std::size_t k = 1; k < count; ++k) {
    const double t = static_cast<double>(k) / intervals;
    for (std::size_t i = 0; i < sample_.size(); ++i) sample_[i] = from[i] + t * (to[i] - from[i]);
    if (!samples_.isValid(sample_)) return timer.verdict(false);
  }
  return timer.verdict(true);
}

}  // namespace kaboum::motion
