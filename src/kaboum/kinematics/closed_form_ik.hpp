// Closed-form inverse kinematics for the two arm families of thesis Appendix A.3. Angles θ are
// in the family's own zero pose (all links pointing up along z); ArmIk (arm_ik.hpp) maps them to
// a URDF chain's joints.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <optional>

#include "kaboum/core/types.hpp"

namespace kaboum::kinematics {

// Six revolute axes (A.3 "Inverse Position for Six Revolute Axes"): base yaw about z; shoulder
// and elbow about y with base height d1, shoulder offset a1, upper arm a2, elbow offset a3,
// lateral offset d3 and forearm d4; a spherical z-y-z wrist; flange d6 along the last axis.
// FK = Rz(θ0) T(a1,0,d1) Ry(θ1) T(0,0,a2) Ry(θ2) T(a3,d3,d4) Rz(θ3) Ry(θ4) Rz(θ5) T(0,0,d6).
struct SixAxisArm {
  using Angles = std::array<double, 6>;
  double d1 = 0, a1 = 0, a2 = 0, a3 = 0, d3 = 0, d4 = 0, d6 = 0;

  [[nodiscard]] Pose flangePose(const Angles& theta) const;
  // One of up to 8 solutions, chosen by k0 (shoulder front/back), k1 (elbow), k2 (wrist flip),
  // each ±1. Unreachable poses (arccos argument beyond ±1, wrist centre closer to the base axis
  // than d3) give nullopt, never NaN.
  [[nodiscard]] std::optional<Angles> solve(const Pose& flange, int k0, int k1, int k2) const;
};

// Five revolute axes (A.3 "Inverse Position for Five Revolute Axes"): base yaw about z; three
// parallel pitch axes about y with base height d1 and links a2, a3; tool roll about z; tool
// centre d5 along the roll axis. FK = Rz(θ0) T(0,0,d1) Ry(θ1) T(0,0,a2) Ry(θ2) T(0,0,a3) Ry(θ3)
// Rz(θ4) T(0,0,d5). The tool frame is Rz(azimuth) Ry(pitch) Rz(roll) at the tool centre, where
// azimuth is the direction of the tool centre seen from the base axis.
struct FiveAxisArm {
  using Angles = std::array<double, 5>;
  double d1 = 0, a2 = 0, a3 = 0, d5 = 0;

  [[nodiscard]] Pose toolPose(const Angles& theta) const;
  // Solution for tool centre `position`, `pitch` β (tool axis from vertical, towards the
  // outside) and `roll` φ; k0 = −1 turns the base around, k1 picks the elbow. Up to 4 solutions.
  [[nodiscard]] std::optional<Angles> solve(const Eigen::Vector3d& position, double pitch,
                                            double roll, int k0, int k1) const;
};

}  // namespace kaboum::kinematics
