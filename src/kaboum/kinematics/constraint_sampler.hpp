// Constraint sampling by iterative projection (thesis §5.2, Definition 4, Algorithm 3): a random
// configuration is projected onto the constraint manifold F(q) = 0 by Gauss–Newton steps
// q ← q − J⁺ F(q), within joint limits.
#pragma once

#include <Eigen/SVD>
#include <cstdint>
#include <random>
#include <span>

#include "kaboum/kinematics/constraint_problem.hpp"

namespace kaboum::kinematics {

struct ConstraintSamplerOptions {
  double tolerance = 1e-6;  // ‖F(q)‖ accepted as on the manifold (Algorithm 3's epsilon)
  int maxIterations = 100;  // per projection; then the projection reports failure
  int maxAttempts = 20;     // random starts per sample() call
  double maxStep = 0.5;     // largest joint change per step (scales the Gauss–Newton step)
  JacobianMode jacobian = JacobianMode::Analytic;
  std::uint64_t seed = 1;
};

class ConstraintSampler {
 public:
  ConstraintSampler(const ConstraintProblem& problem, ConstraintSamplerOptions options = {});

  // Algorithm 3 from random starts (up to maxAttempts): writes a configuration with
  // ‖F(q)‖ ≤ tolerance to `q` and returns true, or false when every projection failed.
  bool sample(std::span<double> q);
  // Algorithm 3's loop from the configuration in `q` (clamped into the limits).
  bool project(std::span<double> q);

  [[nodiscard]] int lastIterations() const { return lastIterations_; }
  [[nodiscard]] int lastAttempts() const { return lastAttempts_; }
  [[nodiscard]] double lastCostNorm() const { return lastCostNorm_; }

 private:
  void keepWithinLimits(std::span<double> q) const;
  // Zeroes the Jacobian columns of joints at a limit that step_ pushes outwards; true if any.
  bool holdJointsAtLimits(std::span<const double> q);

  const ConstraintProblem* problem_;
  ConstraintSamplerOptions options_;
  std::mt19937_64 rng_;
  Eigen::VectorXd cost_, step_;
  Eigen::MatrixXd jacobian_;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd_;
  int lastIterations_ = 0;
  int lastAttempts_ = 0;
  double lastCostNorm_ = 0;
};

}  // namespace kaboum::kinematics
