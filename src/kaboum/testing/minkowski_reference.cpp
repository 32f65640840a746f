#include "kaboum/testing/minkowski_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;

MinkowskiReference minkowskiReference(std::span<const Vec3> a, std::span<const Vec3> b) {
  std::vector<Vec3> difference;
  difference.reserve(a.size() * b.size());
  for (const Vec3& p : a) {
    for (const Vec3& q : b) difference.push_back(p - q);
  }
  const ConvexHull hull = convexHull(difference, "Minkowski difference");
  // Inside iff the origin satisfies every facet's n.x <= d, i.e. every offset d >= 0.
  double depth = std::numeric_limits<double>::infinity();
  for (const HullPlane& plane : hull.planes) depth = std::min(depth, plane.offset);
  if (depth >= 0.0) return {-depth, Vec3::Zero()};
  MinkowskiReference reference{std::numeric_limits<double>::infinity(), Vec3::Zero()};
  const auto& v = hull.mesh.vertices;
  for (const Triangle& t : hull.mesh.triangles) {
    const Vec3 closest = closestPointOnTriangle(Vec3::Zero(), v[t[0]], v[t[1]], v[t[2]]);
    if (closest.norm() < reference.signedDistance) {
      reference.signedDistance = closest.norm();
      reference.closestPoint = closest;
    }
  }
  return reference;
}

}  // namespace kaboum::testing
