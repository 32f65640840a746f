// A robot's kinematic tree (thesis §3.1, kinematic structures R): links with collision geometry,
// joints with limits, and forward kinematics of every link. Loaded from URDF (urdf_loader.hpp).
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/core/types.hpp"

namespace kaboum::kinematics {

enum class JointType { Fixed, Revolute, Continuous, Prismatic };

// Collision geometry of a link; a mesh stays a resolved file path (mesh reading lives elsewhere).
struct CollisionShape {
  enum class Kind { Box, Cylinder, Sphere, Mesh };
  Kind kind = Kind::Box;
  Pose origin = Pose::Identity();  // in the link frame
  Eigen::Vector3d size{0, 0, 0};   // box extents; mesh scale
  double radius = 0;               // cylinder, sphere
  double length = 0;               // cylinder, along its z axis
  std::string meshPath;            // absolute or relative to the working directory
};

struct Link {
  std::string name;
  int parentJoint = -1;  // index into RobotModel::joints(); -1 for the root
  std::vector<CollisionShape> collisions;
};

// One degree of freedom at most. A URDF planar joint is expanded into x, y and θ joints.
struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parentLink = -1;
  int childLink = -1;
  Pose origin = Pose::Identity();  // child frame at q = 0, in the parent link frame
  Eigen::Vector3d axis{0, 0, 1};   // unit, in the joint frame
  int variable = -1;               // index into the configuration vector; -1 if fixed
  double lower = 0, upper = 0;     // position limits (continuous: ±π)
  double maxVelocity = 0;          // 0 when not given

  [[nodiscard]] bool movable() const { return type != JointType::Fixed; }
  // Transform from the parent link frame to the child link frame at joint position `value`.
  [[nodiscard]] Pose transform(double value) const;
};

class RobotModel {
 public:
  RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints);

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] const std::vector<Link>& links() const { return links_; }
  [[nodiscard]] const std::vector<Joint>& joints() const { return joints_; }
  // Number of configuration variables (movable joints).
  [[nodiscard]] int dof() const { return static_cast<int>(variableJoints_.size()); }
  [[nodiscard]] const Joint& variableJoint(int variable) const {
    return joints_[static_cast<std::size_t>(variableJoints_[static_cast<std::size_t>(variable)])];
  }
  [[nodiscard]] std::optional<int> findLink(const std::string& name) const;
  // The link a single chain ends at when no tip is named: descend from the root while a link
  // has exactly one child joint.
  [[nodiscard]] int defaultTip() const;

  // Poses of all links in the model root frame, in link order; `poses` must have links().size()
  // entries. Joints are stored parent-first, so one pass suffices; allocates nothing.
  void linkPoses(std::span<const double> q, std::span<Pose> poses) const;

 private:
  std::string name_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;  // topologically sorted: a joint's parent link is placed earlier
  std::vector<int> variableJoints_;
};

}  // namespace kaboum::kinematics
