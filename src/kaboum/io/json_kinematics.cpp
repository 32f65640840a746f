#include "kaboum/io/json_kinematics.hpp"

#include <Eigen/Geometry>

namespace kaboum::io {

nlohmann::json toJson(const Pose& pose) {
  const Eigen::Vector3d p = pose.translation();
  const Eigen::Quaterniond r(pose.linear());
  return {{"position", {p.x(), p.y(), p.z()}}, {"quaternion_wxyz", {r.w(), r.x(), r.y(), r.z()}}};
}

nlohmann::json ikSolutionsJson(std::span<const std::vector<double>> solutions) {
  nlohmann::json list = nlohmann::json::array();
  for (const std::vector<double>& q : solutions) list.push_back(q);
  return {{"reachable", !solutions.empty()}, {"solutions", list}};
}

}  // namespace kaboum::io
