// Bounded geometric predicates (thesis §4.1, Definition 1, Table 4.1; seed 003 §III-B): inclusion
// in a convex region and resting on a support surface. The collision predicates of Definition 1
// are bodiesCollide / CollisionScene::firstCollision (1), RobotSweep::firstSceneCollision (2) and
// sweptVolumesCollide (3).
#pragma once

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

}  // namespace kaboum::collision
