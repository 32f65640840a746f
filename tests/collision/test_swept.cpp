// Swept volumes (§4.5): the swept support mapping is the hull of both poses, and dense exact
// sampling along motions never finds a collision the swept predicates called free.
#include <gtest/gtest.h>

#include "collision_test_support.hpp"
#include "kaboum/collision/swept.hpp"
#include "kaboum/kinematics/urdf_loader.hpp"

namespace kaboum::collision {
namespace {

TEST(SweptSupport, IsTheSupportOfBothPoses) {
  std::mt19937_64 rng(2);
  const CollisionBody body(test::randomConvexSets(rng, 1, 40, 0.2), "piece");
  for (int i = 0; i < 200; ++i) {
    const Pose start = test::randomPose(rng, 1.0), end = test::randomPose(rng, 1.0);
    const SweptPiece swept(TransformedSupport(body.piece(0), start),
                           TransformedSupport(body.piece(0), end));
    SweptPiece::Hint hint;
    const Vec3 d = test::randomPoint(rng, 1.0);
    double best = -1e300;
    for (const Vec3& v : body.piece(0).vertices()) {
      best = std::max({best, d.dot(start * v), d.dot(end * v)});
    }
    EXPECT_NEAR(d.dot(swept.support(d, hint)), best, 1e-12);
  }
}

// Obstacles scattered around the KR5's workspace.
CollisionScene scatteredBoxes(std::mt19937_64& rng, int count) {
  CollisionScene scene;
  for (int i = 0; i < count; ++i) {
    Vec3 centre = test::randomPoint(rng, 0.8);
    centre.z() = 0.2 + 0.5 * uniformUnit(rng);
    scene.add(test::boxBody(Vec3::Constant(-0.04), Vec3::Constant(0.04)),
              Pose(Eigen::Translation3d(centre)));
  }
  return scene;
}

std::vector<double> randomQ(const RobotModel& model, std::mt19937_64& rng) {
  std::vector<double> q(static_cast<std::size_t>(model.dof()));
  for (int v = 0; v < model.dof(); ++v) {
    const Joint& joint = model.variableJoint(v);
    q[static_cast<std::size_t>(v)] = joint.lower + uniformUnit(rng) * (joint.upper - joint.lower);
  }
  return q;
}

// Exact checks (margin 0) at `samples` + 1 evenly spaced configurations of qa -> qb.
bool denseSamplingCollides(const RobotCollisionModel& robot, std::span<const double> qa,
                           std::span<const double> qb, const CollisionScene& scene, int samples) {
  std::vector<Pose> poses(robot.model().links().size());
  std::vector<double> q(qa.size());
  for (int s = 0; s <= samples; ++s) {
    for (std::size_t v = 0; v < q.size(); ++v) q[v] = qa[v] + s * (qb[v] - qa[v]) / samples;
    robot.model().linkPoses(q, poses);
    if (robot.firstSceneCollision(poses, scene, 0.0)) return true;
  }
  return false;
}

TEST(RobotSweep, DenseSamplingNeverFindsACollisionTheSweepCalledFree) {
  RobotCollisionModel robot(loadUrdf(test::kKr5));
  const int palm = *robot.model().findLink("palm");
  robot.attach(test::boxBody(Vec3(0, -0.02, -0.02), Vec3(0.25, 0.02, 0.02)), palm,
               Pose::Identity());
  RobotSweep sweep(robot);
  std::mt19937_64 rng(8);
  const CollisionScene scene = scatteredBoxes(rng, 15);
#if defined(__SANITIZE_ADDRESS__)
  const int motions = 40;
#else
  const int motions = 300;
#endif
  const double epsilon = 0.005;
  int sweptCollisions = 0, sampledCollisions = 0;
  for (int m = 0; m < motions; ++m) {
    const auto qa = randomQ(robot.model(), rng);
    auto qb = randomQ(robot.model(), rng);
    for (std::size_t v = 0; v < qb.size(); ++v) qb[v] = qa[v] + 0.5 * (qb[v] - qa[v]);
    const bool swept = sweep.firstSceneCollision(qa, qb, scene, 0.0, epsilon).has_value();
    const bool sampled = denseSamplingCollides(robot, qa, qb, scene, 400);
    if (sampled) {
      EXPECT_TRUE(swept) << "motion " << m << " collides between samples";
    }
    sweptCollisions += swept;
    sampledCollisions += sampled;
  }
  EXPECT_GT(sampledCollisions, motions / 10);
  EXPECT_LT(sweptCollisions, motions);
  // Single-sided but tight: the sweep rarely reports a collision dense sampling does not see.
  EXPECT_LE(sweptCollisions - sampledCollisions, motions / 20);
}

TEST(RobotSweep, StepsShrinkWithEpsilonAndAStillRobotNeedsOne) {
  const RobotCollisionModel robot(loadUrdf(test::kKr5));
  RobotSweep sweep(robot);
  const std::vector<double> qa{0, 0, 0, 0, 0, 0}, qb{1, -0.5, 0.5, 1, 1, 1};
  sweep.sweep(qa, qa, 0.001);
  EXPECT_EQ(sweep.sampleCount(), 2U);
  sweep.sweep(qa, qb, 0.004);
  const auto coarse = sweep.sampleCount();
  sweep.sweep(qa, qb, 0.001);
  EXPECT_GE(sweep.sampleCount(), 2 * coarse - 1) << "Proposition 3: 4x precision, 2x samples";
}

TEST(SweptVolumes, DenseSamplingNeverFindsACollisionTheSweepsCalledFree) {
  // Two KR5s facing each other 0.9 m apart; the volumes are compared regardless of timing.
  const RobotModel model = loadUrdf(test::kKr5);
  const Pose offset(Eigen::Translation3d(0.9, 0, 0) * Eigen::AngleAxisd(3.14159, Vec3::UnitY()));
  RobotCollisionModel left(model), right(model);
  right.setBasePose(offset);
  RobotSweep sweepLeft(left), sweepRight(right);
  std::mt19937_64 rng(12);
  std::vector<Pose> a(model.links().size()), b(model.links().size());
#if defined(__SANITIZE_ADDRESS__)
  const int motions = 10;
#else
  const int motions = 60;
#endif
  int collisions = 0;
  const double epsilon = 0.005;
  for (int m = 0; m < motions; ++m) {
    const auto qa0 = randomQ(model, rng), qa1 = randomQ(model, rng);
    const auto qb0 = randomQ(model, rng), qb1 = randomQ(model, rng);
    const bool swept = sweptVolumesCollide(sweepLeft, qa0, qa1, sweepRight, qb0, qb1, 0, epsilon);
    collisions += swept;
    if (swept) continue;
    std::vector<double> qa(6), qb(6);
    for (int i = 0; i <= 40; ++i) {
      for (std::size_t v = 0; v < 6; ++v) qa[v] = qa0[v] + i * (qa1[v] - qa0[v]) / 40;
      model.linkPoses(qa, a);
      for (int j = 0; j <= 40; ++j) {
        for (std::size_t v = 0; v < 6; ++v) qb[v] = qb0[v] + j * (qb1[v] - qb0[v]) / 40;
        model.linkPoses(qb, b);
        for (std::size_t p = 0; p < left.partCount(); ++p) {
          for (std::size_t r = 0; r < right.partCount(); ++r) {
            ASSERT_FALSE(bodiesCollide(*left.part(p).body, left.partPose(p, a), *right.part(r).body,
                                       right.partPose(r, b), 0.0))
                << "motion " << m << " samples " << i << ", " << j;
          }
        }
      }
    }
  }
  EXPECT_GT(collisions, 0);
  EXPECT_LT(collisions, motions);
}

}  // namespace
}  // namespace kaboum::collision
