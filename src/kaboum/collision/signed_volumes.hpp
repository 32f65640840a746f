// The signed-volume distance sub-algorithm of GJK (Montanari, Petrinic & Barbieri 2017), the
// inner step of thesis §4.1's convex–convex query: the face of a simplex closest to the origin.
// Inline and specialised per simplex size, so that the per-instruction-set pair queries
// (placed_pair.cpp) compile it into their loops.
#pragma once

#include <Eigen/Core>
#include <array>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::collision::detail {

// Points of the Minkowski difference a − b and the barycentric weights of the current closest
// point. reduceSimplex() records in `kept` where each remaining point was before compaction.
struct Simplex {
  std::array<Vec3, 4> w;
  std::array<double, 4> lambda{};
  std::array<int, 4> kept{};
  int size = 0;

  [[nodiscard]] bool contains(const Vec3& point) const {
    for (int i = 0; i < size; ++i) {
      if (w[i] == point) return true;
    }
    return false;
  }
};

namespace simplex_faces {

// The closest point of a face of the simplex: the points it keeps (bit i for point i), their
// weights indexed by point, the point itself and its squared norm. Only kept weights are set.
struct Face {
  std::array<double, 4> lambda{};
  unsigned kept = 0;
  Vec3 point = Vec3::Zero();
  double squaredNorm = 0.0;
};

inline bool sameSign(double a, double b) {
  return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0);
}

inline void vertexFace(const Vec3* w, int i, Face& out) {
  out.kept = 1U << i;
  out.lambda[static_cast<std::size_t>(i)] = 1.0;
  out.point = w[i];
  out.squaredNorm = out.point.squaredNorm();
}

// Segment (S1D): the origin's projection parameter along the segment (i0 < i1).
inline void segmentFace(const Vec3* w, int i0, int i1, Face& out) {
  const Vec3 t = w[i1] - w[i0];
  const double tt = t.squaredNorm();
  const double mu = tt > 0.0 ? -w[i0].dot(t) / tt : 0.0;
  if (mu <= 0.0) return vertexFace(w, i0, out);
  if (mu >= 1.0) return vertexFace(w, i1, out);
  out.kept = (1U << i0) | (1U << i1);
  out.lambda[static_cast<std::size_t>(i0)] = 1.0 - mu;
  out.lambda[static_cast<std::size_t>(i1)] = mu;
  // Exactly orthogonal to the segment: a rounding error along it would bias every later lower
  // bound w.v / |v| by about eps |w| / |v| when the distance is tiny.
  const Vec3 point = w[i0] + mu * t;
  out.point = point - t * (point.dot(t) / tt);
  out.squaredNorm = out.point.squaredNorm();
}

// Replaces `best` by `candidate` when it is closer or `best` is still empty (ties keep `best`).
inline void keepCloser(const Face& candidate, Face& best) {
  if (best.kept == 0 || candidate.squaredNorm < best.squaredNorm) best = candidate;
}

inline void closerSegment(const Vec3* w, int i0, int i1, Face& best) {
  Face candidate;
  segmentFace(w, i0, i1, candidate);
  keepCloser(candidate, best);
}

// Triangle (S2D, i0 < i1 < i2): project the origin on the plane, then compare signed areas in
// the coordinate plane where the triangle's projection is largest; edges facing the origin are
// tried otherwise.
inline void triangleFace(const Vec3* w, int i0, int i1, int i2, Face& out) {
  const Vec3& p0 = w[i0];
  const Vec3& p1 = w[i1];
  const Vec3& p2 = w[i2];
  const Vec3 e1 = p1 - p0;
  const Vec3 e2 = p2 - p0;
  const Vec3 n = e1.cross(e2);
  const double nn = n.squaredNorm();
  out.kept = 0;
  // Flat (sine of the angle below 1e-12): only the edges are meaningful.
  if (!(nn > 1e-24 * e1.squaredNorm() * e2.squaredNorm())) {
    closerSegment(w, i0, i1, out);
    closerSegment(w, i0, i2, out);
    closerSegment(w, i1, i2, out);
    return;
  }
  const Vec3 projected = n * (p0.dot(n) / nn);
  const double ax = std::abs(n.x());
  const double ay = std::abs(n.y());
  const double az = std::abs(n.z());
  // The first largest coordinate, as Eigen's maxCoeff.
  const int axis = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
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
    out.kept = (1U << i0) | (1U << i1) | (1U << i2);
    out.lambda[static_cast<std::size_t>(i0)] = c0 / total;
    out.lambda[static_cast<std::size_t>(i1)] = c1 / total;
    out.lambda[static_cast<std::size_t>(i2)] = c2 / total;
    // The projection itself, exactly along the normal (see segmentFace).
    out.point = projected;
    out.squaredNorm = projected.squaredNorm();
    return;
  }
  if (!in0) closerSegment(w, i1, i2, out);
  if (!in1) closerSegment(w, i0, i2, out);
  if (!in2) closerSegment(w, i0, i1, out);
}

inline double determinant(const Vec3& a, const Vec3& b, const Vec3& c) {
  return a.dot(b.cross(c));
}

// Signed volumes of the tetrahedron (w0, w1, w2, w3) with the origin in place of each vertex;
// they sum to the whole volume.
inline std::array<double, 4> signedVolumes(const Vec3& w0, const Vec3& w1, const Vec3& w2,
                                           const Vec3& w3) {
  return {determinant(w1, w2, w3), -determinant(w0, w2, w3), determinant(w0, w1, w3),
          -determinant(w0, w1, w2)};
}

inline bool allShareSign(double total, const std::array<double, 4>& c) {
  return sameSign(total, c[0]) && sameSign(total, c[1]) && sameSign(total, c[2]) &&
         sameSign(total, c[3]);
}

// Tetrahedron (S3D): signed volumes with the origin in place of each vertex; they all share the
// sign of the whole volume exactly when the origin is inside. Returns true then.
inline bool tetrahedronFace(const Vec3* w, Face& out) {
  const std::array<double, 4> c = signedVolumes(w[0], w[1], w[2], w[3]);
  const double total = c[0] + c[1] + c[2] + c[3];
  if (allShareSign(total, c)) {
    out.kept = 0xF;
    for (std::size_t i = 0; i < 4; ++i) out.lambda[i] = c[i] / total;
    out.point = Vec3::Zero();
    out.squaredNorm = 0.0;
    return true;
  }
  out.kept = 0;
  const auto closerTriangle = [&](int i0, int i1, int i2) {
    Face candidate;
    triangleFace(w, i0, i1, i2, candidate);
    keepCloser(candidate, out);
  };
  if (!sameSign(total, c[0])) closerTriangle(1, 2, 3);
  if (!sameSign(total, c[1])) closerTriangle(0, 2, 3);
  if (!sameSign(total, c[2])) closerTriangle(0, 1, 3);
  if (!sameSign(total, c[3])) closerTriangle(0, 1, 2);
  return false;
}

}  // namespace simplex_faces

// Signed-volume distance sub-algorithm: keeps the smallest face of the simplex whose hull holds
// the point closest to the origin, sets its weights and returns that point in `closest`. Returns
// true when the origin lies inside the tetrahedron (the simplex then keeps its 4 points).
inline bool reduceSimplex(Simplex& simplex, Vec3& closest) {
  using namespace simplex_faces;
  Face face;
  bool inside = false;
  switch (simplex.size) {
    case 1:
      vertexFace(simplex.w.data(), 0, face);
      break;
    case 2:
      segmentFace(simplex.w.data(), 0, 1, face);
      break;
    case 3:
      triangleFace(simplex.w.data(), 0, 1, 2, face);
      break;
    default:
      inside = tetrahedronFace(simplex.w.data(), face);
      break;
  }
  // Compact the kept points to the front, in increasing order (in place is safe).
  int size = 0;
  for (unsigned rest = face.kept; rest != 0; rest &= rest - 1) {
    const int from = __builtin_ctz(rest);
    simplex.w[static_cast<std::size_t>(size)] = simplex.w[static_cast<std::size_t>(from)];
    simplex.kept[static_cast<std::size_t>(size)] = from;
    simplex.lambda[static_cast<std::size_t>(size)] = face.lambda[static_cast<std::size_t>(from)];
    ++size;
  }
  simplex.size = size;
  closest = face.point;
  return inside;
}

// Whether the origin lies strictly inside the tetrahedron (w0, w1, w2, w3): the four signed
// volumes with the origin in place of each vertex share the sign of the whole volume.
inline bool originInsideTetrahedron(const Vec3& w0, const Vec3& w1, const Vec3& w2,
                                    const Vec3& w3) {
  const std::array<double, 4> c = simplex_faces::signedVolumes(w0, w1, w2, w3);
  return simplex_faces::allShareSign(c[0] + c[1] + c[2] + c[3], c);
}

}  // namespace kaboum::collision::detail
