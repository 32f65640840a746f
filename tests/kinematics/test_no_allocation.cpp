// Hot paths allocate nothing per call: FK, Jacobian, closed-form and numeric IK, constraint
// evaluation and sampling. Counts global operator new calls around each call.
#include <gtest/gtest.h>

#include <numbers>

#include "../support/allocation_counter.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/constraint_sampler.hpp"
#include "kaboum/kinematics/numeric_ik.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using kaboum::test::allocationsDuring;

TEST(NoAllocation, KinematicsHotPaths) {
  const RobotModel kr5 = loadUrdf(test::kKr5);
  const KinematicChain chain(kr5);
  const auto ik = ArmIk::fit(chain);
  ASSERT_TRUE(ik);
  std::vector<double> q{0.1, 0.2, -0.3, 0.4, 0.5, 0.6}, solution(6);
  std::vector<Pose> poses(kr5.links().size());
  Jacobian jacobian(6, 6);
  ArmIk::Solutions solutions;
  NumericIk numeric(chain);
  const Pose target = chain.toolPose(q);
  EXPECT_GT(allocationsDuring([&] { const KinematicChain copy(kr5); }), 0);  // counter works
  EXPECT_EQ(allocationsDuring([&] { kr5.linkPoses(q, poses); }), 0);
  EXPECT_EQ(allocationsDuring([&] { (void)chain.toolPoseAndJacobian(q, jacobian); }), 0);
  EXPECT_EQ(allocationsDuring([&] { ik->solve(target, solutions); }), 0);
  EXPECT_EQ(allocationsDuring([&] { ASSERT_TRUE(numeric.solve(target, {}, solution)); }), 0);

  ConstraintProblem problem;
  problem.addRobot(chain);
  const auto center =
      problem.attachToTool(0, Pose::Identity(), PrimitiveShape::makePoint({0, 0, 0}));
  const auto axis =
      problem.attachToTool(0, Pose::Identity(), PrimitiveShape::makeLine({0, 0, 0}, {1, 0, 0}));
  const auto plane =
      problem.attachToObject(Pose::Identity(), PrimitiveShape::makePlane({0, 0, 0.3}, {0, 0, 1}));
  problem.addConstraint(ConstraintType::Distance, center, plane, 0.1);
  problem.addConstraint(ConstraintType::Parallel, axis, plane);
  ConstraintSampler sampler(problem);
  Eigen::VectorXd cost(problem.costDimension());
  Eigen::MatrixXd costJacobian(problem.costDimension(), problem.dof());
  EXPECT_EQ(allocationsDuring([&] { problem.evaluate(q, cost, costJacobian); }), 0);
  EXPECT_EQ(allocationsDuring([&] { ASSERT_TRUE(sampler.sample(q)); }), 0);
}

}  // namespace
}  // namespace kaboum::kinematics
