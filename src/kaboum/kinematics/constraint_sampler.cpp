#include "kaboum/kinematics/constraint_sampler.hpp"

#include <algorithm>

#include "kaboum/kinematics/random_configuration.hpp"

namespace kaboum::kinematics {

ConstraintSampler::ConstraintSampler(const ConstraintProblem& problem,
                                     ConstraintSamplerOptions options)
    : problem_(&problem),
      options_(options),
      rng_(options.seed),
      cost_(problem.costDimension()),
      step_(problem.dof()),
      jacobian_(problem.costDimension(), problem.dof()),
      svd_(problem.costDimension(), problem.dof(), Eigen::ComputeThinU | Eigen::ComputeThinV) {}

void ConstraintSampler::keepWithinLimits(std::span<double> q) const {
  for (int r = 0; r < problem_->robotCount(); ++r) {
    const KinematicChain& chain = problem_->chain(r);
    chain.keepWithinLimits(q.subspan(static_cast<std::size_t>(problem_->firstVariable(r)),
                                     static_cast<std::size_t>(chain.dof())));
  }
}

bool ConstraintSampler::holdJointsAtLimits(std::span<const double> q) {
  bool changed = false;
  for (int r = 0; r < problem_->robotCount(); ++r) {
    const KinematicChain& chain = problem_->chain(r);
    for (int i = 0; i < chain.dof(); ++i) {
      const int column = problem_->firstVariable(r) + i;
      const double value = q[static_cast<std::size_t>(column)];
      const bool pushedOut = (value <= chain.lower(i) && step_[column] > 0) ||
                             (value >= chain.upper(i) && step_[column] < 0);
      if (pushedOut && chain.joint(i).type != JointType::Continuous &&
          !jacobian_.col(column).isZero(0)) {
        jacobian_.col(column).setZero();
        changed = true;
      }
    }
  }
  return changed;
}

bool ConstraintSampler::project(std::span<double> q) {
  keepWithinLimits(q);
  for (lastIterations_ = 0; lastIterations_ <= options_.maxIterations; ++lastIterations_) {
    problem_->evaluate(q, cost_, jacobian_, options_.jacobian);
    lastCostNorm_ = cost_.norm();
    if (lastCostNorm_ <= options_.tolerance) return true;
    if (lastIterations_ == options_.maxIterations) break;
    // Gauss–Newton step with the pseudo-inverse (rank-deficient J allowed). A joint at a limit
    // that the step pushes outwards is held there (its column removed) and the step recomputed,
    // so projections slide along the limits instead of sticking to them.
    for (int held = 0;; ++held) {
      svd_.compute(jacobian_);
      svd_.setThreshold(1e-10);
      step_ = svd_.solve(cost_);
      if (held == problem_->dof() || !holdJointsAtLimits(q)) break;
    }
    const double largest = step_.cwiseAbs().maxCoeff();
    if (!(largest > 1e-12)) break;  // stationary outside the manifold: a local minimum
    if (largest > options_.maxStep) step_ *= options_.maxStep / largest;
    for (std::size_t i = 0; i < q.size(); ++i) q[i] -= step_[static_cast<Eigen::Index>(i)];
    keepWithinLimits(q);
  }
  return false;
}

bool ConstraintSampler::sample(std::span<double> q) {
  for (lastAttempts_ = 1; lastAttempts_ <= options_.maxAttempts; ++lastAttempts_) {
    for (int r = 0; r < problem_->robotCount(); ++r) {
      const KinematicChain& chain = problem_->chain(r);
      randomConfiguration(chain, rng_,
                          q.subspan(static_cast<std::size_t>(problem_->firstVariable(r)),
                                    static_cast<std::size_t>(chain.dof())));
    }
    if (project(q)) return true;
  }
  lastAttempts_ = options_.maxAttempts;
  return false;
}

}  // namespace kaboum::kinematics
