#include "kaboum/geometry/triangle_intersection.hpp"

namespace kaboum {
namespace {

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

int sharedCount(const Triangle& t, const Triangle& u, int& tOnly, int& uOnly) {
  int shared = 0;
  tOnly = uOnly = -1;
  for (int i = 0; i < 3; ++i) {
    const bool inU = t[i] == u[0] || t[i] == u[1] || t[i] == u[2];
    const bool inT = u[i] == t[0] || u[i] == t[1] || u[i] == t[2];
    shared += inU ? 1 : 0;
    if (!inU) tOnly = i;
    if (!inT) uOnly = i;
  }
  return shared;
}

}  // namespace

bool segmentMeetsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                          const Vec3& c) {
  const double dp = orient(a, b, c, p);
  const double dq = orient(a, b, c, q);
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || (dp == 0 && dq == 0)) return false;
  const double s1 = orient(p, q, a, b);
  const double s2 = orient(p, q, b, c);
  const double s3 = orient(p, q, c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

namespace {

// True when all of `x` lies strictly on one side of the plane of `y`, vertices shared with `y`
// (which lie on it) aside: then the two cannot meet beyond their shared vertices.
bool strictlyOneSide(const std::array<Vec3, 3>& x, const Triangle& xIds,
                     const std::array<Vec3, 3>& y, const Triangle& yIds) {
  const Vec3 n = (y[1] - y[0]).cross(y[2] - y[0]);
  int positive = 0, negative = 0;
  for (int i = 0; i < 3; ++i) {
    if (xIds[i] == yIds[0] || xIds[i] == yIds[1] || xIds[i] == yIds[2]) continue;
    const double d = n.dot(x[i] - y[0]);
    if (d > 0) {
      ++positive;
    } else if (d < 0) {
      ++negative;
    } else {
      return false;
    }
  }
  return positive == 0 || negative == 0;
}

}  // namespace

bool trianglesIntersect(const std::array<Vec3, 3>& t, const Triangle& tIds,
                        const std::array<Vec3, 3>& u, const Triangle& uIds) {
  if (strictlyOneSide(u, uIds, t, tIds) || strictlyOneSide(t, tIds, u, uIds)) return false;
  int tOnly = -1, uOnly = -1;
  switch (sharedCount(tIds, uIds, tOnly, uOnly)) {
    case 0:
      // Non-coplanar triangles intersect exactly when an edge of one meets the other.
      for (int i = 0; i < 3; ++i) {
        if (segmentMeetsTriangle(t[i], t[(i + 1) % 3], u[0], u[1], u[2])) return true;
        if (segmentMeetsTriangle(u[i], u[(i + 1) % 3], t[0], t[1], t[2])) return true;
      }
      return false;
    case 1: {
      // Sharing vertex s, they meet elsewhere only if an edge opposite s crosses the other triangle
      // (an edge from s meets the other plane only at s).
      const auto opposite = [](const std::array<Vec3, 3>& x, const Triangle& xIds,
                               const Triangle& yIds, Vec3& p, Vec3& q) {
        int k = 0;
        for (; k < 3; ++k) {
          if (xIds[k] == yIds[0] || xIds[k] == yIds[1] || xIds[k] == yIds[2]) break;
        }
        p = x[(k + 1) % 3];
        q = x[(k + 2) % 3];
      };
      Vec3 p, q;
      opposite(t, tIds, uIds, p, q);
      if (segmentMeetsTriangle(p, q, u[0], u[1], u[2])) return true;
      opposite(u, uIds, tIds, p, q);
      return segmentMeetsTriangle(p, q, t[0], t[1], t[2]);
    }
    default:
      return false;
  }
}

}  // namespace kaboum
