#include "kaboum/kinematics/closed_form_ik.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kaboum::kinematics {
namespace {

constexpr double kDomainSlack = 1e-10;  // rounding tolerance on arccos and sqrt domains

Eigen::Matrix3d rotZ(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}
Eigen::Matrix3d rotY(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
}
Pose rotationPose(const Eigen::Matrix3d& rotation) {
  Pose pose = Pose::Identity();
  pose.linear() = rotation;
  return pose;
}
Pose translation(double x, double y, double z) {
  return Pose(Eigen::Translation3d(x, y, z));
}

// arccos that reports an argument outside [−1, 1] (beyond rounding) as unreachable.
std::optional<double> safeAcos(double cosine) {
  if (!(std::abs(cosine) <= 1 + kDomainSlack)) return std::nullopt;
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

}  // namespace

Pose SixAxisArm::flangePose(const Angles& t) const {
  return rotationPose(rotZ(t[0])) * translation(a1, 0, d1) * rotationPose(rotY(t[1])) *
         translation(0, 0, a2) * rotationPose(rotY(t[2])) * translation(a3, d3, d4) *
         rotationPose(rotZ(t[3]) * rotY(t[4]) * rotZ(t[5])) * translation(0, 0, d6);
}

std::optional<SixAxisArm::Angles> SixAxisArm::solve(const Pose& flange, int k0, int k1,
                                                    int k2) const {
  Angles t{};
  const Eigen::Vector3d wrist = flange.translation() - d6 * flange.linear().col(2);
  // Base: the wrist centre lies at lateral offset d3 from the arm plane.
  const double radial2 = wrist.x() * wrist.x() + wrist.y() * wrist.y() - d3 * d3;
  if (!(radial2 >= -kDomainSlack)) return std::nullopt;
  const double radial = k0 * std::sqrt(std::max(radial2, 0.0));
  t[0] = std::atan2(wrist.y(), wrist.x()) - std::atan2(d3, radial);
  // Shoulder and elbow: a planar two-link problem in the arm plane (law of cosines).
  const double s0 = radial - a1;
  const double s1 = wrist.z() - d1;
  const double forearm = std::hypot(a3, d4);
  const double reach2 = s0 * s0 + s1 * s1;
  const auto elbow = safeAcos((reach2 - a2 * a2 - forearm * forearm) / (2 * a2 * forearm));
  if (!elbow) return std::nullopt;
  t[2] = k1 * *elbow - std::atan2(a3, d4);
  const double localX = a3 * std::cos(t[2]) + d4 * std::sin(t[2]);
  const double localZ = a2 - a3 * std::sin(t[2]) + d4 * std::cos(t[2]);
  t[1] = std::atan2(s0, s1) - std::atan2(localX, localZ);
  // Spherical wrist: z-y-z Euler angles of the remaining rotation.
  const Eigen::Matrix3d w = (rotZ(t[0]) * rotY(t[1] + t[2])).transpose() * flange.linear();
  const double sin4 = k2 * std::hypot(w(0, 2), w(1, 2));
  t[4] = std::atan2(sin4, w(2, 2));
  if (std::abs(sin4) > 1e-12) {
    t[3] = std::atan2(k2 * w(1, 2), k2 * w(0, 2));
    t[5] = std::atan2(k2 * w(2, 1), -k2 * w(2, 0));
  } else if (w(2, 2) > 0) {  // wrist singularity: only θ3 + θ5 is defined
    t[3] = 0;
    t[5] = std::atan2(w(1, 0), w(0, 0));
  } else {
    t[3] = 0;
    t[5] = -std::atan2(-w(1, 0), -w(0, 0));
  }
  return t;
}

Pose FiveAxisArm::toolPose(const Angles& t) const {
  return rotationPose(rotZ(t[0])) * translation(0, 0, d1) * rotationPose(rotY(t[1])) *
         translation(0, 0, a2) * rotationPose(rotY(t[2])) * translation(0, 0, a3) *
         rotationPose(rotY(t[3]) * rotZ(t[4])) * translation(0, 0, d5);
}

std::optional<FiveAxisArm::Angles> FiveAxisArm::solve(const Eigen::Vector3d& position, double pitch,
                                                      double roll, int k0, int k1) const {
  Angles t{};
  const double azimuth = std::atan2(position.y(), position.x());
  const double radial = k0 * std::hypot(position.x(), position.y());
  const double beta = k0 * pitch;
  t[0] = k0 > 0 ? azimuth : azimuth + std::numbers::pi;
  // Pitch-axis position of the last pitch joint in the arm plane (A.3: t3).
  const double tx = radial - d5 * std::sin(beta);
  const double tz = position.z() - d1 - d5 * std::cos(beta);
  const auto elbow = safeAcos((tx * tx + tz * tz - a2 * a2 - a3 * a3) / (2 * a2 * a3));
  if (!elbow) return std::nullopt;
  t[2] = k1 * *elbow;
  t[1] = std::atan2(tx, tz) - std::atan2(a3 * std::sin(t[2]), a2 + a3 * std::cos(t[2]));
  t[3] = beta - t[1] - t[2];
  t[4] = k0 > 0 ? roll : roll - std::numbers::pi;
  return t;
}

}  // namespace kaboum::kinematics
