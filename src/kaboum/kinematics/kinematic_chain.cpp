#include "kaboum/kinematics/kinematic_chain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kaboum/core/error.hpp"

namespace kaboum::kinematics {

KinematicChain::KinematicChain(const RobotModel& model, const std::string& tipLink,
                               const std::string& baseLink) {
  const auto linkNamed = [&](const std::string& name) {
    const auto found = model.findLink(name);
    if (!found) throw InputError(locate(model.name(), "no link named '" + name + "'"));
    return *found;
  };
  const int tip = tipLink.empty() ? model.defaultTip() : linkNamed(tipLink);
  const int base = baseLink.empty() ? 0 : linkNamed(baseLink);
  tipName_ = model.links()[static_cast<std::size_t>(tip)].name;
  std::vector<const Joint*> path;
  for (int link = tip; link != base;) {
    if (model.links()[static_cast<std::size_t>(link)].parentJoint < 0) {
      throw InputError(
          locate(model.name(),
                 "link '" + baseLink + "' is not on the path from the root to '" + tipName_ + "'"));
    }
    const Joint& joint = model.joints()[static_cast<std::size_t>(
        model.links()[static_cast<std::size_t>(link)].parentJoint)];
    path.push_back(&joint);
    link = joint.parentLink;
  }
  std::reverse(path.begin(), path.end());
  Pose pending = Pose::Identity();
  for (const Joint* joint : path) {
    if (!joint->movable()) {
      pending = pending * joint->origin;
      continue;
    }
    Joint merged = *joint;
    merged.origin = pending * joint->origin;
    merged.variable = static_cast<int>(joints_.size());
    joints_.push_back(merged);
    pending = Pose::Identity();
  }
  tipOffset_ = pending;
}

bool KinematicChain::withinLimits(std::span<const double> q, double tolerance) const {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    if (q[i] < joints_[i].lower - tolerance || q[i] > joints_[i].upper + tolerance) return false;
  }
  return true;
}

void KinematicChain::keepWithinLimits(std::span<double> q) const {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    q[i] = joints_[i].type == JointType::Continuous
               ? std::remainder(q[i], 2 * std::numbers::pi)
               : std::clamp(q[i], joints_[i].lower, joints_[i].upper);
  }
}

Pose KinematicChain::toolPose(std::span<const double> q) const {
  Pose pose = Pose::Identity();
  for (std::size_t i = 0; i < joints_.size(); ++i) pose = pose * joints_[i].transform(q[i]);
  return pose * tipOffset_;
}

Pose KinematicChain::toolPoseAndJacobian(std::span<const double> q, Jacobian& jacobian) const {
  // Forward pass storing each joint's world axis and origin in the Jacobian columns, then the
  // linear part ω × (p_tool − p_joint) once the tool position is known.
  Pose pose = Pose::Identity();
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const Joint& joint = joints_[i];
    pose = pose * joint.origin;
    const Eigen::Vector3d axis = pose.linear() * joint.axis;
    const auto column = static_cast<Eigen::Index>(i);
    if (joint.type == JointType::Prismatic) {
      jacobian.col(column).head<3>() = axis;
      jacobian.col(column).tail<3>().setZero();
      pose = pose * Eigen::Translation3d(q[i] * joint.axis);
    } else {
      jacobian.col(column).head<3>() = pose.translation();  // joint origin, finished below
      jacobian.col(column).tail<3>() = axis;
      pose = pose * Eigen::AngleAxisd(q[i], joint.axis);
    }
  }
  pose = pose * tipOffset_;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    if (joints_[i].type == JointType::Prismatic) continue;
    const auto column = static_cast<Eigen::Index>(i);
    const Eigen::Vector3d lever = pose.translation() - jacobian.col(column).head<3>();
    jacobian.col(column).head<3>() = jacobian.col(column).tail<3>().cross(lever);
  }
  return pose;
}

}  // namespace kaboum::kinematics
