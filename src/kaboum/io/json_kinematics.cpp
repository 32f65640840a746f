#include "kaboum/io/json_kinematics.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>

#include "kaboum/core/error.hpp"

namespace kaboum::io {

nlohmann::json toJson(const Pose& pose) {
  const Eigen::Vector3d p = pose.translation();
  const Eigen::Quaterniond r(pose.linear());
  return {{"position", {p.x(), p.y(), p.z()}}, {"quaternion_wxyz", {r.w(), r.x(), r.y(), r.z()}}};
}

Pose poseFromJson(const nlohmann::json& value, const std::string& file, const std::string& key) {
  const auto fail = [&](const std::string& at, const std::string& what) {
    throw InputError(locate(file, at + ": " + what));
  };
  const auto numbers = [&](const char* name, std::size_t count) {
    const std::string at = key + "." + name;
    if (!value.is_object()) fail(key, "expected an object");
    if (!value.contains(name)) fail(key, fmt::format("missing key '{}'", name));
    const nlohmann::json& list = value[name];
    if (!list.is_array()) fail(at, "expected an array of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (!list[i].is_number()) fail(fmt::format("{}[{}]", at, i), "expected a number");
      out.push_back(list[i].get<double>());
    }
    if (out.size() != count) fail(at, fmt::format("expected {} numbers", count));
    return out;
  };
  const std::vector<double> position = numbers("position", 3);
  const std::vector<double> q = numbers("quaternion_wxyz", 4);
  const Eigen::Quaterniond rotation(q[0], q[1], q[2], q[3]);
  if (!std::isfinite(rotation.norm()) || std::abs(rotation.norm() - 1) > 1e-6 ||
      !std::isfinite(position[0] + position[1] + position[2])) {
    fail(key, "not a finite position and unit quaternion");
  }
  Pose pose = Pose::Identity();
  pose.translation() = Vec3(position[0], position[1], position[2]);
  pose.linear() = rotation.normalized().toRotationMatrix();
  return pose;
}

nlohmann::json ikSolutionsJson(std::span<const std::vector<double>> solutions) {
  nlohmann::json list = nlohmann::json::array();
  for (const std::vector<double>& q : solutions) list.push_back(q);
  return {{"reachable", !solutions.empty()}, {"solutions", list}};
}

}  // namespace kaboum::io
