#include "kaboum/geometry/bounded_contraction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace kaboum::geometry {
namespace {

constexpr double kParallel = 1e-10;  // squared sine below which two planes count as parallel

// Minimizer of q on the affine subspace where the listed half-spaces hold with equality, by the
// direct subspace substitution x = A y + b of Eq. 4.12–4.14. nullopt for a degenerate subset.
std::optional<Vec3> solveOnSubspace(const Quadric& q, std::span<const HalfSpace* const> active) {
  const auto gradientAt = [&](const Vec3& x) -> Vec3 { return q.a * x + q.b; };
  switch (active.size()) {
    case 0: {  // Eq. 4.15: unconstrained, A x = -b; rows of A⁻¹ are the column cross products /
               // det.
      const Eigen::Matrix3d& a = q.a;
      const Vec3 c0 = a.col(1).cross(a.col(2));
      const double det = a.col(0).dot(c0);
      if (!(det > 0.0)) return std::nullopt;
      const Vec3 c1 = a.col(2).cross(a.col(0));
      const Vec3 c2 = a.col(0).cross(a.col(1));
      return Vec3(-c0.dot(q.b) / det, -c1.dot(q.b) / det, -c2.dot(q.b) / det);
    }
    case 1: {  // Eq. 4.16: a plane spanned by two tangents.
      const Vec3& n = active[0]->normal;
      const Vec3 axis = std::abs(n.x()) < std::abs(n.y())
                            ? (std::abs(n.x()) < std::abs(n.z()) ? Vec3::UnitX() : Vec3::UnitZ())
                            : (std::abs(n.y()) < std::abs(n.z()) ? Vec3::UnitY() : Vec3::UnitZ());
      const Vec3 u = axis.cross(n).normalized();
      const Vec3 w = n.cross(u);
      const Vec3 b = active[0]->offset * n;
      const Vec3 g = gradientAt(b);
      const Vec3 au = q.a * u;
      const Vec3 aw = q.a * w;
      const double h00 = u.dot(au), h01 = u.dot(aw), h11 = w.dot(aw);
      const double det = h00 * h11 - h01 * h01;
      if (!(det > 0.0)) return std::nullopt;
      const double g0 = u.dot(g), g1 = w.dot(g);
      const double y0 = (-g0 * h11 + g1 * h01) / det;
      const double y1 = (-g1 * h00 + g0 * h01) / det;
      return Vec3(b + y0 * u + y1 * w);
    }
    case 2: {  // Eq. 4.17: the intersection line of two planes.
      const Vec3& n1 = active[0]->normal;
      const Vec3& n2 = active[1]->normal;
      const Vec3 t = n1.cross(n2);
      const double sin2 = t.squaredNorm();
      if (sin2 < kParallel) return std::nullopt;
      // Point of the line nearest the origin: x = α n1 + β n2 with nᵢ·x = dᵢ.
      const double c = n1.dot(n2);
      const double d1 = active[0]->offset, d2 = active[1]->offset;
      const double alpha = (d1 - c * d2) / sin2;
      const double beta = (d2 - c * d1) / sin2;
      const Vec3 b = alpha * n1 + beta * n2;
      const double curvature = t.dot(q.a * t);
      if (!(curvature > 0.0)) return std::nullopt;
      return Vec3(b - (t.dot(gradientAt(b)) / curvature) * t);
    }
    case 3: {  // Eq. 4.18: the common point of three planes.
      const Vec3& n1 = active[0]->normal;
      const Vec3& n2 = active[1]->normal;
      const Vec3& n3 = active[2]->normal;
      const Vec3 c23 = n2.cross(n3);
      const double det = n1.dot(c23);
      if (std::abs(det) < 1e-7) return std::nullopt;
      return Vec3((active[0]->offset * c23 + active[1]->offset * n3.cross(n1) +
                   active[2]->offset * n1.cross(n2)) /
                  det);
    }
    default:
      return std::nullopt;
  }
}

bool satisfiesAll(const Vec3& x, std::span<const HalfSpace> halfSpaces, double tolerance) {
  for (const HalfSpace& h : halfSpaces) {
    if (h.signedDistance(x) < -tolerance) return false;
  }
  return true;
}

// Keeps the cheapest candidate offered.
struct Best {
  ContractionPoint point;
  void offer(const Quadric& q, const Vec3& x) {
    const double cost = q(x);
    if (!point.feasible || cost < point.cost) point = {true, x, cost};
  }
};

}  // namespace

std::optional<Vec3> unconstrainedMinimizer(const Quadric& q) {
  return solveOnSubspace(q, {});
}

double dualMinimumBound(const Quadric& q, const Vec3& minimizer, double minimum,
                        std::span<const HalfSpace> halfSpaces, double tolerance,
                        double curvatureFloor) {
  const std::size_t k = std::min<std::size_t>(halfSpaces.size(), 3);
  // A⁻¹ = adj(A) / det, with the rows of adj(A) the cross products of A's columns.
  const Eigen::Matrix3d& a = q.a;
  const Vec3 c0 = a.col(1).cross(a.col(2)), c1 = a.col(2).cross(a.col(0)),
             c2 = a.col(0).cross(a.col(1));
  const double det = a.col(0).dot(c0);
  if (!(det > 0.0) || k == 0) return minimum;
  std::array<Vec3, 3> inverseNormals;  // A⁻¹ nᵢ
  std::array<double, 3> s{};           // violation of each relaxed half-space at the minimizer
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& n = halfSpaces[i].normal;
    inverseNormals[i] = Vec3(c0.dot(n), c1.dot(n), c2.dot(n)) / det;
    s[i] = -halfSpaces[i].signedDistance(minimizer) - tolerance;
  }
  std::array<std::array<double, 3>, 3> g{};  // G = NᵀA⁻¹N
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i; j < k; ++j) {
      g[i][j] = g[j][i] = halfSpaces[i].normal.dot(inverseNormals[j]);
    }
  }
  // Each subset S offers λ = 2 G_S⁻¹ s_S (zero outside S) when every multiplier is non-negative,
  // with dual value ½ λ·s; the optimal subset's is the minimum. A⁻¹ may be inaccurate for a nearly
  // singular A, so the best offer's value is then certified without G: with y = ½ A⁻¹Nλ as computed
  // and r = 2Ay - Nλ its residual, min_y L(y, λ) ≥ L(y, λ) - |r|² / (4 curvatureFloor), a lower
  // bound whatever the error in y.
  Vec3 bestLambda = Vec3::Zero();
  double bestValue = 0.0;
  const auto offer = [&](const Vec3& lambda) {
    if ((lambda.array() < 0.0).any()) return;
    const double value = 0.5 * (lambda[0] * s[0] + lambda[1] * s[1] + lambda[2] * s[2]);
    if (value > bestValue) {
      bestValue = value;
      bestLambda = lambda;
    }
  };
  for (std::size_t i = 0; i < k; ++i) {  // one half-space
    if (!(g[i][i] > 0.0)) continue;
    Vec3 lambda = Vec3::Zero();
    lambda[static_cast<Eigen::Index>(i)] = 2.0 * s[i] / g[i][i];
    offer(lambda);
  }
  for (std::size_t i = 0; i < k; ++i) {  // two half-spaces: a 2×2 system
    for (std::size_t j = i + 1; j < k; ++j) {
      const double d = g[i][i] * g[j][j] - g[i][j] * g[i][j];
      if (!(d > 0.0)) continue;
      Vec3 lambda = Vec3::Zero();
      lambda[static_cast<Eigen::Index>(i)] = 2.0 * (g[j][j] * s[i] - g[i][j] * s[j]) / d;
      lambda[static_cast<Eigen::Index>(j)] = 2.0 * (g[i][i] * s[j] - g[i][j] * s[i]) / d;
      offer(lambda);
    }
  }
  if (k == 3) {  // all three: Cramer's rule
    const Eigen::Matrix3d gm{
        {g[0][0], g[0][1], g[0][2]}, {g[1][0], g[1][1], g[1][2]}, {g[2][0], g[2][1], g[2][2]}};
    const Vec3 sv(s[0], s[1], s[2]);
    const Vec3 r0 = gm.col(1).cross(gm.col(2)), r1 = gm.col(2).cross(gm.col(0)),
               r2 = gm.col(0).cross(gm.col(1));
    const double d = gm.col(0).dot(r0);
    if (d > 0.0) offer(2.0 * Vec3(r0.dot(sv), r1.dot(sv), r2.dot(sv)) / d);
  }
  if (!(bestValue > 0.0)) return minimum;
  Vec3 y = Vec3::Zero(), pull = Vec3::Zero();  // pull = Nλ
  double constant = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const double lambda = bestLambda[static_cast<Eigen::Index>(i)];
    y += (0.5 * lambda) * inverseNormals[i];
    pull += lambda * halfSpaces[i].normal;
    constant += lambda * s[i];
  }
  const Vec3 ay = a * y;
  const Vec3 residual = 2.0 * ay - pull;
  const double lagrangian = y.dot(ay) - pull.dot(y) + constant;
  const double best = std::max(0.0, lagrangian - residual.squaredNorm() / (4.0 * curvatureFloor));
  return minimum + best;
}

ContractionPoint solveContractionExhaustive(const Quadric& q, std::span<const HalfSpace> halfSpaces,
                                            double tolerance) {
  Best best;
  const auto consider = [&](std::span<const HalfSpace* const> subset) {
    if (auto x = solveOnSubspace(q, subset); x && satisfiesAll(*x, halfSpaces, tolerance)) {
      best.offer(q, *x);
    }
  };
  const std::size_t k = halfSpaces.size();
  consider({});
  for (std::size_t i = 0; i < k; ++i) {
    const std::array<const HalfSpace*, 1> one{&halfSpaces[i]};
    consider(one);
    for (std::size_t j = i + 1; j < k; ++j) {
      const std::array<const HalfSpace*, 2> two{&halfSpaces[i], &halfSpaces[j]};
      consider(two);
      for (std::size_t l = j + 1; l < k; ++l) {
        const std::array<const HalfSpace*, 3> three{&halfSpaces[i], &halfSpaces[j], &halfSpaces[l]};
        consider(three);
      }
    }
  }
  return best.point;
}

ContractionPoint solveContraction(const Quadric& q, std::span<const HalfSpace> halfSpaces,
                                  double tolerance) {
  const auto start = unconstrainedMinimizer(q);
  if (!start) return solveContractionExhaustive(q, halfSpaces, tolerance);
  return solveContractionFrom(q, *start, halfSpaces, tolerance);
}

ContractionPoint solveContractionFrom(const Quadric& q, const Vec3& minimizer,
                                      std::span<const HalfSpace> halfSpaces, double tolerance) {
  std::array<const HalfSpace*, 3> active{};
  std::size_t activeCount = 0;
  Vec3 x = minimizer;
  double cost = q(x);

  constexpr int kMaxRounds = 64;
  for (int round = 0; round < kMaxRounds; ++round) {
    const HalfSpace* violated = nullptr;
    double worst = -tolerance;
    for (const HalfSpace& h : halfSpaces) {
      const double s = h.signedDistance(x);
      if (s < worst) {
        worst = s;
        violated = &h;
      }
    }
    if (violated == nullptr) {
      ContractionPoint optimum{true, x, cost};
      optimum.activeCount = static_cast<int>(activeCount);
      for (std::size_t i = 0; i < activeCount; ++i) {
        optimum.active[i] = static_cast<int>(active[i] - halfSpaces.data());
      }
      return optimum;
    }

    // The optimum over active ∪ {violated} has `violated` active (else it would be the current x,
    // which violates it), so only subsets containing it are candidates: {v}, {a,v}, {a,b,v}.
    std::array<const HalfSpace*, 4> pool{};
    for (std::size_t i = 0; i < activeCount; ++i) pool[i] = active[i];
    pool[activeCount] = violated;
    const std::span<const HalfSpace* const> poolSpan(pool.data(), activeCount + 1);
    const auto feasibleForPool = [&](const Vec3& p) {
      for (const HalfSpace* h : poolSpan) {
        if (h->signedDistance(p) < -tolerance) return false;
      }
      return true;
    };

    bool found = false;
    double bestCost = std::numeric_limits<double>::infinity();
    Vec3 bestX;
    std::array<const HalfSpace*, 3> bestSet{};
    std::size_t bestCount = 0;
    const auto tryCandidate = [&](std::span<const HalfSpace* const> subset) {
      const auto p = solveOnSubspace(q, subset);
      if (!p || !feasibleForPool(*p)) return;
      const double c = q(*p);
      if (c < bestCost) {
        found = true;
        bestCost = c;
        bestX = *p;
        bestCount = subset.size();
        for (std::size_t i = 0; i < subset.size(); ++i) bestSet[i] = subset[i];
      }
    };
    const std::array<const HalfSpace*, 1> single{violated};
    tryCandidate(single);
    for (std::size_t i = 0; i < activeCount; ++i) {
      const std::array<const HalfSpace*, 2> pair{active[i], violated};
      tryCandidate(pair);
      for (std::size_t j = i + 1; j < activeCount; ++j) {
        const std::array<const HalfSpace*, 3> triple{active[i], active[j], violated};
        tryCandidate(triple);
      }
    }
    if (!found) return {};  // even this subset of the half-spaces has no common point
    if (bestCost < cost - 1e-12 * (1.0 + std::abs(cost))) break;  // numerical stall: cost must rise
    x = bestX;
    cost = bestCost;
    active = bestSet;
    activeCount = bestCount;
  }
  return solveContractionExhaustive(q, halfSpaces, tolerance);
}

}  // namespace kaboum::geometry
