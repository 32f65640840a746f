#include "kaboum/kinematics/numeric_ik.hpp"

#include <algorithm>
#include <stdexcept>

#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::kinematics {

NumericIk::NumericIk(const KinematicChain& chain, NumericIkOptions options)
    : chain_(&chain),
      options_(options),
      rng_(options.seed),
      jacobian_(6, chain.dof()),
      q_(chain.dof()),
      trial_(chain.dof()),
      step_(chain.dof()) {}

NumericIk::Twist NumericIk::poseError(const Pose& target, const Pose& current) const {
  Twist error;
  error.head<3>() = target.translation() - current.translation();
  const Eigen::AngleAxisd turn(target.linear() * current.linear().transpose());
  error.tail<3>() = turn.angle() * turn.axis();
  return error;
}

bool NumericIk::descend(const Pose& target, Eigen::VectorXd& q) {
  // Levenberg–Marquardt: Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e, λ shrinking on success and growing on
  // failure; steps are kept within the joint limits.
  double lambda = 1e-2;
  Pose current = chain_->toolPoseAndJacobian(asSpan(q), jacobian_);
  Twist error = poseError(target, current);
  for (int iteration = 0; iteration < options_.maxIterations; ++iteration) {
    if (error.head<3>().norm() < options_.positionTolerance &&
        error.tail<3>().norm() < options_.orientationTolerance) {
      return true;
    }
    const Eigen::Matrix<double, 6, 6> normal =
        jacobian_.lazyProduct(jacobian_.transpose()) +
        lambda * lambda * Eigen::Matrix<double, 6, 6>::Identity();
    step_.noalias() = jacobian_.transpose() * normal.ldlt().solve(error);
    trial_ = q + step_;
    chain_->keepWithinLimits(std::span(trial_.data(), static_cast<std::size_t>(trial_.size())));
    const Pose next = chain_->toolPose(asSpan(trial_));
    const Twist nextError = poseError(target, next);
    if (nextError.squaredNorm() < error.squaredNorm()) {
      q = trial_;
      chain_->toolPoseAndJacobian(asSpan(q), jacobian_);
      error = nextError;
      lambda = std::max(lambda * 0.5, 1e-6);
    } else {
      lambda *= 4;
      if (lambda > 1e3) return false;  // stuck in a local minimum or at a limit
    }
  }
  return false;
}

bool NumericIk::solve(const Pose& target, std::span<const double> initial,
                      std::span<double> solution) {
  if (!initial.empty() && initial.size() != static_cast<std::size_t>(chain_->dof())) {
    throw std::invalid_argument("NumericIk::solve: initial guess needs one value per joint");
  }
  for (startsUsed_ = 1; startsUsed_ <= options_.maxStarts; ++startsUsed_) {
    if (startsUsed_ == 1 && !initial.empty()) {
      std::copy(initial.begin(), initial.end(), q_.begin());
      chain_->keepWithinLimits(std::span(q_.data(), static_cast<std::size_t>(q_.size())));
    } else {
      randomConfiguration(*chain_, rng_, std::span(q_.data(), static_cast<std::size_t>(q_.size())));
    }
    if (descend(target, q_)) {
      std::copy(q_.begin(), q_.end(), solution.begin());
      return true;
    }
  }
  startsUsed_ = options_.maxStarts;
  return false;
}

}  // namespace kaboum::kinematics
