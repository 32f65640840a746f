// Bounded geometric predicates (thesis §4.1, Definition 1, Table 4.1; seed 003 §III-B): inclusion
// in a convex region and resting on a support surface. The collision predicates of Definition 1
// are bodiesCollide / CollisionScene::firstCollision (1), RobotSweep::firstSceneCollision (2) and
// sweptVolumesCollide (3).
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/scene.hpp"
#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

// A convex region { x : n.x <= d for every facet plane } in its own frame, e.g. a goal region or
// the inside of a tray (a "location" of seed 003's isInside).
class ConvexContainer {
 public:
  // The convex hull of `points`; throws InputError (naming `what`) as convexHull() does.
  explicit ConvexContainer(std::span<const Vec3> points, const std::string& what = "container")
      : planes_(convexHull(points, what).planes) {}
  [[nodiscard]] const std::vector<HullPlane>& planes() const { return planes_; }

 private:
  std::vector<HullPlane> planes_;
};

// Definition 1 (4), object ⊆ container: every vertex of every convex piece of `object` lies in
// every half-space. The pieces contain the object, so this never answers "inside" when the object
// is not; it may answer "not inside" when only the pieces' bounding error (≤ ε for a bounding
// convex decomposition at ε) sticks out. Allocates nothing.
bool isInside(const CollisionBody& object, const Pose& objectPose, const ConvexContainer& container,
              const Pose& containerPose);

// Seed 003's isOnSupportSurface for scene object `object` at its pose in `state`: the object is
// collision-free (no other object present in `state` within distance 0 of its pieces) and every
// vertical segment of length `drop` going down (−z) from its lowest vertices (those within `band`
// of the lowest one) touches another present object. Allocates nothing.
bool isOnSupportSurface(const CollisionScene& scene, std::span<const Placement> state,
                        std::size_t object, double drop, double band);

// A line segment [a, b] as a support mapping (the downward probes of isOnSupportSurface).
struct SegmentSupport {
  using Hint = int;
  Vec3 a, b;
  [[nodiscard]] Vec3 support(const Vec3& direction, Hint& /*hint*/) const {
    return direction.dot(b) > direction.dot(a) ? b : a;
  }
  [[nodiscard]] Vec3 center() const { return 0.5 * (a + b); }
};
static_assert(SupportMapping<SegmentSupport>);

// The probes of seed 003's support heuristic: calls probe(segment) for the vertical segment of
// length `drop` going down (−z) from each lowest vertex of `body`'s pieces at `pose` (those within
// `band` of the lowest one), in piece and vertex order, until probe returns false. Returns whether
// every call returned true. Allocates nothing.
template <class Probe>
bool allBottomProbes(const CollisionBody& body, const Pose& pose, double drop, double band,
                     Probe&& probe) {
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    for (const Vec3& v : body.piece(p).vertices()) lowest = std::min(lowest, (pose * v).z());
  }
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    for (const Vec3& v : body.piece(p).vertices()) {
      const Vec3 top = pose * v;
      if (top.z() > lowest + band) continue;
      if (!probe(SegmentSupport{top, top - Vec3(0, 0, drop)})) return false;
    }
  }
  return true;
}

// Whether the probe `segment` (a downward one of allBottomProbes) touches a piece of an object
// present in `state` other than `ignore`, or comes within `margin` of one (a probe from the corner
// of a block stacked flush on an equal one runs down the lower block's edge); which one, the first
// the broad phase finds.
inline std::optional<std::size_t> probeTouches(const CollisionScene& scene,
                                               std::span<const Placement> state,
                                               const SegmentSupport& segment,
                                               std::optional<std::size_t> ignore,
                                               double margin = 0.0) {
  const Aabb box{segment.a.cwiseMin(segment.b), segment.a.cwiseMax(segment.b)};
  return scene.firstWithin(state, segment, box, segment.center(),
                           0.5 * (segment.a - segment.b).norm(), margin, ignore);
}

}  // namespace kaboum::collision
