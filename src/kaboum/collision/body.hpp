// Rigid bodies made of convex pieces (thesis §4.4, bounding convex decompositions): the
// bounding convex decomposition of one object or robot link in its own frame, posed by an
// Isometry3d at query time without copying or transforming vertices.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/broad_phase.hpp"
#include "kaboum/collision/convex_polytope.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

// Culling data of one piece in the body frame: a bounding sphere and a box.
struct PieceBounds {
  Vec3 centre{0, 0, 0};
  double radius = 0;
  Aabb box;
};

class CollisionBody {
 public:
  // One piece per vertex set (each set's convex hull). Throws InputError naming `what` and the
  // piece for an empty list or a set without volume (fewer than four non-coplanar points).
  CollisionBody(std::span<const std::vector<Vec3>> convexSets, const std::string& what);

  [[nodiscard]] std::size_t pieceCount() const { return pieces_.size(); }
  [[nodiscard]] const ConvexPolytope& piece(std::size_t i) const { return pieces_[i]; }
  [[nodiscard]] const PieceBounds& pieceBounds(std::size_t i) const { return bounds_[i]; }
  // Bounds of the whole body (the union of its pieces).
  [[nodiscard]] const PieceBounds& bounds() const { return bodyBounds_; }
  // Largest distance of a vertex from the body frame origin (r in the sweep steps, Eq. 4.19).
  [[nodiscard]] double reach() const { return reach_; }
  // Bounding-volume tree over the pieces' local boxes (ids are piece indices).
  [[nodiscard]] const AabbTree& pieceTree() const { return tree_; }

 private:
  std::vector<ConvexPolytope> pieces_;
  std::vector<PieceBounds> bounds_;
  PieceBounds bodyBounds_;
  double reach_ = 0;
  AabbTree tree_;
};

using BodyPtr = std::shared_ptr<const CollisionBody>;

// `pose` expressed in the frame `frame` (frame⁻¹ · pose), with the rotation inverted by transpose.
inline Pose inFrameOf(const Pose& frame, const Pose& pose) {
  const Eigen::Matrix3d toFrame = frame.linear().transpose();
  Pose relative = Pose::Identity();
  relative.linear() = toFrame * pose.linear();
  relative.translation() = toFrame * (pose.translation() - frame.translation());
  return relative;
}

// True when `piece` (with its culling `bounds`), placed in the body's frame by `inBody`, comes
// within `margin` of some piece of `body`: its box there queries the body's piece tree, and the
// narrow phase (sphere pre-tests, then portal/GJK) decides the pieces found. Allocates nothing.
bool pieceWithinBody(const CollisionBody& body, const ConvexPolytope& piece,
                     const PieceBounds& bounds, const Pose& inBody, double margin);

// True when some pieces of `a` and `b` (posed by `poseA`, `poseB`) are within `margin` of each
// other (single-sided: never false at distance <= margin; may be true slightly above, within the
// narrow phase's tolerance). Runs in a's frame: each piece of b goes through pieceWithinBody().
// Allocates nothing.
bool bodiesCollide(const CollisionBody& a, const Pose& poseA, const CollisionBody& b,
                   const Pose& poseB, double margin);

// Whether the posed spheres (c1, r1) and (c2, r2) come within `margin`.
inline bool spheresWithin(const Vec3& c1, double r1, const Vec3& c2, double r2, double margin) {
  const double reach = r1 + r2 + margin;
  return (c1 - c2).squaredNorm() <= reach * reach;
}

}  // namespace kaboum::collision
