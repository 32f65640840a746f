// Numeric inverse kinematics for any chain: damped least squares (Levenberg–Marquardt) on the
// pose error with joint limits and seeded random restarts. Used where no closed form fits
// (e.g. the 7-DOF Barrett WAM).
#pragma once

#include <cstdint>
#include <random>
#include <span>

#include "kaboum/kinematics/kinematic_chain.hpp"

namespace kaboum::kinematics {

struct NumericIkOptions {
  int maxIterations = 100;             // per start
  int maxStarts = 50;                  // the initial guess plus random restarts
  double positionTolerance = 1e-6;     // metres
  double orientationTolerance = 1e-6;  // radians
  std::uint64_t seed = 1;
};

class NumericIk {
 public:
  explicit NumericIk(const KinematicChain& chain, NumericIkOptions options = {});

  // Solves FK(q) = target from `initial` (dof() values, or empty for a random start), then random
  // restarts. Writes the solution (within limits) to `solution` and returns true, or false when
  // every start failed. Allocates nothing; restarts draw from the solver's own seeded generator.
  bool solve(const Pose& target, std::span<const double> initial, std::span<double> solution);

  // Starts used by the last solve (1 = the first start succeeded).
  [[nodiscard]] int startsUsed() const { return startsUsed_; }

 private:
  using Twist = Eigen::Matrix<double, 6, 1>;
  Twist poseError(const Pose& target, const Pose& current) const;
  bool descend(const Pose& target, Eigen::VectorXd& q);

  const KinematicChain* chain_;
  NumericIkOptions options_;
  std::mt19937_64 rng_;
  Jacobian jacobian_;
  Eigen::VectorXd q_, trial_, step_;
  int startsUsed_ = 0;
};

}  // namespace kaboum::kinematics
