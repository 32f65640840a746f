#include "kaboum/collision/body.hpp"

#include "kaboum/collision/gjk.hpp"
#include "kaboum/core/error.hpp"

namespace kaboum::collision {

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
}

bool bodiesCollide(const CollisionBody& a, const Pose& poseA, const CollisionBody& b,
                   const Pose& poseB, double margin) {
  const Vec3 centreB = poseB * b.bounds().centre;
  if (!spheresWithin(poseA * a.bounds().centre, a.bounds().radius, centreB, b.bounds().radius,
                     margin)) {
    return false;
  }
  for (std::size_t i = 0; i < a.pieceCount(); ++i) {
    const PieceBounds& boundsA = a.pieceBounds(i);
    const Vec3 centreA = poseA * boundsA.centre;
    if (!spheresWithin(centreA, boundsA.radius, centreB, b.bounds().radius, margin)) continue;
    const TransformedSupport pieceA(a.piece(i), poseA);
    for (std::size_t j = 0; j < b.pieceCount(); ++j) {
      const PieceBounds& boundsB = b.pieceBounds(j);
      if (spheresWithin(centreA, boundsA.radius, poseB * boundsB.centre, boundsB.radius, margin) &&
          intersects(pieceA, TransformedSupport(b.piece(j), poseB), margin)) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace kaboum::collision
