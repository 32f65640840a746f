// A scene of posed collision bodies (obstacles, movable objects) with an AABB-tree broad phase
// over all their pieces (issue 3, "a scene of many bodies with a broad phase").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kaboum/collision/body.hpp"
#include "kaboum/collision/gjk.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

class CollisionScene {
 public:
  // Adds `body` at `pose` and returns its object id (ids count up from 0 and stay valid). The
  // broad phase is rebuilt, so queries stay const and allocation-free.
  std::size_t add(BodyPtr body, const Pose& pose, std::string name = {});
  // Moves an object; the broad phase is refitted in place (no allocation, no rebuild).
  void setPose(std::size_t object, const Pose& pose);
  // An inactive object takes part in no query (e.g. while it is held by a robot).
  void setActive(std::size_t object, bool active);

  [[nodiscard]] std::size_t size() const { return objects_.size(); }
  [[nodiscard]] const CollisionBody& body(std::size_t object) const {
    return *objects_[object].body;
  }
  [[nodiscard]] const BodyPtr& sharedBody(std::size_t object) const {
    return objects_[object].body;
  }
  [[nodiscard]] const Pose& pose(std::size_t object) const { return objects_[object].pose; }
  [[nodiscard]] const std::string& name(std::size_t object) const { return objects_[object].name; }
  [[nodiscard]] bool active(std::size_t object) const { return objects_[object].active; }

  // The object of the first scene piece found within `margin` of the convex `shape` (any
  // SupportMapping in world coordinates) whose world box is `box` and bounding sphere (centre,
  // radius); `ignore` is skipped. Single-sided like the narrow phase: never misses a piece at
  // distance <= margin.
  template <SupportMapping Shape>
  [[nodiscard]] std::optional<std::size_t> firstWithin(
      const Shape& shape, const Aabb& box, const Vec3& centre, double radius, double margin,
      std::optional<std::size_t> ignore = {}) const {
    std::optional<std::size_t> hit;
    tree_.forEachOverlapping(box.inflated(margin), [&](std::uint32_t slotId) {
      const Slot& slot = slots_[slotId];
      if (slot.object == ignore) return true;
      const Object& object = objects_[slot.object];
      const PieceBounds& bounds = object.body->pieceBounds(slot.piece);
      if (spheresWithin(centre, radius, slot.centre, bounds.radius, margin) &&
          intersects(shape, TransformedSupport(object.body->piece(slot.piece), object.pose),
                     margin)) {
        hit = slot.object;
        return false;
      }
      return true;
    });
    return hit;
  }

  // An object with a piece within `margin` of `body` at `pose` (model-model collision,
  // Definition 1 (1)), skipping `ignore`: the first the scene tree visits, so the same for the
  // same scene and query, but not necessarily the lowest index when several collide.
  [[nodiscard]] std::optional<std::size_t> firstCollision(
      const CollisionBody& body, const Pose& pose, double margin,
      std::optional<std::size_t> ignore = {}) const;

 private:
  struct Object {
    BodyPtr body;
    Pose pose;
    std::string name;
    bool active = true;
    std::size_t firstSlot = 0;  // its pieces' slots follow this one when active
  };
  struct Slot {  // one piece of one active object in the broad phase
    std::size_t object = 0;
    std::size_t piece = 0;
    Vec3 centre{0, 0, 0};  // world centre of the piece's bounding sphere
  };
  void rebuild();
  static Aabb worldBox(const ConvexPolytope& piece, const Pose& pose);

  std::vector<Object> objects_;
  std::vector<Slot> slots_;
  std::vector<Aabb> slotBoxes_;
  AabbTree tree_;
};

}  // namespace kaboum::collision
