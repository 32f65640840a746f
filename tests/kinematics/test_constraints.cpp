#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kaboum/core/error.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/constraint_problem.hpp"
#include "kaboum/kinematics/constraint_sampler.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using Kind = PrimitiveShape::Kind;
using Shape = PrimitiveShape;

Pose translation(double x, double y, double z) {
  return Pose(Eigen::Translation3d(x, y, z));
}

// Cost of one constraint between two fixed object shapes (no robot: F has no variables).
Eigen::VectorXd objectCost(ConstraintType type, const Shape& first, const Shape& second,
                           double distance = 0) {
  ConstraintProblem problem;
  const auto a = problem.attachToObject(Pose::Identity(), first);
  const auto b = problem.attachToObject(Pose::Identity(), second);
  problem.addConstraint(type, a, b, distance);
  Eigen::VectorXd cost;
  problem.evaluate({}, cost);
  return cost;
}

// Table 5.1 values and dimensions on hand-checked configurations.
TEST(GeometricConstraint, CostFunctionsOfTable51) {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                        z = Eigen::Vector3d::UnitZ(), o = Eigen::Vector3d::Zero();
  using T = ConstraintType;
  // Coincident point–point: p1 − p2.
  EXPECT_TRUE(objectCost(T::Coincident, Shape::makePoint({1, 2, 3}), Shape::makePoint(o))
                  .isApprox(Eigen::Vector3d(1, 2, 3)));
  // Coincident point–line: 2 components, the perpendicular offset.
  EXPECT_EQ(objectCost(T::Coincident, Shape::makePoint({5, 0, 0}), Shape::makeLine(o, x)).size(),
            2);
  EXPECT_NEAR(objectCost(T::Coincident, Shape::makePoint({5, 0, 0}), Shape::makeLine(o, x)).norm(),
              0, 1e-15);
  EXPECT_NEAR(
      objectCost(T::Coincident, Shape::makePoint({5, 0.3, 0.4}), Shape::makeLine(o, x)).norm(), 0.5,
      1e-15);
  // Coincident point–plane: signed height.
  EXPECT_NEAR(objectCost(T::Coincident, Shape::makePoint({1, 1, -0.2}), Shape::makePlane(o, z))(0),
              -0.2, 1e-15);
  // Coincident line–line: 4 components; zero for the same line with any anchor and direction sign.
  EXPECT_EQ(objectCost(T::Coincident, Shape::makeLine(o, x), Shape::makeLine({3, 0, 0}, -x)).size(),
            4);
  EXPECT_NEAR(
      objectCost(T::Coincident, Shape::makeLine(o, x), Shape::makeLine({3, 0, 0}, -x)).norm(), 0,
      1e-15);
  EXPECT_GT(objectCost(T::Coincident, Shape::makeLine(o, x), Shape::makeLine(o, y)).norm(), 0.9);
  // Coincident line–plane (Figure 5.4b): line inside the plane.
  EXPECT_NEAR(
      objectCost(T::Coincident, Shape::makeLine({0, 0, 1}, x), Shape::makePlane({0, 0, 1}, z))
          .norm(),
      0, 1e-15);
  EXPECT_GT(objectCost(T::Coincident, Shape::makeLine({0, 0, 1}, z), Shape::makePlane({0, 0, 1}, z))
                .norm(),
            0.9);
  // Coincident plane–plane: 3 components, zero for opposite normals too.
  EXPECT_EQ(objectCost(T::Coincident, Shape::makePlane(x, z), Shape::makePlane(y, -z)).size(), 3);
  EXPECT_NEAR(objectCost(T::Coincident, Shape::makePlane(x, z), Shape::makePlane(y, -z)).norm(), 0,
              1e-15);
  // Parallel line–line and plane–plane: 2 components; line–plane and perpendicular: 1.
  EXPECT_NEAR(objectCost(T::Parallel, Shape::makeLine(o, x), Shape::makeLine({0, 5, 1}, -x)).norm(),
              0, 1e-15);
  EXPECT_NEAR(objectCost(T::Parallel, Shape::makeLine(o, x), Shape::makeLine(o, y)).norm(), 1,
              1e-15);
  EXPECT_EQ(objectCost(T::Parallel, Shape::makePlane(o, z), Shape::makePlane(x, z)).size(), 2);
  EXPECT_NEAR(objectCost(T::Parallel, Shape::makePlane(o, z), Shape::makePlane(x, z)).norm(), 0,
              1e-15);
  EXPECT_NEAR(objectCost(T::Parallel, Shape::makeLine(o, x), Shape::makePlane(o, z))(0), 0, 1e-15);
  EXPECT_NEAR(objectCost(T::Parallel, Shape::makeLine(o, z), Shape::makePlane(o, z))(0), 1, 1e-15);
  EXPECT_NEAR(objectCost(T::Perpendicular, Shape::makePlane(o, x), Shape::makePlane(o, y))(0), 0,
              1e-15);
  // Distances: norm minus d; the point–plane distance is unsigned.
  EXPECT_NEAR(objectCost(T::Distance, Shape::makePoint({3, 4, 0}), Shape::makePoint(o), 2)(0), 3,
              1e-15);
  EXPECT_NEAR(objectCost(T::Distance, Shape::makePoint({7, 3, 4}), Shape::makeLine(o, x), 1)(0), 4,
              1e-15);
  EXPECT_NEAR(
      objectCost(T::Distance, Shape::makePoint({1, 1, -0.5}), Shape::makePlane(o, z), 0.5)(0), 0,
      1e-15);
}

TEST(GeometricConstraint, IncompatiblePrimitivesAreInputErrors) {
  const Shape point = Shape::makePoint({0, 0, 0});
  const Shape line = Shape::makeLine({0, 0, 0}, {1, 0, 0});
  const Shape plane = Shape::makePlane({0, 0, 0}, {0, 0, 1});
  using T = ConstraintType;
  EXPECT_THROW(objectCost(T::Parallel, point, line), InputError);
  EXPECT_THROW(objectCost(T::Perpendicular, line, line), InputError);
  EXPECT_THROW(objectCost(T::Distance, line, line), InputError);
  EXPECT_THROW(objectCost(T::Coincident, plane, point), InputError);
  EXPECT_THROW(objectCost(T::Distance, point, point, -1.0), InputError);
  try {
    objectCost(T::Parallel, point, plane);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "Parallel(Point, Plane) is not a defined constraint (Table 5.1)");
  }
  ConstraintProblem problem;
  EXPECT_THROW(problem.addConstraint(T::Coincident, 0, 1), InputError);
}

// Analytic ∂F/∂q equals central differences for every cost function, with shapes on two robots
// and on objects, including two shapes on the same robot.
TEST(ConstraintProblem, AnalyticJacobianMatchesCentralDifferences) {
  const RobotModel kr5 = loadUrdf(test::kKr5);
  const RobotModel comau = loadUrdf(test::kComauRight);
  const KinematicChain arm(kr5), other(comau);
  const Pose tool = translation(0.1, 0.02, 0) *
                    Pose(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()));
  const Shape shapes[] = {Shape::makePoint({0.01, 0.02, 0.03}),
                          Shape::makeLine({0.0, 0.01, 0.0}, {0.2, 0.1, 1.0}),
                          Shape::makePlane({0.02, 0.0, 0.01}, {0.3, -0.2, 1.0})};
  using T = ConstraintType;
  const T types[] = {T::Coincident, T::Parallel, T::Perpendicular, T::Distance};
  std::mt19937_64 rng(21);
  int checked = 0;
  for (const T type : types) {
    for (const Shape& first : shapes) {
      for (const Shape& second : shapes) {
        ConstraintProblem problem;
        problem.addRobot(arm, translation(0, 0.3, 0));
        problem.addRobot(other, translation(1.0, -0.5, 0.2));
        const auto onArm = problem.attachToTool(0, tool, first);
        const auto onOther = problem.attachToTool(1, Pose::Identity(), second);
        const auto onArmToo = problem.attachToTool(0, translation(0, 0.05, 0), second);
        const auto onObject = problem.attachToObject(translation(0.5, 0.1, 0.3), second);
        try {
          problem.addConstraint(type, onArm, onOther, 0.1);
        } catch (const InputError&) {
          continue;  // not a Table 5.1 pair
        }
        problem.addConstraint(type, onArm, onArmToo, 0.1);
        problem.addConstraint(type, onArm, onObject, 0.1);
        Eigen::VectorXd cost, reference;
        Eigen::MatrixXd analytic, numeric;
        for (int trial = 0; trial < 5; ++trial) {
          std::vector<double> q = test::randomConfiguration(arm, rng);
          const std::vector<double> q2 = test::randomConfiguration(other, rng);
          q.insert(q.end(), q2.begin(), q2.end());
          problem.evaluate(q, cost, analytic, JacobianMode::Analytic);
          problem.evaluate(q, reference, numeric, JacobianMode::CentralDifferences);
          EXPECT_TRUE(cost.isApprox(reference, 1e-12));
          EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6)
              << toString(type) << "(" << toString(first.kind) << ", " << toString(second.kind)
              << ")";
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 13 * 5);  // every cost function of Table 5.1 plus Coincident(Line, Plane)
}

// The KR5 with its base link at the world origin (z up) and a tool frame whose z axis is the
// last (roll) axis, 0.1 m beyond the flange.
struct Kr5Setup {
  RobotModel model = loadUrdf(test::kKr5);
  KinematicChain chain{model};
  Pose base = Pose::Identity();
  Pose tool = translation(0.1, 0, 0) *
              Pose(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()));
  Kr5Setup() {
    std::vector<Pose> poses(model.links().size());
    model.linkPoses(std::vector<double>(6, 0.0), poses);
    base = poses[static_cast<std::size_t>(*model.findLink("base_link"))].inverse();
  }
};

// §5.2.3: a distance-to-line constraint started exactly on the line must still move off it.
TEST(ConstraintSampler, LeavesTheLineOfAPointLineDistance) {
  Kr5Setup kr5;
  ConstraintProblem problem;
  problem.addRobot(kr5.chain, kr5.base);
  const auto center = problem.attachToTool(0, kr5.tool, Shape::makePoint({0, 0, 0}));
  const std::vector<double> start{0.3, 0.4, -0.6, 0.2, 0.5, 0.1};
  const Eigen::Vector3d onLine = problem.worldShape(center, start).point;
  const auto line = problem.attachToObject(Pose::Identity(), Shape::makeLine(onLine, {0, 0, 1}));
  problem.addConstraint(ConstraintType::Distance, center, line, 0.05);
  ConstraintSampler sampler(problem);
  std::vector<double> q = start;
  ASSERT_TRUE(sampler.project(q));
  const Eigen::Vector3d moved = problem.worldShape(center, q).point;
  EXPECT_NEAR((moved - onLine).head<2>().norm(), 0.05, 1e-6);
}

TEST(ConstraintSampler, ImpossibleConstraintsFailAfterBoundedWork) {
  Kr5Setup kr5;
  ConstraintProblem problem;
  problem.addRobot(kr5.chain, kr5.base);
  const auto center = problem.attachToTool(0, kr5.tool, Shape::makePoint({0, 0, 0}));
  const auto far = problem.attachToObject(Pose::Identity(), Shape::makePoint({5, 0, 0}));
  problem.addConstraint(ConstraintType::Coincident, center, far);
  ConstraintSampler sampler(problem, {.maxIterations = 50, .maxAttempts = 3});
  std::vector<double> q(6);
  EXPECT_FALSE(sampler.sample(q));
  EXPECT_EQ(sampler.lastAttempts(), 3);
  EXPECT_GT(sampler.lastCostNorm(), 1.0);
  EXPECT_TRUE(kr5.chain.withinLimits(q));
}

TEST(ConstraintSampler, SameSeedSameSamples) {
  Kr5Setup kr5;
  ConstraintProblem problem;
  problem.addRobot(kr5.chain, kr5.base);
  const auto center = problem.attachToTool(0, kr5.tool, Shape::makePoint({0, 0, 0}));
  const auto plane =
      problem.attachToObject(Pose::Identity(), Shape::makePlane({0, 0, 0.3}, {0, 0, 1}));
  problem.addConstraint(ConstraintType::Coincident, center, plane);
  ConstraintSampler first(problem, {.seed = 9}), second(problem, {.seed = 9});
  std::vector<double> a(6), b(6);
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(first.sample(a));
    ASSERT_TRUE(second.sample(b));
    EXPECT_EQ(a, b);
  }
}

// Two Comau arms of the bimanual scenario (bases from scene.wrl) hand over: tool centres
// coincide and tool axes are anti-parallel lines; every sample satisfies both by independent FK.
TEST(ConstraintSampler, BimanualConstraintBetweenTwoTools) {
  const RobotModel left = loadUrdf(test::kComauLeft);
  const RobotModel right = loadUrdf(test::kComauRight);
  const KinematicChain leftArm(left, "body6"), rightArm(right);
  ConstraintProblem problem;
  problem.addRobot(leftArm, translation(0, 0.57, 0));
  problem.addRobot(rightArm, translation(0.1, -0.57, 0));
  const Pose gripper = translation(0, 0, 0.2);
  const auto leftCenter = problem.attachToTool(0, gripper, Shape::makePoint({0, 0, 0}));
  const auto rightCenter = problem.attachToTool(1, gripper, Shape::makePoint({0, 0, 0}));
  const auto leftAxis = problem.attachToTool(0, gripper, Shape::makeLine({0, 0, 0}, {0, 0, 1}));
  const auto rightAxis = problem.attachToTool(1, gripper, Shape::makeLine({0, 0, 0}, {0, 0, 1}));
  problem.addConstraint(ConstraintType::Coincident, leftCenter, rightCenter);
  problem.addConstraint(ConstraintType::Coincident, leftAxis, rightAxis);
  ConstraintSampler sampler(problem, {.seed = 4});
  std::vector<double> q(12);
  int successes = 0;
  for (int i = 0; i < 20; ++i) {
    if (!sampler.sample(q)) continue;
    ++successes;
    const Pose l = translation(0, 0.57, 0) * leftArm.toolPose(std::span(q).first(6)) * gripper;
    const Pose r = translation(0.1, -0.57, 0) * rightArm.toolPose(std::span(q).last(6)) * gripper;
    EXPECT_LT((l.translation() - r.translation()).norm(), 1e-5);
    EXPECT_GT(std::abs(l.linear().col(2).dot(r.linear().col(2))), 1 - 1e-9);
    EXPECT_TRUE(leftArm.withinLimits(std::span(q).first(6)));
    EXPECT_TRUE(rightArm.withinLimits(std::span(q).last(6)));
  }
  EXPECT_GE(successes, 18);
}

}  // namespace
}  // namespace kaboum::kinematics
