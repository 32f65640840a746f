// The geometric state of the integrated planner (thesis §6.1.2, the geometric part of
// Definition 5's state): every robot's configuration, where the movable objects are, and what each
// robot holds. A plain value, copied freely by a search; the World evaluates queries on it.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/collision/scene.hpp"

namespace kaboum::world {

using namespace kaboum::collision;

// One robot's part of a state: its configuration (RobotModel variable order) and the objects it
// holds. held[i] is the scene object heldObjects[i], rigidly attached to a link at its grasp pose
// (Attachment::inLink: the object frame in the link frame).
struct RobotState {
  std::vector<double> configuration;
  std::vector<Attachment> held;
  std::vector<std::size_t> heldObjects;
};

// Equality and hash compare exact doubles (configurations, poses): two states are equal only when
// bit-for-bit the same values (0.0 and -0.0 aside), so states reached by different arithmetic are
// different states. A held object is compared by its object id, link and grasp pose; joined pairs
// are compared too.
struct GeometricState {
  std::vector<RobotState> robots;  // in the World's robot order
  SceneState placements;           // one per movable object, at CollisionScene::slot
  // (a held object's placement is absent)
  // Pairs of movable objects joined by an assembly (object ids, first < second, in order): they
  // touch where they fit into each other, and no collision query checks one against the other.
  std::vector<std::pair<std::size_t, std::size_t>> joined;

  // Records that objects `a` and `b` are joined (once).
  void join(std::size_t a, std::size_t b);
  [[nodiscard]] bool areJoined(std::size_t a, std::size_t b) const;
  // Whether object `object` is joined to some other object.
  [[nodiscard]] bool isJoined(std::size_t object) const;

  [[nodiscard]] bool operator==(const GeometricState& other) const;
  [[nodiscard]] std::size_t hashValue() const;
};

}  // namespace kaboum::world

template <>
struct std::hash<kaboum::world::GeometricState> {
  std::size_t operator()(const kaboum::world::GeometricState& state) const noexcept {
    return state.hashValue();
  }
};
