#include "kaboum/collision/simplex.hpp"

namespace kaboum::collision::detail {
namespace {

// Both strictly positive or both strictly negative (without branches: the signs are data).
bool sameSign(double a, double b) {
  return ((a > 0.0) & (b > 0.0)) | ((a < 0.0) & (b < 0.0));
}

// Where the closest point of a face replaces `best`: always (kAlways: a fresh face, written even
// when its norm is not a number) or only when it is closer; ties keep `best`.
template <bool kAlways>
bool replaces(double squaredNorm, const SimplexFace& best) {
  return kAlways || squaredNorm < best.squaredNorm;
}

template <bool kAlways>
void vertex(const Vec3* w, int i, SimplexFace& best) {
  const double squaredNorm = w[i].squaredNorm();
  if (!replaces<kAlways>(squaredNorm, best)) return;
  best.kept = 1U << i;
  best.lambda[i] = 1.0;
  best.point = w[i];
  best.squaredNorm = squaredNorm;
}

// Segment (S1D): the origin's projection parameter along the segment.
template <bool kAlways>
void segment(const Vec3* w, int i0, int i1, SimplexFace& best) {
  const Vec3 t = w[i1] - w[i0];
  const double tt = t.squaredNorm();
  const double along = -w[i0].dot(t);
  if (!(along > 0.0)) return vertex<kAlways>(w, i0, best);  // also a zero-length segment
  if (along >= tt) return vertex<kAlways>(w, i1, best);
  const double inverse = 1.0 / tt;
  const double mu = along * inverse;
  // Exactly orthogonal to the segment: a rounding error along it would bias every later lower
  // bound w.v / |v| by about eps |w| / |v| when the distance is tiny.
  const Vec3 onSegment = w[i0] + mu * t;
  const Vec3 point = onSegment - t * (onSegment.dot(t) * inverse);
  const double squaredNorm = point.squaredNorm();
  if (!replaces<kAlways>(squaredNorm, best)) return;
  best.kept = (1U << i0) | (1U << i1);
  best.lambda[i0] = 1.0 - mu;
  best.lambda[i1] = mu;
  best.point = point;
  best.squaredNorm = squaredNorm;
}

// Triangle (S2D): project the origin on the plane, then compare signed areas in the coordinate
// plane where the triangle's projection is largest; edges facing the origin are tried otherwise
// (each only where closer than `best` so far).
template <bool kAlways>
void triangle(const Vec3* w, int i0, int i1, int i2, SimplexFace& best) {
  const Vec3& p0 = w[i0];
  const Vec3& p1 = w[i1];
  const Vec3& p2 = w[i2];
  const Vec3 e1 = p1 - p0;
  const Vec3 e2 = p2 - p0;
  const Vec3 n = e1.cross(e2);
  const double nn = n.squaredNorm();
  // Flat (sine of the angle below 1e-12): only the edges are meaningful.
  if (!(nn > 1e-24 * e1.squaredNorm() * e2.squaredNorm())) {
    segment<false>(w, i0, i1, best);
    segment<false>(w, i0, i2, best);
    segment<false>(w, i1, i2, best);
    return;
  }
  const Vec3 projected = n * (p0.dot(n) / nn);
  // The axis of the largest normal component (the first one on ties).
  const double ax = std::abs(n.x());
  const double ay = std::abs(n.y());
  const double az = std::abs(n.z());
  const int axis = (ax >= ay) & (ax >= az) ? 0 : (ay >= az ? 1 : 2);
  const int j = axis == 2 ? 0 : axis + 1;
  const int k = axis == 0 ? 2 : axis - 1;
  const auto area = [j, k](const Vec3& a, const Vec3& b, const Vec3& c) {
    return (b[j] - a[j]) * (c[k] - a[k]) - (b[k] - a[k]) * (c[j] - a[j]);
  };
  const double c0 = area(projected, p1, p2);
  const double c1 = area(p0, projected, p2);
  const double c2 = area(p0, p1, projected);
  const double total = n[axis];
  const bool in0 = sameSign(total, c0);
  const bool in1 = sameSign(total, c1);
  const bool in2 = sameSign(total, c2);
  if (in0 && in1 && in2) {
    // The projection itself, exactly along the normal (see segment()).
    const double squaredNorm = projected.squaredNorm();
    if (!replaces<kAlways>(squaredNorm, best)) return;
    const double inverse = 1.0 / total;
    best.kept = (1U << i0) | (1U << i1) | (1U << i2);
    best.lambda[i0] = c0 * inverse;
    best.lambda[i1] = c1 * inverse;
    best.lambda[i2] = c2 * inverse;
    best.point = projected;
    best.squaredNorm = squaredNorm;
    return;
  }
  if (!in0) segment<false>(w, i1, i2, best);
  if (!in1) segment<false>(w, i0, i2, best);
  if (!in2) segment<false>(w, i0, i1, best);
}

// Signed volumes of the tetrahedron (w0, w1, w2, w3) with the origin in place of each vertex;
// they sum to the whole volume (six times it).
std::array<double, 4> signedVolumes(const Vec3& w0, const Vec3& w1, const Vec3& w2,
                                    const Vec3& w3) {
  const Vec3 c23 = w2.cross(w3);
  return {w1.dot(c23), -w0.dot(c23), w0.dot(w1.cross(w3)), -w0.dot(w1.cross(w2))};
}

// Tetrahedron (S3D): the origin is inside exactly when all signed volumes share the sign of the
// whole volume; returns true then. Otherwise the faces whose volume disagrees are tried.
bool tetrahedron(const Vec3* w, SimplexFace& out) {
  const std::array<double, 4> c = signedVolumes(w[0], w[1], w[2], w[3]);
  const double total = c[0] + c[1] + c[2] + c[3];
  const bool in0 = sameSign(total, c[0]);
  const bool in1 = sameSign(total, c[1]);
  const bool in2 = sameSign(total, c[2]);
  const bool in3 = sameSign(total, c[3]);
  if (in0 && in1 && in2 && in3) {
    const double inverse = 1.0 / total;
    out.kept = 0xF;
    for (int i = 0; i < 4; ++i) out.lambda[i] = c[i] * inverse;
    out.point = Vec3::Zero();
    out.squaredNorm = 0.0;
    return true;
  }
  if (!in0) triangle<false>(w, 1, 2, 3, out);
  if (!in1) triangle<false>(w, 0, 2, 3, out);
  if (!in2) triangle<false>(w, 0, 1, 3, out);
  if (!in3) triangle<false>(w, 0, 1, 2, out);
  return false;
}

}  // namespace

bool closestFace(const Vec3* w, int size, SimplexFace& face) {
  switch (size) {
    case 1:
      vertex<true>(w, 0, face);
      return false;
    case 2:
      segment<true>(w, 0, 1, face);
      return false;
    case 3:
      triangle<true>(w, 0, 1, 2, face);
      return false;
    default:
      return tetrahedron(w, face);
  }
}

bool originInsideTetrahedron(const Vec3& w0, const Vec3& w1, const Vec3& w2, const Vec3& w3) {
  const std::array<double, 4> c = signedVolumes(w0, w1, w2, w3);
  const double total = c[0] + c[1] + c[2] + c[3];
  return sameSign(total, c[0]) && sameSign(total, c[1]) && sameSign(total, c[2]) &&
         sameSign(total, c[3]);
}

}  // namespace kaboum::collision::detail
