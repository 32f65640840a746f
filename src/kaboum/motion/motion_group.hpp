// The robots that move together in one motion (thesis §6.1.2: transit and transfer paths of one
// arm, or of several arms at once for bimanual actions) and the state they move in: one joint
// space, the concatenation of the moving robots' configurations, over a fixed context (the other
// robots, the objects, what every robot holds).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "kaboum/world/world.hpp"

namespace kaboum::motion {

using namespace kaboum::world;

class MotionGroup {
 public:
  // `robots`: indices into world.robots(), each at most once, in the order of the joint space.
  // Throws std::invalid_argument for an empty list, an unknown or repeated robot, or a context of
  // the wrong shape. `world` must outlive the group.
  MotionGroup(const World& world, GeometricState context, std::vector<std::size_t> robots);

  [[nodiscard]] const World& world() const { return *world_; }
  [[nodiscard]] const GeometricState& context() const { return context_; }
  [[nodiscard]] const std::vector<std::size_t>& robots() const { return robots_; }
  [[nodiscard]] std::size_t dimension() const { return lower_.size(); }
  // Joint limits of each coordinate (the URDF's; continuous joints ±π).
  [[nodiscard]] const std::vector<double>& lower() const { return lower_; }
  [[nodiscard]] const std::vector<double>& upper() const { return upper_; }
  // The coordinates of the k-th moving robot within q.
  [[nodiscard]] std::span<const double> robotPart(std::span<const double> q, std::size_t k) const {
    return q.subspan(offsets_[k], offsets_[k + 1] - offsets_[k]);
  }
  // The moving robots' configurations in `state`, concatenated.
  [[nodiscard]] std::vector<double> configuration(const GeometricState& state) const;
  // Writes q into the moving robots' configurations of `state` (of the world's shape). Allocates
  // nothing.
  void assign(std::span<const double> q, GeometricState& state) const;
  // Keeps variable `variable` of the k-th moving robot at its value in the context: its limits
  // become that value, so that no motion of the group moves it (a hand's fingers while its arm
  // moves). Throws std::out_of_range for an unknown robot or variable.
  void holdStill(std::size_t k, int variable);
  // The first coordinate outside its limits (beyond `tolerance`), or dimension().
  [[nodiscard]] std::size_t firstOutsideLimits(std::span<const double> q,
                                               double tolerance = 1e-9) const;
  // The robot (index into world.robots()) and its configuration variable at coordinate i.
  struct Coordinate {
    std::size_t robot = 0;
    int variable = 0;
  };
  [[nodiscard]] Coordinate coordinate(std::size_t i) const;
  // "joint2 of robot 'left'": the name of coordinate i, for messages.
  [[nodiscard]] std::string coordinateName(std::size_t i) const;

 private:
  const World* world_;
  GeometricState context_;
  std::vector<std::size_t> robots_;
  std::vector<std::size_t> offsets_;  // robots_.size() + 1 offsets into q
  std::vector<double> lower_, upper_;
};

}  // namespace kaboum::motion
