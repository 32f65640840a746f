#include "kaboum/collision/scene.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

std::size_t CollisionScene::add(BodyPtr body, const Pose& pose, std::string name) {
  objects_.push_back({std::move(body), pose, std::move(name), true, 0});
  rebuild();
  return objects_.size() - 1;
}

void CollisionScene::setPose(std::size_t object, const Pose& pose) {
  Object& moved = objects_.at(object);
  moved.pose = pose;
  if (!moved.active) return;
  for (std::size_t slot = moved.firstSlot; slot < moved.firstSlot + moved.body->pieceCount();
       ++slot) {
    slots_[slot].centre = pose * moved.body->pieceBounds(slots_[slot].piece).centre;
    slotBoxes_[slot] = worldBox(moved.body->piece(slots_[slot].piece), pose);
  }
  tree_.refit(slotBoxes_);
}

void CollisionScene::setActive(std::size_t object, bool active) {
  objects_.at(object).active = active;
  rebuild();
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

void CollisionScene::rebuild() {
  slots_.clear();
  slotBoxes_.clear();
  for (std::size_t o = 0; o < objects_.size(); ++o) {
    Object& object = objects_[o];
    object.firstSlot = slots_.size();
    if (!object.active) continue;
    for (std::size_t p = 0; p < object.body->pieceCount(); ++p) {
      slots_.push_back({o, p, object.pose * object.body->pieceBounds(p).centre});
      slotBoxes_.push_back(worldBox(object.body->piece(p), object.pose));
    }
  }
  tree_.build(slotBoxes_);
}

std::optional<std::size_t> CollisionScene::firstCollision(const CollisionBody& body,
                                                          const Pose& pose, double margin,
                                                          std::optional<std::size_t> ignore) const {
  if (body.pieceCount() == 1) {
    const PieceBounds& bounds = body.pieceBounds(0);
    return firstWithin(TransformedSupport(body.piece(0), pose), transformedAabb(bounds.box, pose),
                       pose * bounds.centre, bounds.radius, margin, ignore);
  }
  // One scene-tree query for the whole body; each obstacle piece found, placed in the body's
  // frame, then queries the body's piece tree (pieceWithinBody, as bodiesCollide does).
  const Eigen::Matrix3d toBody = pose.linear().transpose();
  const PieceBounds& own = body.bounds();
  std::optional<std::size_t> hit;
  tree_.forEachOverlapping(
      transformedAabb(own.box, pose).inflated(margin), [&](std::uint32_t slotId) {
        const Slot& slot = slots_[slotId];
        if (slot.object == ignore) return true;
        const Object& object = objects_[slot.object];
        const PieceBounds& bounds = object.body->pieceBounds(slot.piece);
        if (!spheresWithin(own.centre, own.radius, toBody * (slot.centre - pose.translation()),
                           bounds.radius, margin)) {
          return true;
        }
        if (!pieceWithinBody(body, object.body->piece(slot.piece), bounds,
                             inFrameOf(pose, object.pose), margin)) {
          return true;
        }
        hit = slot.object;
        return false;
      });
  return hit;
}

}  // namespace kaboum::collision
