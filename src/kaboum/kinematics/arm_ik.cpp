#include "kaboum/kinematics/arm_ik.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace kaboum::kinematics {
namespace {

constexpr double kAxisTolerance = 1e-6;  // parallel/perpendicular/intersecting axes
constexpr double kPoseTolerance = 1e-7;  // FK agreement of a solution or of the fitted model

struct AxisLine {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;  // unit
};

// Parameters s, t of the closest points point + s·direction on two lines.
std::pair<double, double> closestParameters(const AxisLine& a, const AxisLine& b) {
  const Eigen::Vector3d w = a.point - b.point;
  const double cosine = a.direction.dot(b.direction);
  const double d = a.direction.dot(w);
  const double e = b.direction.dot(w);
  const double denominator = 1 - cosine * cosine;
  if (denominator < 1e-12) return {0.0, e};
  return {(cosine * e - d) / denominator, (e - cosine * d) / denominator};
}

bool perpendicular(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::abs(a.dot(b)) < kAxisTolerance;
}
bool parallel(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::abs(a.dot(b)) > 1 - kAxisTolerance;
}

bool posesAgree(const Pose& a, const Pose& b) {
  return (a.translation() - b.translation()).norm() < kPoseTolerance &&
         (a.linear() - b.linear()).cwiseAbs().maxCoeff() < kPoseTolerance;
}

// Axis lines of the chain's joints at q = 0, expressed in `frame`.
std::vector<AxisLine> axesAtZero(const KinematicChain& chain, const Pose& frame) {
  std::vector<AxisLine> axes;
  Pose pose = Pose::Identity();
  const Pose toFrame = frame.inverse();
  for (int i = 0; i < chain.dof(); ++i) {
    pose = pose * chain.joint(i).origin;
    axes.push_back(
        {toFrame * pose.translation(), toFrame.linear() * pose.linear() * chain.joint(i).axis});
  }
  return axes;
}

// Base frame of the family: z along axis 0, y along axis 1, origin on axis 0 at the foot of the
// chain root origin.
std::optional<Pose> familyBase(const std::vector<AxisLine>& axes) {
  const Eigen::Vector3d z = axes[0].direction;
  const Eigen::Vector3d y = axes[1].direction;
  if (!perpendicular(z, y)) return std::nullopt;
  Pose base = Pose::Identity();
  base.linear().col(0) = y.cross(z);
  base.linear().col(1) = y;
  base.linear().col(2) = z;
  base.translation() = axes[0].point - axes[0].point.dot(z) * z;
  return base;
}

double sign(double value) {
  return value < 0 ? -1.0 : 1.0;
}

}  // namespace

std::optional<ArmIk> ArmIk::fit(const KinematicChain& chain) {
  const int n = chain.dof();
  if (n != 5 && n != 6) return std::nullopt;
  for (int i = 0; i < n; ++i) {
    const JointType type = chain.joint(i).type;
    if (type != JointType::Revolute && type != JointType::Continuous) return std::nullopt;
  }
  const auto base = familyBase(axesAtZero(chain, Pose::Identity()));
  if (!base) return std::nullopt;
  const std::vector<AxisLine> axes = axesAtZero(chain, *base);
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  ArmIk ik(chain, n == 6 ? Family::SixAxis : Family::FiveAxis);
  ik.base_ = *base;
  // Shoulder: the point of axis 1 nearest the base axis, projected into the plane y = 0.
  const double onShoulder = closestParameters(axes[0], axes[1]).second;
  Eigen::Vector3d shoulder = axes[1].point + onShoulder * axes[1].direction;
  shoulder.y() = 0;
  const auto planarAngle = [](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    return std::atan2(to.x() - from.x(), to.z() - from.z());
  };
  const auto planarDistance = [](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    return std::hypot(to.x() - from.x(), to.z() - from.z());
  };
  if (!parallel(axes[2].direction, y)) return std::nullopt;
  ik.sign_[2] = sign(axes[2].direction.dot(y));
  const Eigen::Vector3d elbow = axes[2].point;
  const double upperArm = planarDistance(shoulder, elbow);
  ik.offset_[1] = planarAngle(shoulder, elbow);
  if (n == 6) {
    // Wrist centre: where axes 3, 4 and 5 meet.
    const double s3 = closestParameters(axes[3], axes[4]).first;
    const Eigen::Vector3d wrist = axes[3].point + s3 * axes[3].direction;
    const auto distanceToWrist = [&](const AxisLine& axis) {
      const Eigen::Vector3d r = wrist - axis.point;
      return (r - r.dot(axis.direction) * axis.direction).norm();
    };
    if (distanceToWrist(axes[4]) > kAxisTolerance || distanceToWrist(axes[5]) > kAxisTolerance ||
        !perpendicular(axes[3].direction, y) || !parallel(axes[4].direction, y) ||
        !perpendicular(axes[5].direction, y)) {
      return std::nullopt;
    }
    Eigen::Vector3d forearm = axes[3].direction;
    if ((wrist - elbow).dot(forearm) < 0) forearm = -forearm;
    ik.sign_[3] = sign(forearm.dot(axes[3].direction));
    ik.sign_[4] = sign(axes[4].direction.dot(y));
    const double phi = std::atan2(forearm.x(), forearm.z());
    ik.offset_[2] = phi - ik.offset_[1];
    ik.offset_[4] = std::atan2(axes[5].direction.x(), axes[5].direction.z()) - phi;
    const double dx = wrist.x() - elbow.x();
    const double dz = wrist.z() - elbow.z();
    ik.six_ = {shoulder.z(), shoulder.x(),
               upperArm,     std::cos(phi) * dx - std::sin(phi) * dz,
               wrist.y(),    std::sin(phi) * dx + std::cos(phi) * dz,
               0.0};
    if (!(ik.six_.a2 > kAxisTolerance) || !(std::hypot(ik.six_.a3, ik.six_.d4) > kAxisTolerance)) {
      return std::nullopt;
    }
  } else {
    // Pitch axes 1–3 in the arm plane, the roll axis through axis 3; no shoulder offset.
    if (std::abs(shoulder.x()) > kAxisTolerance || !parallel(axes[3].direction, y) ||
        !perpendicular(axes[4].direction, y)) {
      return std::nullopt;
    }
    ik.sign_[3] = sign(axes[3].direction.dot(y));
    const Eigen::Vector3d wrist = axes[3].point;
    const auto [s3, s4] = closestParameters(axes[3], axes[4]);
    if ((axes[3].point + s3 * axes[3].direction - axes[4].point - s4 * axes[4].direction).norm() >
        kAxisTolerance) {
      return std::nullopt;
    }
    ik.offset_[2] = planarAngle(elbow, wrist) - ik.offset_[1];
    ik.offset_[3] =
        std::atan2(axes[4].direction.x(), axes[4].direction.z()) - ik.offset_[1] - ik.offset_[2];
    ik.five_ = {shoulder.z(), upperArm, planarDistance(elbow, wrist), 0.0};
    if (!(ik.five_.a2 > kAxisTolerance) || !(ik.five_.a3 > kAxisTolerance)) return std::nullopt;
  }
  // Axis 0 is the family's z and axis 1 its y by construction (signs +1, offset 0).
  const std::array<double, 6> zero{};
  ik.tool_ = Pose::Identity();
  ik.tool_ = ik.familyTip(zero).inverse() *
             chain.toolPose(std::span(zero.data(), static_cast<std::size_t>(n)));
  // Verify the fitted model against the chain's own FK on configurations across the limits.
  for (int sample = 1; sample <= 7; ++sample) {
    Solution q{};
    for (int i = 0; i < n; ++i) {
      const double fraction = std::fmod(0.137 + 0.618034 * sample * (i + 1), 1.0);
      q[static_cast<std::size_t>(i)] =
          chain.lower(i) + fraction * (chain.upper(i) - chain.lower(i));
    }
    const std::span qs(q.data(), static_cast<std::size_t>(n));
    if (!posesAgree(ik.familyTip(qs), chain.toolPose(qs))) return std::nullopt;
  }
  return ik;
}

Pose ArmIk::familyTip(std::span<const double> q) const {
  if (family_ == Family::SixAxis) {
    SixAxisArm::Angles theta{};
    for (std::size_t i = 0; i < 6; ++i) theta[i] = sign_[i] * q[i] + offset_[i];
    return base_ * six_.flangePose(theta) * tool_;
  }
  FiveAxisArm::Angles theta{};
  for (std::size_t i = 0; i < 5; ++i) theta[i] = sign_[i] * q[i] + offset_[i];
  return base_ * five_.toolPose(theta) * tool_;
}

bool ArmIk::toJoints(std::span<const double> theta, Solution& q) const {
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double value = std::remainder(sign_[i] * (theta[i] - offset_[i]), 2 * std::numbers::pi);
    const int joint = static_cast<int>(i);
    bool found = false;
    for (const double shift : {0.0, 2 * std::numbers::pi, -2 * std::numbers::pi}) {
      const double candidate = value + shift;
      if (candidate >= chain_->lower(joint) - 1e-9 && candidate <= chain_->upper(joint) + 1e-9) {
        q[i] = std::clamp(candidate, chain_->lower(joint), chain_->upper(joint));
        found = true;
        break;
      }
    }
    if (!found) return false;
  }
  return true;
}

void ArmIk::addIfNew(const Solution& q, const Pose& tip, Solutions& out) const {
  const auto n = static_cast<std::size_t>(dof());
  if (!posesAgree(chain_->toolPose(std::span(q.data(), n)), tip)) return;
  for (int s = 0; s < out.count; ++s) {
    double difference = 0;
    for (std::size_t i = 0; i < n; ++i) {
      difference = std::max(difference, std::abs(out.q[static_cast<std::size_t>(s)][i] - q[i]));
    }
    if (difference < 1e-6) return;
  }
  out.q[static_cast<std::size_t>(out.count++)] = q;
}

void ArmIk::solve(const Pose& tip, Solutions& out) const {
  out.count = 0;
  const Pose flange = base_.inverse() * tip * tool_.inverse();
  Solution q{};
  if (family_ == Family::SixAxis) {
    for (const int k0 : {1, -1}) {
      for (const int k1 : {1, -1}) {
        for (const int k2 : {1, -1}) {
          const auto theta = six_.solve(flange, k0, k1, k2);
          if (theta && toJoints(*theta, q)) addIfNew(q, tip, out);
        }
      }
    }
    return;
  }
  // Five axes: read azimuth, pitch and roll off the target; FK rejects unreachable orientations.
  const Eigen::Vector3d position = flange.translation();
  const double azimuth = std::atan2(position.y(), position.x());
  const Eigen::Matrix3d inPlane =
      Eigen::AngleAxisd(-azimuth, Eigen::Vector3d::UnitZ()).toRotationMatrix() * flange.linear();
  const double pitch = std::atan2(inPlane(0, 2), inPlane(2, 2));
  const Eigen::Matrix3d rolled =
      Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() * inPlane;
  const double roll = std::atan2(rolled(1, 0), rolled(0, 0));
  for (const int k0 : {1, -1}) {
    for (const int k1 : {1, -1}) {
      const auto theta = five_.solve(position, pitch, roll, k0, k1);
      if (theta && toJoints(*theta, q)) addIfNew(q, tip, out);
    }
  }
}

}  // namespace kaboum::kinematics
