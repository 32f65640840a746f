#include <gtest/gtest.h>

#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/numeric_ik.hpp"
#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

// Random reachable poses of the 7-DOF WAM (FK of random configurations) are solved from random
// starts, within limits, to the requested tolerance.
TEST(NumericIk, SolvesRandomReachableWamPoses) {
  const RobotModel wam = loadUrdf(test::kWam);
  const KinematicChain chain(wam);
  ASSERT_EQ(chain.dof(), 7);
  NumericIk ik(chain, {.seed = 3});
  std::mt19937_64 rng(17);
  std::vector<double> solution(7);
  int solved = 0;
  const int trials = 100;
  for (int trial = 0; trial < trials; ++trial) {
    const Pose target = chain.toolPose(test::randomConfiguration(chain, rng));
    if (!ik.solve(target, {}, solution)) continue;
    ++solved;
    const Pose reached = chain.toolPose(solution);
    EXPECT_LT((reached.translation() - target.translation()).norm(), 1e-6);
    EXPECT_LT(Eigen::AngleAxisd(reached.linear() * target.linear().transpose()).angle(), 1e-6);
    EXPECT_TRUE(chain.withinLimits(solution));
  }
  EXPECT_GE(solved, 98);
}

TEST(NumericIk, StartsFromTheInitialGuessAndIsDeterministic) {
  const RobotModel wam = loadUrdf(test::kWam);
  const KinematicChain chain(wam);
  const std::vector<double> q{0.3, -0.5, 0.2, 1.2, -0.4, 0.6, 0.1};
  const Pose target = chain.toolPose(q);
  NumericIk ik(chain);
  std::vector<double> near = q, solution(7);
  near[3] += 0.01;
  ASSERT_TRUE(ik.solve(target, near, solution));
  EXPECT_EQ(ik.startsUsed(), 1);
  for (std::size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(solution[i], q[i], 0.05);
  NumericIk first(chain, {.seed = 8}), second(chain, {.seed = 8});
  std::vector<double> a(7), b(7);
  ASSERT_TRUE(first.solve(target, {}, a));
  ASSERT_TRUE(second.solve(target, {}, b));
  EXPECT_EQ(a, b);
}

TEST(NumericIk, ReportsUnreachableTargets) {
  const RobotModel wam = loadUrdf(test::kWam);
  const KinematicChain chain(wam);
  NumericIk ik(chain, {.maxStarts = 5});
  Pose far = Pose::Identity();
  far.translation() = Eigen::Vector3d(3, 0, 0);
  std::vector<double> solution(7);
  EXPECT_FALSE(ik.solve(far, {}, solution));
  EXPECT_EQ(ik.startsUsed(), 5);
}

}  // namespace
}  // namespace kaboum::kinematics
