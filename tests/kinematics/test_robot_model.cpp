#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kaboum/core/error.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using test::kComauLeft;
using test::kComauRight;
using test::kKr5;
using test::kWam;

TEST(UrdfLoader, LoadsKr5JointsLimitsAndMeshes) {
  const RobotModel robot = loadUrdf(kKr5);
  EXPECT_EQ(robot.dof(), 6);
  EXPECT_EQ(robot.links().front().name, "world");
  const Joint& yaw = robot.variableJoint(0);
  EXPECT_EQ(yaw.name, "shoulder_yaw");
  EXPECT_EQ(yaw.type, JointType::Revolute);
  EXPECT_DOUBLE_EQ(yaw.lower, -2.9671);
  EXPECT_DOUBLE_EQ(yaw.maxVelocity, 6.545);
  const auto palm = robot.findLink("palm");
  ASSERT_TRUE(palm);
  const auto& shapes = robot.links()[static_cast<std::size_t>(*palm)].collisions;
  ASSERT_EQ(shapes.size(), 1u);
  EXPECT_EQ(shapes[0].kind, CollisionShape::Kind::Mesh);
  EXPECT_NE(shapes[0].meshPath.find("KR5/meshes/palm.STL"), std::string::npos);
  EXPECT_EQ(KinematicChain(robot).tipName(), "palm");
}

TEST(UrdfLoader, ResolvesPackageMeshesOfTheWam) {
  const RobotModel robot = loadUrdf(kWam);
  EXPECT_EQ(robot.dof(), 7);
  const auto link = robot.findLink("/wam3");
  ASSERT_TRUE(link);
  const auto& shapes = robot.links()[static_cast<std::size_t>(*link)].collisions;
  ASSERT_FALSE(shapes.empty());
  EXPECT_NE(shapes[0].meshPath.find("wam/meshes/wam/wam3_collision.STL"), std::string::npos);
}

TEST(UrdfLoader, ReadsPrimitivesAndExpandsPlanarJoints) {
  const std::string xml = R"(<robot name="base">
    <link name="floor"/>
    <link name="cart"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.3 0.2"/></geometry></collision>
      <collision><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision>
      <collision><geometry><sphere radius="0.07"/></geometry></collision></link>
    <joint name="drive" type="planar"><parent link="floor"/><child link="cart"/><axis xyz="0 0 1"/>
      <limit lower="-5" upper="5" effort="0" velocity="1"/></joint>
  </robot>)";
  const RobotModel robot = parseUrdf(xml, "base.urdf", ".");
  ASSERT_EQ(robot.dof(), 3);
  EXPECT_EQ(robot.variableJoint(2).type, JointType::Continuous);
  const auto cart = robot.findLink("cart");
  ASSERT_TRUE(cart);
  const auto& shapes = robot.links()[static_cast<std::size_t>(*cart)].collisions;
  ASSERT_EQ(shapes.size(), 3u);
  EXPECT_EQ(shapes[0].kind, CollisionShape::Kind::Box);
  EXPECT_DOUBLE_EQ(shapes[0].size.y(), 0.3);
  EXPECT_DOUBLE_EQ(shapes[0].origin.translation().z(), 0.1);
  EXPECT_EQ(shapes[1].kind, CollisionShape::Kind::Cylinder);
  EXPECT_DOUBLE_EQ(shapes[1].length, 0.3);
  EXPECT_EQ(shapes[2].kind, CollisionShape::Kind::Sphere);
  // x = 1, y = 2, θ = π/2 puts the cart at (1, 2) in the floor plane, turned a quarter.
  const KinematicChain chain(robot, "cart");
  const std::vector<double> q{1.0, 2.0, std::numbers::pi / 2};
  const Pose pose = chain.toolPose(q);
  EXPECT_NEAR((pose.translation() - Eigen::Vector3d(0, 0, 0)).z(), 0.0, 1e-9);
  EXPECT_NEAR(pose.translation().head<2>().norm(), std::sqrt(5.0), 1e-9);
  EXPECT_TRUE(pose.linear().col(0).isApprox(Eigen::Vector3d(0, 1, 0), 1e-9) ||
              pose.linear().col(0).isApprox(Eigen::Vector3d(0, -1, 0), 1e-9));
}

// Comau conversion checked against the scenario's own files: the base pose comes from scene.wrl
// (left arm at y = 0.57); at q = 0, robots/robot-left.wrl places link1 at (0.15, 0, 0.45)
// rotated −90° about x and link2 at (0.15, 0, 1.04) rotated −120° about (1, 1, 1); every link
// rotation it lists matches FK (see docs/kinematics.md for the elbow-offset position caveat).
TEST(ComauConversion, HomePosesMatchTheScenarioVrml) {
  const RobotModel robot = loadUrdf(kComauLeft);
  EXPECT_EQ(robot.dof(), 8);  // six arm axes and two gripper fingers
  std::vector<Pose> poses(robot.links().size());
  const std::vector<double> home(8, 0.0);
  robot.linkPoses(home, poses);
  const auto pose = [&](const char* name) {
    return poses[static_cast<std::size_t>(*robot.findLink(name))];
  };
  const Pose base(Eigen::Translation3d(0, 0.57, 0));
  const Pose link1 = base * pose("body1");
  EXPECT_TRUE(link1.translation().isApprox(Eigen::Vector3d(0.15, 0.57, 0.45), 1e-9));
  EXPECT_TRUE(link1.linear().isApprox(
      Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix(), 1e-9));
  const Pose link2 = base * pose("body2");
  EXPECT_TRUE(link2.translation().isApprox(Eigen::Vector3d(0.15, 0.57, 1.04), 1e-9));
  EXPECT_TRUE(link2.linear().isApprox(
      Eigen::AngleAxisd(-2.094395, Eigen::Vector3d(1, 1, 1).normalized()).toRotationMatrix(),
      1e-6));
  EXPECT_TRUE(pose("body3").linear().isApprox(
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-9));
  EXPECT_TRUE(pose("body4").linear().isApprox(
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d(0, 1, 1).normalized()).toRotationMatrix(),
      1e-9));
  EXPECT_TRUE(pose("body6").linear().isIdentity(1e-9));
  // Flange height: 0.45 + 0.59 + 0.64707 + 0.095 above the base, shifted back by the 0.13 m
  // elbow offset.
  EXPECT_TRUE(pose("body6").translation().isApprox(Eigen::Vector3d(0.02, 0, 1.78207), 1e-9));
  const RobotModel right = loadUrdf(kComauRight);
  EXPECT_EQ(right.dof(), 6);
}

TEST(KinematicChain, JacobianMatchesCentralDifferences) {
  std::mt19937_64 rng(7);
  for (const auto& path : {kKr5, kWam, kComauLeft}) {
    const RobotModel robot = loadUrdf(path);
    const KinematicChain chain(robot);
    Jacobian jacobian(6, chain.dof());
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> q = test::randomConfiguration(chain, rng);
      const Pose pose = chain.toolPoseAndJacobian(q, jacobian);
      EXPECT_TRUE(pose.isApprox(chain.toolPose(q), 1e-9));
      const double h = 1e-6;
      for (int j = 0; j < chain.dof(); ++j) {
        auto qp = q, qm = q;
        qp[static_cast<std::size_t>(j)] += h;
        qm[static_cast<std::size_t>(j)] -= h;
        const Pose plus = chain.toolPose(qp), minus = chain.toolPose(qm);
        const Eigen::Vector3d linear = (plus.translation() - minus.translation()) / (2 * h);
        const Eigen::AngleAxisd turn(plus.linear() * minus.linear().transpose());
        const Eigen::Vector3d angular = turn.angle() * turn.axis() / (2 * h);
        EXPECT_LT((jacobian.col(j).head<3>() - linear).norm(), 1e-6) << path << " joint " << j;
        EXPECT_LT((jacobian.col(j).tail<3>() - angular).norm(), 1e-6) << path << " joint " << j;
      }
    }
  }
}

TEST(KinematicChain, UnknownTipIsAnInputError) {
  const RobotModel robot = loadUrdf(kKr5);
  EXPECT_THROW(KinematicChain(robot, "no_such_link"), InputError);
}

}  // namespace
}  // namespace kaboum::kinematics
