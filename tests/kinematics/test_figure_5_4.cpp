// Coverage of constraint sampling in the two scenarios of thesis Figure 5.4 (§5.2.4), on the
// KR5 six-axis arm: samples must satisfy the constraints and cover the constraint space.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/constraint_sampler.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using Shape = PrimitiveShape;

Pose translation(double x, double y, double z) {
  return Pose(Eigen::Translation3d(x, y, z));
}

// KR5 with base_link at the world origin; tool z along the roll axis, centre 0.1 m out.
struct Kr5 {
  RobotModel model = loadUrdf(test::kKr5);
  KinematicChain chain{model};
  Pose base = Pose::Identity();
  Pose tool = translation(0.1, 0, 0) *
              Pose(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()));
  Kr5() {
    std::vector<Pose> poses(model.links().size());
    model.linkPoses(std::vector<double>(6, 0.0), poses);
    base = poses[static_cast<std::size_t>(*model.findLink("base_link"))].inverse();
  }
};

// Figure 5.4a: Parallel(Plane tool_z, Plane table) ∧ Distance(Point tool_centre, Plane table) =
// object height. The reachable y range comes independently from the closed-form IK: y values for
// which some x on a 2 cm grid, tool yaw (45° steps) and tool up/down admits a solution at either
// height (the distance is unsigned). The samples' y histogram (5 cm bins) has no empty bin over
// that range, and no sample lies outside it.
TEST(Figure54, PlacingOnATableCoversTheReachableRangeAlongY) {
  Kr5 kr5;
  const double height = 0.15;
  ConstraintProblem problem;
  problem.addRobot(kr5.chain, kr5.base);
  const auto toolPlane = problem.attachToTool(0, kr5.tool, Shape::makePlane({0, 0, 0}, {0, 0, 1}));
  const auto toolCenter = problem.attachToTool(0, kr5.tool, Shape::makePoint({0, 0, 0}));
  const auto table =
      problem.attachToObject(Pose::Identity(), Shape::makePlane({0, 0, 0}, {0, 0, 1}));
  problem.addConstraint(ConstraintType::Parallel, toolPlane, table);
  problem.addConstraint(ConstraintType::Distance, toolCenter, table, height);

  const auto ik = ArmIk::fit(kr5.chain);
  ASSERT_TRUE(ik);
  const double step = 0.02;
  double lowest = 1e9, highest = -1e9;
  ArmIk::Solutions solutions;
  for (double y = -1.0; y <= 1.0; y += step) {
    bool reachable = false;
    for (double x = -1.0; x <= 1.0 && !reachable; x += step) {
      for (const double z : {height, -height}) {
        for (const double flip : {0.0, std::numbers::pi}) {
          for (int yaw = 0; yaw < 8 && !reachable; ++yaw) {
            const Pose toolPose =
                translation(x, y, z) *
                Pose(Eigen::AngleAxisd(yaw * std::numbers::pi / 4, Eigen::Vector3d::UnitZ())) *
                Pose(Eigen::AngleAxisd(flip, Eigen::Vector3d::UnitX()));
            ik->solve(kr5.base.inverse() * toolPose * kr5.tool.inverse(), solutions);
            reachable = solutions.count > 0;
          }
        }
      }
    }
    if (reachable) {
      lowest = std::min(lowest, y);
      highest = std::max(highest, y);
    }
  }
  ASSERT_LT(lowest, -0.4);
  ASSERT_GT(highest, 0.4);

  ConstraintSampler sampler(problem, {.seed = 2});
  const double binWidth = 0.05;
  const int bins = static_cast<int>(std::floor((highest - lowest) / binWidth));
  std::vector<int> histogram(static_cast<std::size_t>(bins), 0);
  std::vector<double> q(6);
  Eigen::VectorXd cost;
  int successes = 0;
  for (int i = 0; i < 3000; ++i) {
    if (!sampler.sample(q)) continue;
    ++successes;
    problem.evaluate(q, cost);
    ASSERT_LT(cost.norm(), 1e-6);
    ASSERT_TRUE(kr5.chain.withinLimits(q));
    const double y = (kr5.base * kr5.chain.toolPose(q) * kr5.tool).translation().y();
    EXPECT_GE(y, lowest - step);
    EXPECT_LE(y, highest + step);
    const int bin = static_cast<int>(std::floor((y - lowest) / binWidth));
    if (bin >= 0 && bin < bins) ++histogram[static_cast<std::size_t>(bin)];
  }
  EXPECT_GT(successes, 2900);
  for (int b = 0; b < bins; ++b) {
    EXPECT_GT(histogram[static_cast<std::size_t>(b)], 0)
        << "no sample with y in [" << lowest + b * binWidth << ", " << lowest + (b + 1) * binWidth
        << ")";
  }
}

// Figure 5.4b: grasping a cylinder at its rim: Parallel(Line tool_z, Line cylinder_axis) ∧
// Distance(Point tool_centre, Line cylinder_axis) = radius ∧ Coincident(Line tool_x, Plane
// cylinder_top). The grasp angle around the axis is sampled over all of ]−π, π]: 24 bins of 15°,
// none empty.
TEST(Figure54, GraspingACylinderRimCoversAllGraspAngles) {
  Kr5 kr5;
  const Eigen::Vector3d axisPoint(0.4, 0.0, 0.0);
  const double radius = 0.04, top = 0.2;
  ConstraintProblem problem;
  problem.addRobot(kr5.chain, kr5.base);
  const auto toolZ = problem.attachToTool(0, kr5.tool, Shape::makeLine({0, 0, 0}, {0, 0, 1}));
  const auto toolX = problem.attachToTool(0, kr5.tool, Shape::makeLine({0, 0, 0}, {1, 0, 0}));
  const auto toolCenter = problem.attachToTool(0, kr5.tool, Shape::makePoint({0, 0, 0}));
  const auto axis = problem.attachToObject(Pose::Identity(), Shape::makeLine(axisPoint, {0, 0, 1}));
  const auto topPlane =
      problem.attachToObject(Pose::Identity(), Shape::makePlane({0.4, 0.0, top}, {0, 0, 1}));
  problem.addConstraint(ConstraintType::Parallel, toolZ, axis);
  problem.addConstraint(ConstraintType::Distance, toolCenter, axis, radius);
  problem.addConstraint(ConstraintType::Coincident, toolX, topPlane);

  ConstraintSampler sampler(problem, {.seed = 5});
  constexpr int kBins = 24;
  std::array<int, kBins> histogram{};
  std::vector<double> q(6);
  int successes = 0;
  for (int i = 0; i < 1200; ++i) {
    if (!sampler.sample(q)) continue;
    ++successes;
    const Pose tool = kr5.base * kr5.chain.toolPose(q) * kr5.tool;
    const Eigen::Vector3d offset = tool.translation() - axisPoint;
    ASSERT_NEAR(offset.head<2>().norm(), radius, 1e-6);
    ASSERT_NEAR(offset.z(), top, 1e-6);
    ASSERT_GT(std::abs(tool.linear().col(2).z()), 1 - 1e-9);
    const double angle = std::atan2(offset.y(), offset.x());
    const int bin = std::min(
        kBins - 1, static_cast<int>((angle + std::numbers::pi) / (2 * std::numbers::pi) * kBins));
    ++histogram[static_cast<std::size_t>(bin)];
  }
  EXPECT_GT(successes, 1100);
  for (int b = 0; b < kBins; ++b)
    EXPECT_GT(histogram[static_cast<std::size_t>(b)], 0) << "bin " << b;
}

}  // namespace
}  // namespace kaboum::kinematics
