#include "kaboum/motion/motion_group.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace kaboum::motion {

MotionGroup::MotionGroup(const World& world, GeometricState context,
                         std::vector<std::size_t> robots)
    : world_(&world), context_(std::move(context)), robots_(std::move(robots)) {
  if (robots_.empty()) throw std::invalid_argument("a motion group needs at least one robot");
  if (context_.robots.size() != world.robots().size()) {
    throw std::invalid_argument("motion context of " + std::to_string(context_.robots.size()) +
                                " robots for a world of " + std::to_string(world.robots().size()));
  }
  offsets_.push_back(0);
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    const std::size_t r = robots_[k];
    if (r >= world.robots().size()) {
      throw std::invalid_argument("no robot " + std::to_string(r) + " in the world");
    }
    if (std::count(robots_.begin(), robots_.end(), r) > 1) {
      throw std::invalid_argument("robot '" + world.robots()[r].name + "' moves twice");
    }
    const RobotModel& model = world.robots()[r].collision.model();
    if (context_.robots[r].configuration.size() != static_cast<std::size_t>(model.dof())) {
      throw std::invalid_argument("motion context of robot '" + world.robots()[r].name +
                                  "' has the wrong size");
    }
    for (int v = 0; v < model.dof(); ++v) {
      lower_.push_back(model.variableJoint(v).lower);
      upper_.push_back(model.variableJoint(v).upper);
    }
    offsets_.push_back(lower_.size());
  }
}

void MotionGroup::holdStill(std::size_t k, int variable) {
  const std::size_t robot = robots_.at(k);
  const std::vector<double>& q = context_.robots[robot].configuration;
  const std::size_t i = offsets_[k] + static_cast<std::size_t>(variable);
  if (variable < 0 || i >= offsets_[k + 1]) {
    throw std::out_of_range("robot '" + world_->robots()[robot].name + "' has no variable " +
                            std::to_string(variable));
  }
  lower_[i] = upper_[i] = q[static_cast<std::size_t>(variable)];
}

std::vector<double> MotionGroup::configuration(const GeometricState& state) const {
  std::vector<double> q;
  q.reserve(dimension());
  for (const std::size_t r : robots_) {
    const std::vector<double>& part = state.robots.at(r).configuration;
    q.insert(q.end(), part.begin(), part.end());
  }
  return q;
}

void MotionGroup::assign(std::span<const double> q, GeometricState& state) const {
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    const std::span<const double> part = robotPart(q, k);
    std::copy(part.begin(), part.end(), state.robots[robots_[k]].configuration.begin());
  }
}

std::size_t MotionGroup::firstOutsideLimits(std::span<const double> q, double tolerance) const {
  for (std::size_t i = 0; i < dimension(); ++i) {
    if (!(q[i] >= lower_[i] - tolerance && q[i] <= upper_[i] + tolerance)) return i;
  }
  return dimension();
}

MotionGroup::Coordinate MotionGroup::coordinate(std::size_t i) const {
  const std::size_t k = static_cast<std::size_t>(
      std::upper_bound(offsets_.begin(), offsets_.end(), i) - offsets_.begin() - 1);
  return {robots_[k], static_cast<int>(i - offsets_[k])};
}

std::string MotionGroup::coordinateName(std::size_t i) const {
  const auto [r, variable] = coordinate(i);
  const WorldRobot& robot = world_->robots()[r];
  return robot.collision.model().variableJoint(variable).name + " of robot '" + robot.name + "'";
}

}  // namespace kaboum::motion
