// Swept volumes (§4.5): the swept support mapping is the hull of both poses, and dense exact
// sampling along motions never finds a collision the swept predicates called free.
#include <gtest/gtest.h>

#include "collision_test_support.hpp"
#include "kaboum/collision/swept.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/testing/robot_collision_models.hpp"

namespace kaboum::collision {

using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;

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

// Exact checks (margin 0) at `samples` + 1 evenly spaced configurations of qa -> qb, holding
// `held`.
bool denseSamplingCollides(const RobotCollisionModel& robot, std::span<const Attachment> held,
                           std::span<const double> qa, std::span<const double> qb,
                           const CollisionScene& scene, int samples) {
  std::vector<Pose> poses(robot.model().links().size());
  std::vector<double> q(qa.size());
  for (int s = 0; s <= samples; ++s) {
    for (std::size_t v = 0; v < q.size(); ++v) q[v] = qa[v] + s * (qb[v] - qa[v]) / samples;
    robot.model().linkPoses(q, poses);
    if (robot.firstSceneCollision(poses, held, scene, {}, 0.0)) return true;
  }
  return false;
}

TEST(RobotSweep, DenseSamplingNeverFindsACollisionTheSweepCalledFree) {
  const RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  const int palm = *robot.model().findLink("palm");
  const std::vector<Attachment> held{
      {test::boxBody(Vec3(0, -0.02, -0.02), Vec3(0.25, 0.02, 0.02)), palm, Pose::Identity()}};
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
    const auto qa = randomConfiguration(robot.model(), rng);
    auto qb = randomConfiguration(robot.model(), rng);
    for (std::size_t v = 0; v < qb.size(); ++v) qb[v] = qa[v] + 0.5 * (qb[v] - qa[v]);
    const bool swept = sweep.firstSceneCollision(qa, qb, held, scene, {}, 0.0, epsilon).has_value();
    const bool sampled = denseSamplingCollides(robot, held, qa, qb, scene, 400);
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
  const RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  RobotSweep sweep(robot);
  const std::vector<double> qa{0, 0, 0, 0, 0, 0}, qb{1, -0.5, 0.5, 1, 1, 1};
  sweep.sweep(qa, qa, {}, 0.001);
  EXPECT_EQ(sweep.sampleCount(), 2U);
  sweep.sweep(qa, qb, {}, 0.004);
  const auto coarse = sweep.sampleCount();
  sweep.sweep(qa, qb, {}, 0.001);
  EXPECT_GE(sweep.sampleCount(), 2 * coarse - 1) << "Proposition 3: 4x precision, 2x samples";
}

// Exact self-collision checks (margin 0) at `samples` + 1 evenly spaced configurations, holding
// `held`; returns the first colliding sample, or -1.
int firstSelfCollidingSample(const RobotCollisionModel& robot, std::span<const double> qa,
                             std::span<const double> qb, int samples,
                             std::span<const Attachment> held = {}) {
  std::vector<Pose> poses(robot.model().links().size());
  std::vector<double> q(qa.size());
  for (int s = 0; s <= samples; ++s) {
    for (std::size_t v = 0; v < q.size(); ++v) q[v] = qa[v] + s * (qb[v] - qa[v]) / samples;
    robot.model().linkPoses(q, poses);
    if (robot.selfCollides(poses, held, 0.0)) return s;
  }
  return -1;
}

TEST(RobotSweep, SelfCollisionOnlyInTheMiddleOfAMotionIsCaught) {
  const RobotCollisionModel robot = test::kr5AllowingHomeOverlaps();
  RobotSweep sweep(robot);
  // Found by random search: shoulder, elbow and wrist pitch move, the palm passes through the
  // base between two self-collision-free end configurations.
  const std::vector<double> qa{2.723, -1.592, 0.895, -2.127, 1.829, 5.203};
  const std::vector<double> qb{2.723, -1.385, -2.445, -2.127, 1.304, 5.203};
  ASSERT_EQ(firstSelfCollidingSample(robot, qa, qa, 1), -1);
  ASSERT_EQ(firstSelfCollidingSample(robot, qb, qb, 1), -1);
  ASSERT_GT(firstSelfCollidingSample(robot, qa, qb, 400), 0);
  for (const double epsilon : {0.001, 0.005, 0.02}) {
    EXPECT_TRUE(sweep.selfCollides(qa, qb, {}, 0.0, epsilon)) << "epsilon " << epsilon;
  }
}

TEST(RobotSweep, DenseSamplingNeverFindsASelfCollisionTheSweepCalledFree) {
  const RobotCollisionModel robot = test::kr5AllowingHomeOverlaps();
  RobotSweep sweep(robot);
  std::mt19937_64 rng(21);
#if defined(__SANITIZE_ADDRESS__)
  const int motions = 60;
#else
  const int motions = 400;
#endif
  const double epsilon = 0.005;
  const int samples = 400;
  int swept = 0, sampled = 0, loose = 0;
  for (int m = 0; m < motions; ++m) {
    const auto qa = randomConfiguration(robot.model(), rng),
               qb = randomConfiguration(robot.model(), rng);
    const bool sweptHit = sweep.selfCollides(qa, qb, {}, 0.0, epsilon);
    const int first = firstSelfCollidingSample(robot, qa, qb, samples);
    if (first >= 0) {
      EXPECT_TRUE(sweptHit) << "motion " << m << " self-collides at sample " << first;
    } else if (sweptHit) {
      // Single-sided ε: a "collides" must come within 2ε (plus what the samples skip).
      std::vector<Pose> poses(robot.model().links().size());
      std::vector<double> q(qa.size());
      bool near = false;
      for (int s = 0; s <= samples && !near; ++s) {
        for (std::size_t v = 0; v < q.size(); ++v) q[v] = qa[v] + s * (qb[v] - qa[v]) / samples;
        robot.model().linkPoses(q, poses);
        near = robot.selfCollides(poses, {}, 3 * epsilon);
      }
      loose += !near;
    }
    swept += sweptHit;
    sampled += first >= 0;
  }
  EXPECT_GT(sampled, motions / 10);
  EXPECT_LT(swept, motions);
  EXPECT_LE(loose, motions / 100) << "self-collisions reported farther than 3 epsilon";
}

// A held rod sweeps with its link: dense sampling never finds a self-collision (of the rod with
// another link, or of two links) that the swept check called free.
TEST(RobotSweep, DenseSamplingNeverFindsASelfCollisionOfAHeldObjectTheSweepCalledFree) {
  const RobotCollisionModel robot = test::kr5AllowingHomeOverlaps();
  const int palm = *robot.model().findLink("palm");
  // A rod from just beyond the palm's tip (its largest x) outwards.
  double tip = 0;
  for (const Vec3& v : robot.part(robot.partCount() - 1).body->piece(0).vertices()) {
    tip = std::max(tip, v.x());
  }
  const std::vector<Attachment> held{
      {test::boxBody(Vec3(tip + 0.01, -0.02, -0.02), Vec3(tip + 0.4, 0.02, 0.02)), palm,
       Pose::Identity()}};
  RobotSweep sweep(robot);
  std::mt19937_64 rng(17);
#if defined(__SANITIZE_ADDRESS__)
  const int motions = 40;
#else
  const int motions = 120;
#endif
  int swept = 0, heldOnly = 0;
  for (int m = 0; m < motions; ++m) {
    const auto qa = randomConfiguration(robot.model(), rng),
               qb = randomConfiguration(robot.model(), rng);
    const bool sweptHit = sweep.selfCollides(qa, qb, held, 0.0, 0.005);
    const int first = firstSelfCollidingSample(robot, qa, qb, 400, held);
    if (first >= 0) {
      EXPECT_TRUE(sweptHit) << "motion " << m << " self-collides at sample " << first;
      heldOnly += firstSelfCollidingSample(robot, qa, qb, 400) < 0;
    }
    swept += sweptHit;
  }
  EXPECT_GT(heldOnly, 0) << "some motions collide only through the held rod";
  EXPECT_LT(swept, motions);
}

// Two parts no moving joint moves relative to each other (an object held on the wrist and the
// palm while the wrist stays) keep their distance along the motion: checked once, at the start,
// an overlap is reported whatever the other joints do.
TEST(RobotSweep, PartsNoMovingJointMovesApartAreCheckedAtTheStart) {
  RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  for (std::size_t i = 0; i < robot.partCount(); ++i) {  // only the held object is checked
    for (std::size_t j = i + 1; j < robot.partCount(); ++j) robot.filter().allow(i, j);
  }
  const int wrist = *robot.model().findLink("wrist");
  const int palm = *robot.model().findLink("palm");
  const std::vector<double> home(6, 0.0);
  std::vector<Pose> poses(robot.model().links().size());
  robot.model().linkPoses(home, poses);
  // A small box at the palm's centre, held on the wrist.
  std::size_t palmPart = 0;
  while (robot.part(palmPart).link != palm) ++palmPart;
  const Vec3 palmCentre =
      poses[static_cast<std::size_t>(palm)] * robot.part(palmPart).body->bounds().centre;
  const Vec3 inWrist = poses[static_cast<std::size_t>(wrist)].inverse() * palmCentre;
  const std::vector<Attachment> held{
      {test::boxBody(inWrist - Vec3::Constant(0.005), inWrist + Vec3::Constant(0.005)), wrist,
       Pose::Identity()}};
  RobotSweep sweep(robot);
  std::mt19937_64 rng(5);
  for (int m = 0; m < 20; ++m) {
    auto qa = randomConfiguration(robot.model(), rng), qb = randomConfiguration(robot.model(), rng);
    qa[4] = qb[4] = qa[5] = qb[5] = 0;  // the wrist pitch and roll stay
    ASSERT_GE(firstSelfCollidingSample(robot, qa, qb, 10, held), 0);
    EXPECT_TRUE(sweep.selfCollides(qa, qb, held, 0.0, 0.005)) << "motion " << m;
  }
}

// Two KR5s facing each other 0.9 m apart.
struct FacingKr5s {
  RobotModel model = loadUrdf(test::kKr5);
  RobotCollisionModel left = kaboum::testing::robotCollisionModel(model);
  RobotCollisionModel right = kaboum::testing::robotCollisionModel(model);
  FacingKr5s() {
    right.setBasePose(
        Pose(Eigen::Translation3d(0.9, 0, 0) * Eigen::AngleAxisd(3.14159, Vec3::UnitY())));
  }
};

// The part steps' culling gives the verdict of comparing every swept piece of one robot with every
// swept piece of the other.
TEST(SweptVolumes, CullingGivesTheVerdictOfEveryPiecePair) {
  FacingKr5s pair;
  const RobotModel& model = pair.model;
  RobotCollisionModel &left = pair.left, &right = pair.right;
  RobotSweep sweepLeft(left), sweepRight(right), allLeft(left), allRight(right);
  std::mt19937_64 rng(31);
  const double epsilon = 0.005, reach = 2 * epsilon;
  int collisions = 0;
  const int motions = 30;
  for (int m = 0; m < motions; ++m) {
    const auto qa0 = randomConfiguration(model, rng), qa1 = randomConfiguration(model, rng);
    const auto qb0 = randomConfiguration(model, rng);
    const auto qb1 = m % 3 == 0 ? qb0 : randomConfiguration(model, rng);  // b still, or moving
    const bool culled =
        sweptVolumesCollide(sweepLeft, qa0, qa1, {}, sweepRight, qb0, qb1, {}, 0, epsilon);
    const auto piecesA = allLeft.sweep(qa0, qa1, {}, epsilon);
    const auto piecesB = allRight.sweep(qb0, qb1, {}, epsilon);
    bool every = false;
    for (const RobotSweep::Piece& a : piecesA) {
      const Aabb box = a.box.inflated(reach);
      for (const RobotSweep::Piece& b : piecesB) {
        if (box.overlaps(b.box) && intersects(a.shape, b.shape, reach)) {
          every = true;
          break;
        }
      }
      if (every) break;
    }
    EXPECT_EQ(culled, every) << "motion " << m;
    collisions += culled;
  }
  EXPECT_GT(collisions, 0);
  EXPECT_LT(collisions, motions);
}

TEST(RobotSweep, SelfCollisionFollowsTheFilter) {
  RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  RobotSweep sweep(robot);
  // The elbow folds back onto the base between these two configurations.
  const std::vector<double> qa{0, 1.5, 0, 0, 0, 0}, qb{0, 1.5, 2.7, 0, 0, 0};
  ASSERT_GE(firstSelfCollidingSample(robot, qa, qb, 100), 0);
  EXPECT_TRUE(sweep.selfCollides(qa, qb, {}, 0.0, 0.002));
  for (std::size_t i = 0; i < robot.partCount(); ++i) {
    for (std::size_t j = i + 1; j < robot.partCount(); ++j) robot.filter().allow(i, j);
  }
  EXPECT_FALSE(sweep.selfCollides(qa, qb, {}, 0.0, 0.002)) << "every pair allowed";
}

TEST(SweptVolumes, DenseSamplingNeverFindsACollisionTheSweepsCalledFree) {
  // The volumes are compared regardless of timing.
  FacingKr5s pair;
  const RobotModel& model = pair.model;
  RobotCollisionModel &left = pair.left, &right = pair.right;
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
    const auto qa0 = randomConfiguration(model, rng), qa1 = randomConfiguration(model, rng);
    const auto qb0 = randomConfiguration(model, rng), qb1 = randomConfiguration(model, rng);
    const bool swept =
        sweptVolumesCollide(sweepLeft, qa0, qa1, {}, sweepRight, qb0, qb1, {}, 0, epsilon);
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
