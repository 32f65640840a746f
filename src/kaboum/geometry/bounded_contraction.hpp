// The bounded edge-contraction point (thesis §4.3.4, Eq. 4.8–4.18, Algorithm 1): minimize a quadric
// subject to the new vertex lying on the kept side of every plane around the contracted edge.
#pragma once

#include <array>
#include <optional>
#include <span>

#include "kaboum/geometry/quadric.hpp"

namespace kaboum::geometry {

// Half-space constraint normal·x - offset ≥ 0, with a unit normal.
struct HalfSpace {
  Vec3 normal;
  double offset;
  [[nodiscard]] double signedDistance(const Vec3& x) const { return normal.dot(x) - offset; }
};

struct ContractionPoint {
  bool feasible = false;  // false: no point satisfies every half-space
  Vec3 position = Vec3::Zero();
  double cost = 0.0;  // q(position)
  // Indices of the half-spaces held as equalities at the optimum, when known (-1 for unused slots;
  // activeCount < 0: unknown). The optimum stays optimal without the other half-spaces.
  std::array<int, 3> active{-1, -1, -1};
  int activeCount = -1;
};

// The unconstrained minimizer of `q` (Eq. 4.15); nullopt unless `q` is positive definite. It is
// where solveContraction starts, so q at it is a lower bound of the constrained minimum.
std::optional<Vec3> unconstrainedMinimizer(const Quadric& q);

// Algorithm 1 as published: enumerate every subset of 0–3 half-spaces held as equalities, solve
// each subspace in closed form (Eq. 4.15–4.18) and keep the cheapest candidate satisfying all
// half-spaces within `tolerance`. O(k³) in the number of half-spaces; the reference the fast solver
// is tested on.
ContractionPoint solveContractionExhaustive(const Quadric& q, std::span<const HalfSpace> halfSpaces,
                                            double tolerance);

// Same optimum, found by constraint generation: start at the unconstrained minimizer, add the most
// violated half-space, re-solve exactly over the (≤3) active ones plus it, repeat. The cost rises
// strictly every round, so it terminates; it falls back to the exhaustive search only if a
// numerical stall is detected. `q` must be positive definite (regularize singular quadrics before
// calling).
ContractionPoint solveContraction(const Quadric& q, std::span<const HalfSpace> halfSpaces,
                                  double tolerance);
// A lower bound of the minimum of `q` over at most three half-spaces, each relaxed by `tolerance`,
// from the Lagrangian dual in closed form: for each subset S of active half-spaces, the
// multipliers λ_S = 2 G_S⁻¹ s_S (s: violations at the unconstrained minimizer, G = NᵀA⁻¹N), kept
// when non-negative. Any λ ≥ 0 gives a lower bound (weak duality) and the optimal subset gives the
// minimum itself, so it bounds solveContraction's cost over any superset of these half-spaces,
// without solving for a point. `curvatureFloor` is a lower bound of A's smallest eigenvalue (A =
// PSD + floor·I); it makes the bound hold even where A⁻¹ is computed inaccurately.
double dualMinimumBound(const Quadric& q, const Vec3& minimizer, double minimum,
                        std::span<const HalfSpace> halfSpaces, double tolerance,
                        double curvatureFloor);

// solveContraction for a caller that already has the unconstrained minimizer of `q`.
ContractionPoint solveContractionFrom(const Quadric& q, const Vec3& minimizer,
                                      std::span<const HalfSpace> halfSpaces, double tolerance);

}  // namespace kaboum::geometry
