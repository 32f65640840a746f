// Quadric error metrics (thesis Appendix A.1): Q(x) = xᵀAx + 2bᵀx + c ≥ 0, an upper estimate of a
// squared distance, with the merge operators of §4.3.3 used by the bounding mesh algorithm.
#pragma once

#include <Eigen/Core>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

struct Quadric {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  double c = 0.0;

  // Squared distance to the plane through `point` with unit normal `normal` (Eq. A.5).
  static Quadric plane(const Vec3& normal, const Vec3& point);
  // Squared distance to `point` (Eq. A.3).
  static Quadric point(const Vec3& point);

  [[nodiscard]] double operator()(const Vec3& x) const { return x.dot(a * x + 2.0 * b) + c; }
  Quadric& operator+=(const Quadric& o) {
    a += o.a;
    b += o.b;
    c += o.c;
    return *this;
  }
  friend Quadric operator+(Quadric l, const Quadric& r) { return l += r; }
  friend Quadric operator*(double s, Quadric q) {
    q.a *= s;
    q.b *= s;
    q.c *= s;
    return q;
  }

  // A minimizer (Eq. A.7), solved by eigen-decomposition with small eigenvalues treated as zero, so
  // a singular quadric (plane: rank 1, line: rank 2) yields the minimizer nearest to `reference`.
  [[nodiscard]] Vec3 minimizer(const Vec3& reference) const;
  // The same quadric expressed in coordinates centred at `origin`: Q'(z) = Q(origin + z).
  [[nodiscard]] Quadric centredAt(const Vec3& origin) const;
};

// How the quadric of a contracted vertex is formed from its two parents (§4.3.3).
enum class QuadricMerge {
  Sum,       // Q1 + Q2 (Eq. 4.5), the classic upper estimate
  Constant,  // Q1 + Q2 with the constant lowered until it touches min(Q1, Q2) at its minimizer
  Full,      // diagonal bound of Q1 and Q2 in the factorized frame of Q1 + Q2 (Eq. 4.6–4.7)
};

// Merges the quadrics of the two contracted vertices. `reference` picks the minimizer of singular
// quadrics; `lengthScale` is the free parameter l of Eq. 4.7 (used by QuadricMerge::Full).
Quadric mergeQuadrics(const Quadric& q1, const Quadric& q2, QuadricMerge mode,
                      const Vec3& reference, double lengthScale);

}  // namespace kaboum::geometry
