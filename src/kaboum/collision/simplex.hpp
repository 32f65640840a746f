// GJK's simplex and its distance sub-algorithm (thesis §4.1: the convex–convex query): signed
// volumes (Montanari, Petrinic & Barbieri, ACM TOG 2017) find the face of the simplex closest to
// the origin.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::collision::detail {

// Nothing kept per simplex point (boolean queries).
struct NoOrigin {};

// Points of the Minkowski difference a − b, the barycentric weights of the current closest point
// and, per point, where it came from (`Origin`: what the witness points are formed from).
template <class Origin>
struct Simplex {
  std::array<Vec3, 4> w;
  std::array<double, 4> lambda{};
  std::array<Origin, 4> origin{};
  int size = 0;

  // Without branches per point (the answer is almost always false).
  [[nodiscard]] bool contains(const Vec3& point) const {
    bool found = false;
    for (int i = 0; i < size; ++i) {
      found |= (w[i].x() == point.x()) & (w[i].y() == point.y()) & (w[i].z() == point.z());
    }
    return found;
  }
};

// The closest point of one face of the simplex: the points it keeps (bit i for point i), their
// weights (indexed by point; only kept ones are set), the point and its squared norm.
struct SimplexFace {
  std::array<double, 4> lambda{};
  unsigned kept = 0;
  Vec3 point = Vec3::Zero();
  double squaredNorm = std::numeric_limits<double>::infinity();
};

// The face of the simplex (w[0], …, w[size − 1]) closest to the origin, by signed volumes.
// Returns true when the origin lies inside the tetrahedron (size 4; the face is then all of it).
// Out of line: one compact copy serves every pair query (inlined into the per-instruction-set
// builds it made them larger and slower, see docs/benchmarks.md).
bool closestFace(const Vec3* w, int size, SimplexFace& face);

// Signed-volume sub-algorithm: keeps the smallest face of the simplex whose hull holds the point
// closest to the origin (compacted to the front, in order), sets its weights and returns that
// point in `closest`. Returns true when the origin lies inside the tetrahedron (the simplex then
// keeps its 4 points).
template <class Origin>
bool reduceSimplex(Simplex<Origin>& simplex, Vec3& closest) {
  SimplexFace face;
  const bool inside = closestFace(simplex.w.data(), simplex.size, face);
  // In place and without branches: slot `size` is overwritten until a kept point fills it.
  int size = 0;
  for (int i = 0; i < simplex.size; ++i) {
    simplex.w[size] = simplex.w[i];
    simplex.origin[size] = simplex.origin[i];
    simplex.lambda[size] = face.lambda[i];
    size += static_cast<int>((face.kept >> i) & 1U);
  }
  simplex.size = size;
  closest = face.point;
  return inside;
}

// Whether the origin lies strictly inside the tetrahedron (w0, w1, w2, w3): the four signed
// volumes with the origin in place of each vertex share the sign of the whole volume.
bool originInsideTetrahedron(const Vec3& w0, const Vec3& w1, const Vec3& w2, const Vec3& w3);

}  // namespace kaboum::collision::detail
