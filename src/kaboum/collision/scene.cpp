#include "kaboum/collision/scene.hpp"

#include <stdexcept>
#include <string>

namespace kaboum::collision {

using namespace kaboum::geometry;

std::size_t CollisionScene::add(BodyPtr body, const Pose& pose, std::string name) {
  const std::size_t id = objects_.size();
  for (std::size_t p = 0; p < body->pieceCount(); ++p) {
    fixedPieces_.push_back({id, p, pose * body->pieceBounds(p).centre});
    fixedBoxes_.push_back(worldBox(body->piece(p), pose));
  }
  objects_.push_back({std::move(body), pose, std::move(name), kFixed});
  tree_.build(fixedBoxes_);
  return id;
}

std::size_t CollisionScene::addMovable(BodyPtr body, const Pose& initial, std::string name) {
  objects_.push_back({std::move(body), initial, std::move(name), movable_.size()});
  movable_.push_back(objects_.size() - 1);
  return objects_.size() - 1;
}

std::size_t CollisionScene::slot(std::size_t object) const {
  const std::size_t slot = objects_.at(object).slot;
  if (slot == kFixed) {
    throw std::invalid_argument("scene: object " + std::to_string(object) + " (" +
                                objects_[object].name + ") is a fixed obstacle, not movable");
  }
  return slot;
}

SceneState CollisionScene::initialState() const {
  SceneState state;
  state.reserve(movable_.size());
  for (const std::size_t id : movable_) state.push_back({objects_[id].pose, true});
  return state;
}

void CollisionScene::throwStateMismatch(std::size_t placements) const {
  throw std::invalid_argument("scene: a state of " + std::to_string(placements) +
                              " placements for " + std::to_string(movable_.size()) +
                              " movable objects");
}

const Pose& CollisionScene::pose(std::size_t object, std::span<const Placement> state) const {
  checkState(state);
  const Object& found = objects_.at(object);
  return found.slot == kFixed ? found.pose : state[found.slot].pose;
}

bool CollisionScene::present(std::size_t object, std::span<const Placement> state) const {
  checkState(state);
  const Object& found = objects_.at(object);
  return found.slot == kFixed || state[found.slot].present;
}

// Exact world box of the posed vertices: tighter than a rotated local box.
Aabb CollisionScene::worldBox(const ConvexPolytope& piece, const Pose& pose) {
  const auto& vertices = piece.vertices();
  Aabb box{pose * vertices[0], pose * vertices[0]};
  for (const Vec3& v : vertices) {
    const Vec3 w = pose * v;
    box = {box.lo.cwiseMin(w), box.hi.cwiseMax(w)};
  }
  return box;
}

std::optional<std::size_t> CollisionScene::firstCollision(std::span<const Placement> state,
                                                          const CollisionBody& body,
                                                          const Pose& pose, double margin,
                                                          std::optional<std::size_t> ignore) const {
  if (body.pieceCount() == 1) {
    const PieceBounds& bounds = body.pieceBounds(0);
    return firstWithin(state, TransformedSupport(body.piece(0), pose),
                       transformedAabb(bounds.box, pose), pose * bounds.centre, bounds.radius,
                       margin, ignore);
  }
  // One broad-phase pass for the whole body; each obstacle piece found, placed in the body's
  // frame, then queries the body's piece tree (pieceWithinBody, as bodiesCollide does).
  const PieceBounds& own = body.bounds();
  std::optional<std::size_t> hit;
  forEachPieceNear(state, transformedAabb(own.box, pose), pose * own.centre, own.radius, margin,
                   ignore, [&](std::size_t object, std::size_t piece, const Pose& objectPose) {
                     const CollisionBody& obstacle = *objects_[object].body;
                     if (!pieceWithinBody(body, obstacle.piece(piece), obstacle.pieceBounds(piece),
                                          inFrameOf(pose, objectPose), margin)) {
                       return true;
                     }
                     hit = object;
                     return false;
                   });
  return hit;
}

}  // namespace kaboum::collision
