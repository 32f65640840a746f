#include "kaboum/collision/body.hpp"

#include "kaboum/collision/gjk.hpp"
#include "kaboum/core/error.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

CollisionBody::CollisionBody(std::span<const std::vector<Vec3>> convexSets,
                             const std::string& what) {
  if (convexSets.empty()) throw InputError(what + ": no convex pieces");
  pieces_.reserve(convexSets.size());
  for (std::size_t i = 0; i < convexSets.size(); ++i) {
    pieces_.emplace_back(convexSets[i], what + " piece " + std::to_string(i));
    const ConvexPolytope& piece = pieces_.back();
    bounds_.push_back({piece.boundingSphereCenter(), piece.boundingSphereRadius(),
                       Aabb{piece.localBox().min(), piece.localBox().max()}});
    for (const Vec3& v : piece.vertices()) reach_ = std::max(reach_, v.norm());
  }
  Aabb box = bounds_[0].box;
  for (const PieceBounds& b : bounds_) box = box.merged(b.box);
  const Vec3 centre = 0.5 * (box.lo + box.hi);
  double radius = 0;
  for (const ConvexPolytope& piece : pieces_) {
    for (const Vec3& v : piece.vertices()) radius = std::max(radius, (v - centre).norm());
  }
  bodyBounds_ = {centre, radius, box};
  std::vector<Aabb> boxes;
  for (const PieceBounds& b : bounds_) boxes.push_back(b.box);
  tree_.build(boxes);
}

bool pieceWithinBody(const CollisionBody& body, const ConvexPolytope& piece,
                     const PieceBounds& bounds, const Pose& inBody, double margin) {
  const TransformedSupport placed(piece, inBody);
  return !body.pieceTree().forEachOverlapping(
      transformedAabb(bounds.box, inBody).inflated(margin),
      [&](std::uint32_t i) { return !intersects(body.piece(i), placed, margin); });
}

bool bodiesCollide(const CollisionBody& a, const Pose& poseA, const CollisionBody& b,
                   const Pose& poseB, double margin) {
  // b in a's frame: a's pieces need no transform at all.
  const Pose relative = inFrameOf(poseA, poseB);
  const Vec3 centreB = relative * b.bounds().centre;
  if (!spheresWithin(a.bounds().centre, a.bounds().radius, centreB, b.bounds().radius, margin)) {
    return false;
  }
  for (std::size_t j = 0; j < b.pieceCount(); ++j) {
    if (pieceWithinBody(a, b.piece(j), b.pieceBounds(j), relative, margin)) return true;
  }
  return false;
}

}  // namespace kaboum::collision
