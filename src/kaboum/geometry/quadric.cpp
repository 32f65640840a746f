#include "kaboum/geometry/quadric.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace kaboum::geometry {

Quadric Quadric::plane(const Vec3& normal, const Vec3& point) {
  const double d = normal.dot(point);
  Quadric q;
  q.a = normal * normal.transpose();
  q.b = -d * normal;
  q.c = d * d;
  return q;
}

Quadric Quadric::point(const Vec3& point) {
  Quadric q;
  q.a = Eigen::Matrix3d::Identity();
  q.b = -point;
  q.c = point.squaredNorm();
  return q;
}

Quadric Quadric::centredAt(const Vec3& origin) const {
  Quadric q;
  q.a = a;
  q.b = a * origin + b;
  q.c = (*this)(origin);
  return q;
}

Vec3 Quadric::minimizer(const Vec3& reference) const {
  // Solve A (reference + z) = -b for the least-norm z: the gradient at the reference is 2(A r + b).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a);
  const Vec3& values = eig.eigenvalues();
  const double cutoff = 1e-10 * std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  const Vec3 rhs = eig.eigenvectors().transpose() * (-(a * reference + b));
  Vec3 y = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (values[i] > cutoff) y[i] = rhs[i] / values[i];
  }
  return reference + eig.eigenvectors() * y;
}

namespace {

// Q1 + Q2 with the constant lowered so that Q(m) = min(Q1(m), Q2(m)) at m = argmin(Q1 + Q2). Since
// Q ≥ Q(m) = min(...) at its own minimum and Q curves at least as much as either, Q ≽ min(Q1, Q2).
Quadric mergeConstant(const Quadric& q1, const Quadric& q2, const Vec3& reference) {
  Quadric q = q1 + q2;
  const Vec3 m = q.minimizer(reference);
  q.c -= std::max(q1(m), q2(m));
  return q;
}

// Bounds Q1 and Q2 from above by one quadric that is diagonal in the factorized frame of Q1 + Q2
// (Appendix A.1.2). Eq. 4.6 as printed (√(s11² + s12²)) is not an upper bound (s = [1 1; 1 1],
// x = (1, 1) gives 4 > 2√2), so off-diagonal terms are bounded by |2 sij xi xj| ≤ |sij|(xi² + xj²)
// instead. Linear terms use Eq. 4.7: t·x ≤ |t|/(2l) x² + |t| l / 2.
Quadric mergeFull(const Quadric& q1, const Quadric& q2, const Vec3& reference, double l) {
  const Quadric sum = q1 + q2;
  const Vec3 origin = sum.minimizer(reference);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sum.a);
  const Eigen::Matrix3d& v = eig.eigenvectors();  // frame axes as columns

  Vec3 diagonal = Vec3::Zero();
  double constant = 0.0;
  for (const Quadric* qi : {&q1, &q2}) {
    // Express qi in the frame: x = origin + V y.
    const Quadric local = qi->centredAt(origin);
    const Eigen::Matrix3d s = v.transpose() * local.a * v;
    const Vec3 t = 2.0 * (v.transpose() * local.b);
    Vec3 bound;
    for (int i = 0; i < 3; ++i) {
      double row = s(i, i);
      for (int j = 0; j < 3; ++j) {
        if (j != i) row += std::abs(s(i, j));
      }
      bound[i] = row + std::abs(t[i]) / (2.0 * l);
    }
    diagonal = diagonal.cwiseMax(bound);
    constant = std::max(constant, local.c + 0.5 * l * t.cwiseAbs().sum());
  }
  // Back to world coordinates: Q(x) = (x - origin)ᵀ V D Vᵀ (x - origin) + constant.
  Quadric q;
  q.a = v * diagonal.asDiagonal() * v.transpose();
  q.b = -(q.a * origin);
  q.c = origin.dot(q.a * origin) + constant;
  return q;
}

}  // namespace

Quadric mergeQuadrics(const Quadric& q1, const Quadric& q2, QuadricMerge mode,
                      const Vec3& reference, double lengthScale) {
  switch (mode) {
    case QuadricMerge::Sum:
      return q1 + q2;
    case QuadricMerge::Constant:
      return mergeConstant(q1, q2, reference);
    case QuadricMerge::Full:
      return mergeFull(q1, q2, reference, lengthScale);
  }
  return q1 + q2;
}

}  // namespace kaboum::geometry
