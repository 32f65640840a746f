// A scene of collision bodies (thesis §4.1, the models of Definition 1), split like a planner's
// state: the geometry is built once and shared (every body, and the fixed obstacles with an
// AABB-tree broad phase over their pieces); where the movable objects are is per state (a
// SceneState), passed to every const query, so that a search evaluates many states of one scene.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/body.hpp"
#include "kaboum/collision/gjk.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

// Where one movable object is in one state: its pose, and whether it is in the scene at all (an
// absent object, e.g. one a robot holds, takes part in no query).
struct Placement {
  Pose pose = Pose::Identity();
  bool present = true;
};

// The per-state part of a scene: one Placement per movable object, at the object's slot
// (CollisionScene::slot). A plain value; queries take any contiguous placements (a span).
using SceneState = std::vector<Placement>;

class CollisionScene {
 public:
  // Building the geometry (before the scene is shared; each call rebuilds the broad phase of the
  // fixed obstacles). Object ids count up from 0 over both kinds of object and stay valid.
  // A fixed obstacle at `pose`.
  std::size_t add(BodyPtr body, const Pose& pose, std::string name = {});
  // A movable object: its pose and presence come from the state of each query; `initial` is its
  // placement in initialState().
  std::size_t addMovable(BodyPtr body, const Pose& initial, std::string name = {});

  [[nodiscard]] std::size_t size() const { return objects_.size(); }
  [[nodiscard]] const CollisionBody& body(std::size_t object) const {
    return *objects_[object].body;
  }
  [[nodiscard]] const BodyPtr& sharedBody(std::size_t object) const {
    return objects_[object].body;
  }
  [[nodiscard]] const std::string& name(std::size_t object) const { return objects_[object].name; }
  [[nodiscard]] bool movable(std::size_t object) const { return objects_[object].slot != kFixed; }
  [[nodiscard]] std::size_t movableCount() const { return movable_.size(); }
  // Index of a movable object's placement in a SceneState. Throws std::invalid_argument for a
  // fixed obstacle.
  [[nodiscard]] std::size_t slot(std::size_t object) const;
  // Every movable object present at the placement given to addMovable().
  [[nodiscard]] SceneState initialState() const;
  // Pose and presence of an object in `state` (a fixed obstacle: where it was added, always
  // present). Throws std::invalid_argument when `state` does not hold movableCount() placements,
  // as every query below does.
  [[nodiscard]] const Pose& pose(std::size_t object, std::span<const Placement> state) const;
  [[nodiscard]] bool present(std::size_t object, std::span<const Placement> state) const;

  // The object of the first scene piece found within `margin` of the convex `shape` (any
  // SupportMapping in world coordinates) whose world box is `box` and bounding sphere (centre,
  // radius), in `state`; `ignore` is skipped. Single-sided like the narrow phase: never misses a
  // piece at distance <= margin. Allocates nothing.
  template <SupportMapping Shape>
  [[nodiscard]] std::optional<std::size_t> firstWithin(
      std::span<const Placement> state, const Shape& shape, const Aabb& box, const Vec3& centre,
      double radius, double margin, std::optional<std::size_t> ignore = {}) const {
    std::optional<std::size_t> hit;
    forEachPieceNear(
        state, box, centre, radius, margin, ignore,
        [&](std::size_t object, std::size_t piece, const Pose& pose) {
          if (!intersects(shape, TransformedSupport(body(object).piece(piece), pose), margin)) {
            return true;
          }
          hit = object;
          return false;
        });
    return hit;
  }

  // Whether some piece of `state` (except `ignore`) has a box overlapping `box` inflated by
  // `margin` and a bounding sphere within `margin` of (centre, radius): the broad phase alone, to
  // skip the narrow phase of everything inside that box and sphere. Allocates nothing.
  [[nodiscard]] bool anyPieceNear(std::span<const Placement> state, const Aabb& box,
                                  const Vec3& centre, double radius, double margin,
                                  std::optional<std::size_t> ignore = {}) const {
    bool near = false;
    forEachPieceNear(state, box, centre, radius, margin, ignore,
                     [&](std::size_t, std::size_t, const Pose&) { return !(near = true); });
    return near;
  }

  // Calls visit(object, piece, objectPose) for every piece of a fixed obstacle or present movable
  // object of `state` (except `ignore`) whose box overlaps `box` and bounding sphere comes within
  // `margin` of (centre, radius), until visit returns false. Allocates nothing.
  template <class Visit>
  void forEachPieceNear(std::span<const Placement> state, const Aabb& box, const Vec3& centre,
                        double radius, double margin, std::optional<std::size_t> ignore,
                        Visit&& visit) const {
    checkState(state);
    const Aabb reach = box.inflated(margin);
    const bool stopped = !tree_.forEachOverlapping(reach, [&](std::uint32_t id) {
      const FixedPiece& fixed = fixedPieces_[id];
      if (fixed.object == ignore) return true;
      const Object& object = objects_[fixed.object];
      return !spheresWithin(centre, radius, fixed.centre,
                            object.body->pieceBounds(fixed.piece).radius, margin) ||
             visit(fixed.object, fixed.piece, object.pose);
    });
    if (stopped) return;
    for (std::size_t slot = 0; slot < movable_.size(); ++slot) {
      const std::size_t id = movable_[slot];
      if (!state[slot].present || id == ignore) continue;
      const Pose& pose = state[slot].pose;
      const CollisionBody& body = *objects_[id].body;
      if (!spheresWithin(centre, radius, pose * body.bounds().centre, body.bounds().radius,
                         margin)) {
        continue;
      }
      for (std::size_t p = 0; p < body.pieceCount(); ++p) {
        const PieceBounds& bounds = body.pieceBounds(p);
        if (spheresWithin(centre, radius, pose * bounds.centre, bounds.radius, margin) &&
            transformedAabb(bounds.box, pose).overlaps(reach) && !visit(id, p, pose)) {
          return;
        }
      }
    }
  }
  // An object of `state` with a piece within `margin` of `body` at `pose` (model-model collision,
  // Definition 1 (1)), skipping `ignore`: the fixed obstacles in the order the tree visits them,
  // then the present movable objects by slot; so the same for the same state and query, but not
  // necessarily the lowest index when several collide. Allocates nothing.
  [[nodiscard]] std::optional<std::size_t> firstCollision(
      std::span<const Placement> state, const CollisionBody& body, const Pose& pose, double margin,
      std::optional<std::size_t> ignore = {}) const;

 private:
  static constexpr std::size_t kFixed = static_cast<std::size_t>(-1);
  struct Object {
    BodyPtr body;
    Pose pose;  // a fixed obstacle's pose; a movable object's initial placement
    std::string name;
    std::size_t slot = kFixed;  // a movable object's index in SceneState
  };
  struct FixedPiece {  // one piece of one fixed obstacle in the broad phase
    std::size_t object = 0;
    std::size_t piece = 0;
    Vec3 centre{0, 0, 0};  // world centre of the piece's bounding sphere
  };
  void checkState(std::span<const Placement> state) const {
    if (state.size() != movable_.size()) throwStateMismatch(state.size());
  }
  [[noreturn]] void throwStateMismatch(std::size_t placements) const;

  static Aabb worldBox(const ConvexPolytope& piece, const Pose& pose);

  std::vector<Object> objects_;
  std::vector<std::size_t> movable_;  // object id per slot
  std::vector<FixedPiece> fixedPieces_;
  std::vector<Aabb> fixedBoxes_;
  AabbTree tree_;
};

}  // namespace kaboum::collision
