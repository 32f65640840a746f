#include "kaboum/kinematics/robot_model.hpp"

#include <deque>
#include <stdexcept>

namespace kaboum::kinematics {

Pose Joint::transform(double value) const {
  switch (type) {
    case JointType::Revolute:
    case JointType::Continuous:
      return origin * Eigen::AngleAxisd(value, axis);
    case JointType::Prismatic:
      return origin * Eigen::Translation3d(value * axis);
    case JointType::Fixed:
      break;
  }
  return origin;
}

RobotModel::RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints)
    : name_(std::move(name)) {
  // Sort links breadth-first from the root and joints by their child link, so that forward
  // kinematics is a single parent-first pass.
  std::vector<std::vector<int>> childJoints(links.size());
  std::vector<int> parentOf(links.size(), -1);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const auto& joint = joints[j];
    if (joint.parentLink < 0 || joint.childLink < 0 ||
        joint.parentLink >= static_cast<int>(links.size()) ||
        joint.childLink >= static_cast<int>(links.size())) {
      throw std::invalid_argument("joint " + joint.name + " refers to a missing link");
    }
    if (parentOf[static_cast<std::size_t>(joint.childLink)] >= 0) {
      throw std::invalid_argument("link " + links[static_cast<std::size_t>(joint.childLink)].name +
                                  " has two parent joints (kinematic loop)");
    }
    parentOf[static_cast<std::size_t>(joint.childLink)] = static_cast<int>(j);
    childJoints[static_cast<std::size_t>(joint.parentLink)].push_back(static_cast<int>(j));
  }
  int root = -1;
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (parentOf[l] >= 0) continue;
    if (root >= 0) {
      throw std::invalid_argument("links " + links[static_cast<std::size_t>(root)].name + " and " +
                                  links[l].name + " both have no parent joint");
    }
    root = static_cast<int>(l);
  }
  if (root < 0) throw std::invalid_argument("no root link: the joints form a kinematic loop");

  std::vector<int> newLinkIndex(links.size(), -1);
  std::deque<int> queue{root};
  newLinkIndex[static_cast<std::size_t>(root)] = 0;
  links_.push_back(links[static_cast<std::size_t>(root)]);
  links_.back().parentJoint = -1;
  while (!queue.empty()) {
    const int link = queue.front();
    queue.pop_front();
    for (int j : childJoints[static_cast<std::size_t>(link)]) {
      Joint joint = joints[static_cast<std::size_t>(j)];
      const auto child = static_cast<std::size_t>(joint.childLink);
      newLinkIndex[child] = static_cast<int>(links_.size());
      joint.parentLink = newLinkIndex[static_cast<std::size_t>(link)];
      joint.childLink = newLinkIndex[child];
      joint.variable = joint.movable() ? static_cast<int>(variableJoints_.size()) : -1;
      if (joint.movable()) variableJoints_.push_back(static_cast<int>(joints_.size()));
      links_.push_back(links[child]);
      links_.back().parentJoint = static_cast<int>(joints_.size());
      joints_.push_back(std::move(joint));
      queue.push_back(static_cast<int>(child));
    }
  }
  if (links_.size() != links.size()) {
    throw std::invalid_argument("some links are not connected to the root (kinematic loop)");
  }
}

std::optional<int> RobotModel::findLink(const std::string& name) const {
  for (std::size_t l = 0; l < links_.size(); ++l) {
    if (links_[l].name == name) return static_cast<int>(l);
  }
  return std::nullopt;
}

int RobotModel::defaultTip() const {
  int link = 0;
  for (;;) {
    int onlyChild = -1;
    int children = 0;
    for (const auto& joint : joints_) {
      if (joint.parentLink == link) {
        ++children;
        onlyChild = joint.childLink;
      }
    }
    if (children != 1) return link;
    link = onlyChild;
  }
}

void RobotModel::linkPoses(std::span<const double> q, std::span<Pose> poses) const {
  poses[0] = Pose::Identity();
  for (const auto& joint : joints_) {
    const double value = joint.variable >= 0 ? q[static_cast<std::size_t>(joint.variable)] : 0.0;
    poses[static_cast<std::size_t>(joint.childLink)] =
        poses[static_cast<std::size_t>(joint.parentLink)] * joint.transform(value);
  }
}

}  // namespace kaboum::kinematics
