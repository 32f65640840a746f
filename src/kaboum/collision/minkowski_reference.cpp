#include "kaboum/collision/minkowski_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::collision {

Vec3 closestPointOnTriangle(const Vec3& point, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 ab = p1 - p0;
  const Vec3 ac = p2 - p0;
  const Vec3 ap = point - p0;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return p0;
  const Vec3 bp = point - p1;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return p1;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return p0 + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = point - p2;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return p2;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return p0 + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return p1 + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (p2 - p1);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return p0 + ab * (vb * denominator) + ac * (vc * denominator);
}

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

}  // namespace kaboum::collision
