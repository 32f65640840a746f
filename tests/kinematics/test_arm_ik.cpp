#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

bool posesClose(const Pose& a, const Pose& b, double tolerance) {
  return (a.translation() - b.translation()).norm() < tolerance &&
         (a.linear() - b.linear()).cwiseAbs().maxCoeff() < tolerance;
}

SixAxisArm::Angles randomAngles(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  SixAxisArm::Angles theta{};
  for (auto& value : theta) value = angle(rng);
  return theta;
}

// Every (k0, k1, k2) solution of a reachable pose reproduces it, and the generating angles are
// among them; over random arm parameters (including a1, a3, d3 ≠ 0) and random poses.
TEST(SixAxisArm, AllBranchesRoundTripThroughFk) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> length(0.05, 0.8), offset(-0.2, 0.2);
  int solutions = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const SixAxisArm arm{length(rng), offset(rng), length(rng), offset(rng),
                         offset(rng), length(rng), offset(rng)};
    const SixAxisArm::Angles theta = randomAngles(rng);
    const Pose target = arm.flangePose(theta);
    bool foundOriginal = false;
    for (const int k0 : {1, -1}) {
      for (const int k1 : {1, -1}) {
        for (const int k2 : {1, -1}) {
          const auto solution = arm.solve(target, k0, k1, k2);
          if (!solution) continue;
          ++solutions;
          ASSERT_TRUE(posesClose(arm.flangePose(*solution), target, 1e-8)) << "trial " << trial;
          double difference = 0;
          for (std::size_t i = 0; i < 6; ++i) {
            difference =
                std::max(difference,
                         std::abs(std::remainder((*solution)[i] - theta[i], 2 * std::numbers::pi)));
          }
          foundOriginal = foundOriginal || difference < 1e-6;
        }
      }
    }
    EXPECT_TRUE(foundOriginal) << "trial " << trial;
  }
  EXPECT_GT(solutions, 300 * 4);  // most poses have more than four solutions
}

TEST(SixAxisArm, UnreachablePosesGiveNoSolutionAndNoNaN) {
  const SixAxisArm arm{0.4, 0.1, 0.5, 0.05, 0.0, 0.5, 0.1};
  Pose far = Pose::Identity();
  far.translation() = Eigen::Vector3d(3.0, 0.0, 0.4);
  const SixAxisArm lateral{0.4, 0.1, 0.5, 0.05, 0.3, 0.5, 0.0};
  Pose insideOffset = Pose::Identity();
  insideOffset.translation() = Eigen::Vector3d(0.1, 0.0, 0.6);  // closer to the axis than d3
  for (const int k0 : {1, -1}) {
    for (const int k1 : {1, -1}) {
      for (const int k2 : {1, -1}) {
        EXPECT_FALSE(arm.solve(far, k0, k1, k2));
        EXPECT_FALSE(lateral.solve(insideOffset, k0, k1, k2));
      }
    }
  }
}

TEST(FiveAxisArm, AllBranchesRoundTripThroughFk) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> length(0.05, 0.6), angle(-3.0, 3.0);
  for (int trial = 0; trial < 300; ++trial) {
    const FiveAxisArm arm{length(rng), length(rng), length(rng), length(rng)};
    FiveAxisArm::Angles theta{};
    for (auto& value : theta) value = angle(rng);
    const Pose tool = arm.toolPose(theta);
    // Read position, pitch and roll back off the tool frame Rz(azimuth) Ry(pitch) Rz(roll).
    const Eigen::Vector3d position = tool.translation();
    const double azimuth = std::atan2(position.y(), position.x());
    const Eigen::Matrix3d inPlane =
        Eigen::AngleAxisd(-azimuth, Eigen::Vector3d::UnitZ()).toRotationMatrix() * tool.linear();
    const double pitch = std::atan2(inPlane(0, 2), inPlane(2, 2));
    const Eigen::Matrix3d rolled =
        Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() * inPlane;
    const double roll = std::atan2(rolled(1, 0), rolled(0, 0));
    int found = 0;
    for (const int k0 : {1, -1}) {
      for (const int k1 : {1, -1}) {
        const auto solution = arm.solve(position, pitch, roll, k0, k1);
        if (!solution) continue;
        ++found;
        EXPECT_TRUE(posesClose(arm.toolPose(*solution), tool, 1e-8)) << "trial " << trial;
      }
    }
    EXPECT_GE(found, 1) << "trial " << trial;
  }
  const FiveAxisArm arm{0.2, 0.3, 0.3, 0.1};
  EXPECT_FALSE(arm.solve(Eigen::Vector3d(2, 0, 0.2), 0.3, 0.0, 1, 1));
}

// The KR5 and the Comau arms fit the six-axis family; FK round trips on random configurations.
TEST(ArmIk, UrdfArmsRoundTripOnRandomReachablePoses) {
  std::mt19937_64 rng(3);
  for (const auto& path : {test::kKr5, test::kComauLeft, test::kComauRight}) {
    const RobotModel robot = loadUrdf(path);
    const KinematicChain chain(robot, path == test::kComauLeft ? "body6" : "");
    ASSERT_EQ(chain.dof(), 6);
    const auto ik = ArmIk::fit(chain);
    ASSERT_TRUE(ik) << path;
    EXPECT_EQ(ik->family(), ArmIk::Family::SixAxis);
    ArmIk::Solutions solutions;
    for (int trial = 0; trial < 200; ++trial) {
      const std::vector<double> q = test::randomConfiguration(chain, rng);
      const Pose target = chain.toolPose(q);
      ik->solve(target, solutions);
      ASSERT_GE(solutions.count, 1) << path << " trial " << trial;
      bool foundOriginal = false;
      for (int s = 0; s < solutions.count; ++s) {
        const auto& solution = solutions.q[static_cast<std::size_t>(s)];
        const std::span<const double> values(solution.data(), 6);
        EXPECT_TRUE(chain.withinLimits(values));
        EXPECT_TRUE(posesClose(chain.toolPose(values), target, 1e-6));
        double difference = 0;
        for (std::size_t i = 0; i < 6; ++i) {
          difference = std::max(difference,
                                std::abs(std::remainder(solution[i] - q[i], 2 * std::numbers::pi)));
        }
        foundOriginal = foundOriginal || difference < 1e-5;
      }
      EXPECT_TRUE(foundOriginal) << path << " trial " << trial;
    }
  }
}

TEST(ArmIk, Kr5ParametersMatchItsUrdf) {
  const RobotModel robot = loadUrdf(test::kKr5);
  const KinematicChain chain(robot);
  const auto ik = ArmIk::fit(chain);
  ASSERT_TRUE(ik);
  const SixAxisArm& arm = ik->sixAxis();
  // shoulder_pitch at x 0.075, z 0.203 + 0.13 above base_link, which sits 0.5 m along its own z
  // from the URDF root "world"; upper arm 0.27; elbow offset 0.09 above the forearm axis; wrist
  // centre 0.106 + 0.187 along it; lateral offset 0 (the URDF rounds these to ~1e-7).
  EXPECT_NEAR(arm.a1, 0.075, 1e-6);
  EXPECT_NEAR(arm.d1, 0.333 - 0.5, 1e-6);
  EXPECT_NEAR(arm.a2, 0.27, 1e-6);
  EXPECT_NEAR(std::abs(arm.a3), 0.09, 1e-6);
  EXPECT_NEAR(arm.d4, 0.293, 1e-6);
  EXPECT_NEAR(arm.d3, 0.0, 1e-6);
}

TEST(ArmIk, ComauParametersMatchTheRoboticsLibraryModel) {
  const RobotModel robot = loadUrdf(test::kComauRight);
  const KinematicChain chain(robot);
  const auto ik = ArmIk::fit(chain);
  ASSERT_TRUE(ik);
  const SixAxisArm& arm = ik->sixAxis();
  // robot-right.mdl.xml: base height 0.45, shoulder offset 0.15, upper arm 0.59, elbow offset
  // 0.13, forearm 0.64707 (the 0.095 flange is absorbed into the tool transform).
  EXPECT_NEAR(arm.d1, 0.45, 1e-12);
  EXPECT_NEAR(arm.a1, 0.15, 1e-12);
  EXPECT_NEAR(arm.a2, 0.59, 1e-12);
  EXPECT_NEAR(std::abs(arm.a3), 0.13, 1e-12);
  EXPECT_NEAR(arm.d4, 0.64707, 1e-12);
  EXPECT_NEAR(arm.d3, 0.0, 1e-12);
}

TEST(ArmIk, WamDoesNotFitAndUnreachableTargetsHaveNoSolution) {
  const RobotModel wam = loadUrdf(test::kWam);
  EXPECT_FALSE(ArmIk::fit(KinematicChain(wam)));
  const RobotModel kr5 = loadUrdf(test::kKr5);
  const KinematicChain chain(kr5);
  const auto ik = ArmIk::fit(chain);
  ASSERT_TRUE(ik);
  Pose far = Pose::Identity();
  far.translation() = Eigen::Vector3d(2.0, 0.0, 0.0);
  ArmIk::Solutions solutions;
  ik->solve(far, solutions);
  EXPECT_EQ(solutions.count, 0);
}

}  // namespace
}  // namespace kaboum::kinematics
