#include "kaboum/tamp/state_map.hpp"

#include <cmath>
#include <stdexcept>

namespace kaboum::tamp {

std::size_t StateKeyHash::operator()(const StateKey& key) const noexcept {
  std::size_t seed = key.size();
  for (const std::int64_t value : key) {
    seed ^= static_cast<std::size_t>(value) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
  }
  return seed;
}

GeometricStateMap::GeometricStateMap(double tolerance) : tolerance_(tolerance) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) {
    throw std::invalid_argument("the tolerance of the symbolic-geometric map must be positive");
  }
}

void GeometricStateMap::appendRounded(double value, StateKey& key) const {
  key.push_back(std::llround(value / tolerance_));
}

void GeometricStateMap::appendPose(const Pose& pose, StateKey& key) const {
  const auto& matrix = pose.matrix();
  for (Eigen::Index row = 0; row < 3; ++row) {
    for (Eigen::Index column = 0; column < 4; ++column) appendRounded(matrix(row, column), key);
  }
}

// Robots (configuration, then each held object's id, link and grasp), then placements, then the
// joined pairs: a held object's count separates one robot's values from the next robot's.
void GeometricStateMap::keyOf(const GeometricState& state, StateKey& key) const {
  key.clear();
  for (const RobotState& robot : state.robots) {
    for (const double q : robot.configuration) appendRounded(q, key);
    key.push_back(static_cast<std::int64_t>(robot.heldObjects.size()));
    for (std::size_t i = 0; i < robot.heldObjects.size(); ++i) {
      key.push_back(static_cast<std::int64_t>(robot.heldObjects[i]));
      key.push_back(robot.held[i].link);
      appendPose(robot.held[i].inLink, key);
    }
  }
  for (const Placement& placement : state.placements) {
    key.push_back(placement.present ? 1 : 0);
    if (placement.present) appendPose(placement.pose, key);
  }
  for (const auto& [a, b] : state.joined) {
    key.push_back(static_cast<std::int64_t>(a));
    key.push_back(static_cast<std::int64_t>(b));
  }
}

std::size_t GeometricStateMap::intern(const GeometricState& state) {
  keyOf(state, key_);
  const auto [it, added] = ids_.try_emplace(key_, states_.size());
  if (added) states_.push_back(state);
  return it->second;
}

std::optional<std::size_t> GeometricStateMap::find(const GeometricState& state) const {
  keyOf(state, key_);
  const auto it = ids_.find(key_);
  if (it == ids_.end()) return std::nullopt;
  return it->second;
}

std::size_t GeometricStateMap::internPose(std::size_t object, const Pose& pose) {
  if (object >= poses_.size()) poses_.resize(object + 1);
  PoseComponent& component = poses_[object];
  key_.clear();
  appendPose(pose, key_);
  const auto [it, added] = component.ids.try_emplace(key_, component.poses.size());
  if (added) component.poses.push_back(pose);
  return it->second;
}

const Pose& GeometricStateMap::pose(std::size_t object, std::size_t id) const {
  return poses_.at(object).poses.at(id);
}

}  // namespace kaboum::tamp
