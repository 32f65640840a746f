#include "kaboum/world/geometric_state.hpp"

#include <algorithm>

namespace kaboum::world {

namespace {

bool samePose(const Pose& a, const Pose& b) {
  return a.matrix() == b.matrix();
}

bool sameRobotState(const RobotState& a, const RobotState& b) {
  if (a.configuration != b.configuration || a.heldObjects != b.heldObjects ||
      a.held.size() != b.held.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.held.size(); ++i) {
    if (a.held[i].link != b.held[i].link || !samePose(a.held[i].inLink, b.held[i].inLink)) {
      return false;
    }
  }
  return true;
}

void combine(std::size_t& seed, std::size_t value) {
  seed ^= value + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
}

void combinePose(std::size_t& seed, const Pose& pose) {
  const auto& matrix = pose.matrix();
  for (Eigen::Index row = 0; row < 3; ++row) {
    for (Eigen::Index column = 0; column < 4; ++column) {
      combine(seed, std::hash<double>{}(matrix(row, column)));
    }
  }
}

}  // namespace

void GeometricState::join(std::size_t a, std::size_t b) {
  const std::pair<std::size_t, std::size_t> pair = std::minmax(a, b);
  const auto at = std::lower_bound(joined.begin(), joined.end(), pair);
  if (at == joined.end() || *at != pair) joined.insert(at, pair);
}

bool GeometricState::areJoined(std::size_t a, std::size_t b) const {
  return std::binary_search(joined.begin(), joined.end(),
                            std::pair<std::size_t, std::size_t>(std::minmax(a, b)));
}

bool GeometricState::isJoined(std::size_t object) const {
  return std::any_of(joined.begin(), joined.end(), [&](const auto& pair) {
    return pair.first == object || pair.second == object;
  });
}

bool GeometricState::operator==(const GeometricState& other) const {
  if (robots.size() != other.robots.size() || placements.size() != other.placements.size() ||
      joined != other.joined) {
    return false;
  }
  for (std::size_t r = 0; r < robots.size(); ++r) {
    if (!sameRobotState(robots[r], other.robots[r])) return false;
  }
  for (std::size_t i = 0; i < placements.size(); ++i) {
    if (placements[i].present != other.placements[i].present ||
        !samePose(placements[i].pose, other.placements[i].pose)) {
      return false;
    }
  }
  return true;
}

std::size_t GeometricState::hashValue() const {
  std::size_t seed = robots.size();
  for (const RobotState& robot : robots) {
    for (double q : robot.configuration) combine(seed, std::hash<double>{}(q));
    for (std::size_t i = 0; i < robot.held.size(); ++i) {
      combine(seed, robot.heldObjects[i]);
      combine(seed, static_cast<std::size_t>(robot.held[i].link));
      combinePose(seed, robot.held[i].inLink);
    }
  }
  for (const Placement& placement : placements) {
    combine(seed, placement.present ? 1U : 0U);
    combinePose(seed, placement.pose);
  }
  for (const auto& [a, b] : joined) {
    combine(seed, a);
    combine(seed, b);
  }
  return seed;
}

}  // namespace kaboum::world
