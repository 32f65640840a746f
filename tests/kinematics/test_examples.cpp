// The project's example robots (examples/robots): they load, and closed-form IK fits their arms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kaboum/core/error.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/numeric_ik.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

const std::string kExamples = kaboum::testing::exampleFile("robots/");

// Random configurations → FK → closed-form IK finds the configuration again.
void expectRoundTrips(const KinematicChain& chain, const ArmIk& ik, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  ArmIk::Solutions solutions;
  const auto n = static_cast<std::size_t>(chain.dof());
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<double> q = test::randomConfiguration(chain, rng);
    ik.solve(chain.toolPose(q), solutions);
    bool found = false;
    for (int s = 0; s < solutions.count; ++s) {
      double difference = 0;
      for (std::size_t i = 0; i < n; ++i) {
        difference =
            std::max(difference, std::abs(solutions.q[static_cast<std::size_t>(s)][i] - q[i]));
      }
      found = found || difference < 1e-6;
    }
    EXPECT_TRUE(found) << "trial " << trial;
  }
}

TEST(ExampleRobots, MobileFiveAxisArm) {
  const RobotModel robot = loadUrdf(kExamples + "mobile-5axis.urdf");
  EXPECT_EQ(robot.dof(), 8);  // planar base x, y, θ and five arm axes
  const auto base = robot.findLink("base");
  ASSERT_TRUE(base);
  EXPECT_EQ(robot.links()[static_cast<std::size_t>(*base)].collisions.at(0).kind,
            CollisionShape::Kind::Mesh);
  const KinematicChain arm(robot, "tool_center", "arm_base");
  const auto ik = ArmIk::fit(arm);
  ASSERT_TRUE(ik);
  EXPECT_EQ(ik->family(), ArmIk::Family::FiveAxis);
  EXPECT_NEAR(ik->fiveAxis().a2, 0.19, 1e-12);
  EXPECT_NEAR(ik->fiveAxis().a3, 0.139, 1e-12);
  expectRoundTrips(arm, *ik, 1);
  // The whole robot (base and arm) from the world: numeric IK.
  const KinematicChain whole(robot, "tool_center");
  ASSERT_EQ(whole.dof(), 8);
  EXPECT_FALSE(ArmIk::fit(whole));
  Pose target = Pose::Identity();
  target.translation() = Eigen::Vector3d(1.5, -0.7, 0.3);
  target.linear() =
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  NumericIk numeric(whole);
  std::vector<double> q(8);
  ASSERT_TRUE(numeric.solve(target, {}, q));
  EXPECT_LT((whole.toolPose(q).translation() - target.translation()).norm(), 1e-6);
}

TEST(ExampleRobots, TwoSixAxisArms) {
  const RobotModel robot = loadUrdf(kExamples + "two-arm.urdf");
  EXPECT_EQ(robot.dof(), 12);
  for (const std::string side : {"left", "right"}) {
    const KinematicChain arm(robot, side + "_flange");
    ASSERT_EQ(arm.dof(), 6);
    const auto ik = ArmIk::fit(arm);
    ASSERT_TRUE(ik) << side;
    EXPECT_NEAR(ik->sixAxis().a2, 0.3, 1e-12);
    expectRoundTrips(arm, *ik, 2);
  }
}

TEST(ExampleRobots, ChainBaseMustBeAnAncestorOfTheTip) {
  const RobotModel robot = loadUrdf(kExamples + "two-arm.urdf");
  EXPECT_THROW(KinematicChain(robot, "left_flange", "right_mount"), InputError);
}

}  // namespace
}  // namespace kaboum::kinematics
