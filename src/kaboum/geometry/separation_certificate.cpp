#include "kaboum/geometry/separation_certificate.hpp"

#include <algorithm>
#include <cmath>

namespace kaboum::geometry {
namespace {

constexpr double kWellShaped = 1.01e-4;          // crossLength / size² (predicate: 1e-4)
constexpr double kSharedVertexMargin = 1.01e-6;  // height / size (predicate: 1e-6)
constexpr double kDisjointMargin = 1e-4;         // height / size, far beyond the exactness band
constexpr double kDisjointReachSquared = 4.0;    // first corners at most 2 size apart
constexpr double kSteepSquared = 1e-4;           // (height difference / edge length)², 1%
constexpr double kOutsideAngle = 200.0;          // margins outside the angle at the shared corner

// The far edge pq of a triangle sharing only corner `shared` with t stays farther than 99 margin
// from t: either both ends lie farther than `margin` on one side of t's plane (the predicate's
// certificate), or pq is steep to the plane (its ends' heights differ by at least 1% of its length)
// and meets the plane at a point X farther than 200 margin outside t's angle at the shared corner.
// Then every point of pq within `margin` of the plane is within 100 margin of X, and every other
// point is farther than `margin` from t.
bool farEdgeClear(const PlanedTriangle& t, int shared, const Vec3& p, const Vec3& q,
                  double margin) {
  const Vec3& s = *t.corners[shared];
  const double hp = t.unitNormal.dot(p - s), hq = t.unitNormal.dot(q - s);
  if ((hp > margin && hq > margin) || (hp < -margin && hq < -margin)) return true;
  const Vec3 pq = q - p;
  const double rise = hp - hq;
  if (!(rise * rise >= kSteepSquared * pq.squaredNorm())) return false;
  const Vec3 x = p + (hp / rise) * pq - s;  // X relative to s
  const Vec3 e1 = *t.corners[(shared + 1) % 3] - s, e2 = *t.corners[(shared + 2) % 3] - s;
  // t's angle at s is {y : (e1 × y)·n ≥ 0, (y × e2)·n ≥ 0}; X's distance to it is at least its
  // distance to either bounding half-plane it lies outside, -(e1 × X)·n / |e1| or -(X × e2)·n /
  // |e2| (compared squared, without roots).
  const double limit = kOutsideAngle * margin;
  const double outside1 = -e1.cross(x).dot(t.unitNormal);
  if (outside1 > 0.0 && outside1 * outside1 > limit * limit * e1.squaredNorm()) return true;
  const double outside2 = -x.cross(e2).dot(t.unitNormal);
  return outside2 > 0.0 && outside2 * outside2 > limit * limit * e2.squaredNorm();
}

bool allBeyondPlane(const PlanedTriangle& t, const PlanedTriangle& u, double margin) {
  const Vec3& origin = *t.corners[0];
  const double h0 = t.unitNormal.dot(*u.corners[0] - origin);
  if (!(std::abs(h0) > margin)) return false;
  const double h1 = t.unitNormal.dot(*u.corners[1] - origin);
  const double h2 = t.unitNormal.dot(*u.corners[2] - origin);
  return h0 > 0.0 ? (h1 > margin && h2 > margin) : (h1 < -margin && h2 < -margin);
}

}  // namespace

bool certainlyApart(const PlanedTriangle& t, const PlanedTriangle& u) {
  int shared = 0, sharedT = 0, sharedU = 0;
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      if (t.ids[k] == u.ids[l]) {
        ++shared;
        sharedT = k;
        sharedU = l;
      }
    }
  }
  if (shared > 1) return true;  // the predicate ignores triangles sharing an edge
  const double sizeSquared = std::max(t.sizeSquared, u.sizeSquared);
  const double wellShaped = kWellShaped * sizeSquared;
  if (!(t.crossLength >= wellShaped && u.crossLength >= wellShaped)) return false;
  const double size = std::sqrt(sizeSquared);
  if (shared == 1) {
    // The predicate tests each far edge against the other triangle.
    const double margin = kSharedVertexMargin * size;
    return farEdgeClear(t, sharedT, *u.corners[(sharedU + 1) % 3], *u.corners[(sharedU + 2) % 3],
                        margin) &&
           farEdgeClear(u, sharedU, *t.corners[(sharedT + 1) % 3], *t.corners[(sharedT + 2) % 3],
                        margin);
  }
  if ((*t.corners[0] - *u.corners[0]).squaredNorm() > kDisjointReachSquared * sizeSquared) {
    return false;
  }
  const double margin = kDisjointMargin * size;
  return allBeyondPlane(t, u, margin) || allBeyondPlane(u, t, margin);
}

}  // namespace kaboum::geometry
