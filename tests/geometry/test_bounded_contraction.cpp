#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "kaboum/geometry/bounded_contraction.hpp"

namespace kaboum::geometry {
namespace {

Vec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

// A neighbourhood like a mesh's: planes through points near the origin whose normals point roughly
// "up", and a positive-definite quadric built from them plus a small regularization.
struct Problem {
  Quadric q;
  std::vector<HalfSpace> halfSpaces;
};

Problem randomProblem(std::mt19937_64& rng, int planes, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Problem p;
  for (int i = 0; i < planes; ++i) {
    const Vec3 normal = (Vec3::UnitZ() + spread * randomUnit(rng)).normalized();
    const Vec3 point(u(rng), u(rng), 0.2 * u(rng));
    p.q += Quadric::plane(normal, point);
    p.halfSpaces.push_back({normal, normal.dot(point)});
  }
  p.q.a += 1e-6 * Eigen::Matrix3d::Identity();
  return p;
}

TEST(BoundedContraction, FastSolverMatchesExhaustiveAlgorithm1) {
  std::mt19937_64 rng(7);
  int feasibleCount = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int planes = 1 + trial % 16;
    const double spread = (trial % 5) * 0.4;
    const Problem p = randomProblem(rng, planes, spread);
    const ContractionPoint fast = solveContraction(p.q, p.halfSpaces, 1e-12);
    const ContractionPoint exhaustive = solveContractionExhaustive(p.q, p.halfSpaces, 1e-12);
    ASSERT_EQ(fast.feasible, exhaustive.feasible) << "trial " << trial;
    if (!fast.feasible) continue;
    ++feasibleCount;
    EXPECT_NEAR(fast.cost, exhaustive.cost, 1e-8 * (1.0 + exhaustive.cost)) << "trial " << trial;
    for (const HalfSpace& h : p.halfSpaces) EXPECT_GE(h.signedDistance(fast.position), -1e-9);
  }
  EXPECT_GT(feasibleCount, 2000);  // the generator mostly makes feasible problems
}

// The dual bound over the first (up to three) half-spaces never exceeds the constrained minimum
// over all of them of the model the simplifier compares, minimum + (x - x₀)ᵀA(x - x₀), and with
// three or fewer well-conditioned ones it is that minimum. A third of the quadrics are made of
// planes regularized as weakly as the simplifier does (10⁻⁹ of the trace), where A⁻¹ is inaccurate.
TEST(BoundedContraction, DualBoundIsTheMinimumOverItsHalfSpacesAndBoundsSupersets) {
  std::mt19937_64 rng(11);
  int exactChecks = 0, weakChecks = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    const int planes = 1 + trial % 12;
    Problem p = randomProblem(rng, planes, (trial % 5) * 0.4);
    double floor = 1e-6;
    const bool weak = trial % 3 == 0;
    if (weak) {
      p.q.a -= 1e-6 * Eigen::Matrix3d::Identity();
      floor = 1e-9 * p.q.a.trace();
      p.q.a += floor * Eigen::Matrix3d::Identity();
    }
    const auto start = unconstrainedMinimizer(p.q);
    if (!start) continue;
    const double minimum = p.q(*start);
    const std::span<const HalfSpace> firstThree(p.halfSpaces.data(),
                                                std::min<std::size_t>(3, p.halfSpaces.size()));
    const double bound = dualMinimumBound(p.q, *start, minimum, firstThree, 1e-12, floor);
    const ContractionPoint all = solveContraction(p.q, p.halfSpaces, 1e-12);
    if (!all.feasible) continue;
    const Vec3 step = all.position - *start;
    const double cost = minimum + step.dot(p.q.a * step);
    EXPECT_LE(bound, cost + 1e-9 * (std::abs(minimum) + cost)) << "trial " << trial;
    weakChecks += weak ? 1 : 0;
    if (planes <= 3 && !weak) {
      ++exactChecks;
      EXPECT_NEAR(bound, cost, 1e-7 * (1.0 + cost)) << "trial " << trial;
    }
  }
  EXPECT_GT(exactChecks, 400);
  EXPECT_GT(weakChecks, 1000);
}

TEST(BoundedContraction, InfeasibleWhenHalfSpacesAreDisjoint) {
  // A knife edge for an outer bound: x ≥ 1 and x ≤ 0 cannot both hold.
  const std::vector<HalfSpace> h{{Vec3::UnitX(), 1.0}, {-Vec3::UnitX(), 0.0}};
  const Quadric q = Quadric::point(Vec3::Zero());
  EXPECT_FALSE(solveContraction(q, h, 1e-12).feasible);
  EXPECT_FALSE(solveContractionExhaustive(q, h, 1e-12).feasible);
}

TEST(BoundedContraction, EachSubspaceCaseIsExact) {
  const Quadric q = Quadric::point(Vec3::Zero());  // nearest feasible point to the origin
  // m = 0: the origin itself is feasible.
  std::vector<HalfSpace> h{{Vec3::UnitZ(), -1.0}};
  EXPECT_TRUE(solveContraction(q, h, 0).position.isZero(1e-15));
  // m = 1: project onto z = 1.
  h = {{Vec3::UnitZ(), 1.0}};
  EXPECT_TRUE(solveContraction(q, h, 0).position.isApprox(Vec3(0, 0, 1), 1e-14));
  // m = 2: the line x = 1, z = 1.
  h = {{Vec3::UnitZ(), 1.0}, {Vec3::UnitX(), 1.0}};
  EXPECT_TRUE(solveContraction(q, h, 0).position.isApprox(Vec3(1, 0, 1), 1e-14));
  // m = 3: the corner (1, 1, 1), the cost is its squared distance.
  h = {{Vec3::UnitZ(), 1.0}, {Vec3::UnitX(), 1.0}, {Vec3::UnitY(), 1.0}};
  const ContractionPoint corner = solveContraction(q, h, 0);
  EXPECT_TRUE(corner.position.isApprox(Vec3(1, 1, 1), 1e-14));
  EXPECT_NEAR(corner.cost, 3.0, 1e-14);
}

TEST(BoundedContraction, NearParallelPlanesStayStable) {
  // Neighbouring planes differing by 1e-9 rad: the solution must stay on the feasible side.
  const Quadric q = Quadric::point(Vec3(0, 0, -1));
  std::vector<HalfSpace> h;
  for (int i = 0; i < 6; ++i) {
    const double angle = 1e-9 * i;
    const Vec3 n(std::sin(angle), 0.0, std::cos(angle));
    h.push_back({n, 0.0});
  }
  const ContractionPoint p = solveContraction(q, h, 1e-12);
  ASSERT_TRUE(p.feasible);
  for (const HalfSpace& s : h) EXPECT_GE(s.signedDistance(p.position), -1e-12);
  EXPECT_NEAR(p.cost, 1.0, 1e-6);
}

}  // namespace
}  // namespace kaboum::geometry
