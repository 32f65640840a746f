#include "kaboum/collision/scene.hpp"

#include <array>

namespace kaboum::collision {

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
  // One tree query for the whole body; its pieces then test only those candidates.
  std::array<std::uint32_t, kMaxCandidates> candidates{};
  std::size_t count = 0;
  const bool complete = tree_.forEachOverlapping(
      transformedAabb(body.bounds().box, pose).inflated(margin), [&](std::uint32_t slot) {
        if (slots_[slot].object == ignore) return true;
        candidates[count++] = slot;
        return count < candidates.size();
      });
  if (complete && count == 0) return std::nullopt;
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    const PieceBounds& bounds = body.pieceBounds(p);
    const TransformedSupport piece(body.piece(p), pose);
    const Aabb box = transformedAabb(bounds.box, pose).inflated(margin);
    const Vec3 centre = pose * bounds.centre;
    if (!complete) {  // more candidates than the buffer holds: query per piece
      if (auto hit = firstWithin(piece, box, centre, bounds.radius, margin, ignore)) return hit;
      continue;
    }
    for (std::size_t c = 0; c < count; ++c) {
      const Slot& slot = slots_[candidates[c]];
      const Object& object = objects_[slot.object];
      if (slotBoxes_[candidates[c]].overlaps(box) &&
          spheresWithin(centre, bounds.radius, slot.centre,
                        object.body->pieceBounds(slot.piece).radius, margin) &&
          intersects(piece, TransformedSupport(object.body->piece(slot.piece), object.pose),
                     margin)) {
        return slot.object;
      }
    }
  }
  return std::nullopt;
}

}  // namespace kaboum::collision
