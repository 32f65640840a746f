// A serial path through a RobotModel from its root (or a base link) to a tip link: forward
// kinematics of the tool frame FK: Rⁿ → SE(3) and its geometric Jacobian (thesis §3.1, §5.2),
// allocation-free.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::kinematics {

using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// View of an Eigen vector as the joint-value span the kinematics functions take.
inline std::span<const double> asSpan(const Eigen::VectorXd& q) {
  return {q.data(), static_cast<std::size_t>(q.size())};
}

class KinematicChain {
 public:
  // The path from `baseLink` (default: the model root) to `tipLink` (default:
  // RobotModel::defaultTip()); poses are in the base link frame. Throws InputError for an
  // unknown link name or a base that is not an ancestor of the tip.
  explicit KinematicChain(const RobotModel& model, const std::string& tipLink = {},
                          const std::string& baseLink = {});

  [[nodiscard]] int dof() const { return static_cast<int>(joints_.size()); }
  [[nodiscard]] const std::string& tipName() const { return tipName_; }
  [[nodiscard]] const Joint& joint(int i) const { return joints_[static_cast<std::size_t>(i)]; }
  [[nodiscard]] double lower(int i) const { return joint(i).lower; }
  [[nodiscard]] double upper(int i) const { return joint(i).upper; }
  [[nodiscard]] bool withinLimits(std::span<const double> q, double tolerance = 1e-9) const;
  // Moves q into the limits: continuous joints wrap into [−π, π), others are clamped.
  void keepWithinLimits(std::span<double> q) const;

  // Pose of the tip link in the model root frame.
  [[nodiscard]] Pose toolPose(std::span<const double> q) const;
  // Tool pose and the 6×n geometric Jacobian [linear; angular] of the tip origin, both in the
  // root frame. `jacobian` must be sized 6×dof().
  Pose toolPoseAndJacobian(std::span<const double> q, Jacobian& jacobian) const;

 private:
  std::vector<Joint> joints_;          // movable joints, origins absorbing preceding fixed joints
  Pose tipOffset_ = Pose::Identity();  // fixed transform after the last movable joint
  std::string tipName_;
};

}  // namespace kaboum::kinematics
