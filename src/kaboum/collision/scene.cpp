#include "kaboum/collision/scene.hpp"

namespace kaboum::collision {

std::size_t CollisionScene::add(BodyPtr body, const Pose& pose, std::string name) {
  objects_.push_back({std::move(body), pose, std::move(name), true});
  rebuild();
  return objects_.size() - 1;
}

void CollisionScene::setPose(std::size_t object, const Pose& pose) {
  objects_.at(object).pose = pose;
  rebuild();
}

void CollisionScene::setActive(std::size_t object, bool active) {
  objects_.at(object).active = active;
  rebuild();
}

void CollisionScene::rebuild() {
  slots_.clear();
  slotBoxes_.clear();
  for (std::size_t o = 0; o < objects_.size(); ++o) {
    const Object& object = objects_[o];
    if (!object.active) continue;
    for (std::size_t p = 0; p < object.body->pieceCount(); ++p) {
      // Exact world box of the posed vertices: tighter than a rotated local box.
      const auto& vertices = object.body->piece(p).vertices();
      Aabb box{object.pose * vertices[0], object.pose * vertices[0]};
      for (const Vec3& v : vertices) {
        const Vec3 w = object.pose * v;
        box = {box.lo.cwiseMin(w), box.hi.cwiseMax(w)};
      }
      slots_.push_back({o, p, object.pose * object.body->pieceBounds(p).centre});
      slotBoxes_.push_back(box);
    }
  }
  tree_.build(slotBoxes_);
}

std::optional<std::size_t> CollisionScene::firstCollision(const CollisionBody& body,
                                                          const Pose& pose, double margin,
                                                          std::optional<std::size_t> ignore) const {
  if (body.pieceCount() > 1 &&
      !tree_.anyOverlapping(transformedAabb(body.bounds().box, pose).inflated(margin))) {
    return std::nullopt;
  }
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    const PieceBounds& bounds = body.pieceBounds(p);
    const auto hit =
        firstWithin(TransformedSupport(body.piece(p), pose), transformedAabb(bounds.box, pose),
                    pose * bounds.centre, bounds.radius, margin, ignore);
    if (hit) return hit;
  }
  return std::nullopt;
}

}  // namespace kaboum::collision
