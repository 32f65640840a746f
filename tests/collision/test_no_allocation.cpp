// The collision module's hot paths allocate nothing per call (GJK boolean and distance, warm and
// cold; robot, scene, predicate and swept checks of a state), and picking and placing objects
// grows nothing. Counts global operator new calls around each call; the one inclusion of
// allocation_counter.hpp in test_collision is here — add further collision hot paths to this file.
#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"
#include "collision_test_support.hpp"
#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/gjk.hpp"
#include "kaboum/collision/predicates.hpp"
#include "kaboum/collision/swept.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/testing/polytope_pairs.hpp"
#include "kaboum/testing/robot_collision_models.hpp"
#include "kaboum/testing/scene_generator.hpp"

namespace kaboum::collision {

using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using kaboum::test::allocationsDuring;

TEST(NoAllocation, GjkQueries) {
  for (const int n : {8, 64}) {
    const auto pairs = randomPolytopePairs(50, n, 3);
    std::vector<ConvexPolytope> a, b;
    for (const PolytopePair& pair : pairs) {
      a.emplace_back(pair.localA);
      b.emplace_back(pair.localB);
    }
    GjkCache<TransformedSupport, TransformedSupport> cache;
    int hits = 0;
    const long counted = allocationsDuring([&] {
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const TransformedSupport placedA(a[i], pairs[i].poseA);
        const TransformedSupport placedB(b[i], pairs[i].poseB);
        hits += intersects(placedA, placedB) ? 1 : 0;
        hits += intersects(placedA, placedB, 0.1, &cache) ? 1 : 0;
        hits += distance(placedA, placedB).intersecting ? 1 : 0;
        hits += distance(placedA, placedB, &cache).intersecting ? 1 : 0;
      }
    });
    EXPECT_EQ(counted, 0) << "N=" << n;
    EXPECT_GT(hits, 0);
  }
}

// The queries of one state (a scene state with movable objects moved and one picked, the robot
// holding it) allocate nothing.
TEST(NoAllocation, CollisionHotPaths) {
  const RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  const CollisionScene scene =
      randomObstacleScene(Aabb{Vec3(-0.8, -1.2, -0.8), Vec3(0.8, 0.4, 0.8)}, 50, 12, 0.04, 3, 10);
  SceneState state = scene.initialState();
  state[scene.slot(45)].pose.translation() += Vec3(0.1, 0, 0);
  state[scene.slot(40)].present = false;
  const int palm = *robot.model().findLink("palm");
  const std::vector<Attachment> held{
      {scene.sharedBody(40), palm, Pose(Eigen::Translation3d(0.05, 0, 0))}};
  std::vector<Pose> poses(robot.model().links().size());
  const std::vector<double> qa{0.1, 0.2, -0.3, 0.4, 0.5, 0.6}, qb{0.9, -0.2, 0.3, 1.4, -0.5, 0.1};
  robot.model().linkPoses(qa, poses);
  const ConvexContainer container(test::boxCorners(Vec3::Constant(-1), Vec3::Constant(1)));
  RobotSweep sweep(robot);
  EXPECT_GT(allocationsDuring([&] { sweep.sweep(qa, qb, held, 0.001); }), 0);  // counter works
  bool any = false;
  EXPECT_EQ(allocationsDuring([&] {
              any |= robot.firstSceneCollision(poses, held, scene, state, 0).has_value();
            }),
            0);
  EXPECT_EQ(allocationsDuring([&] { any |= robot.selfCollides(poses, held, 0); }), 0);
  EXPECT_EQ(
      allocationsDuring([&] {
        any |=
            scene.firstCollision(state, scene.body(45), scene.pose(45, state), 0.1, 45).has_value();
      }),
      0);
  EXPECT_EQ(allocationsDuring([&] {
              any |= bodiesCollide(scene.body(0), scene.pose(0, state), scene.body(1),
                                   scene.pose(1, state), 0);
            }),
            0);
  EXPECT_EQ(allocationsDuring([&] {
              any |= isInside(scene.body(0), scene.pose(0, state), container, Pose::Identity());
            }),
            0);
  EXPECT_EQ(allocationsDuring([&] { any |= isOnSupportSurface(scene, state, 0, 0.01, 0.001); }), 0);
  EXPECT_EQ(allocationsDuring([&] { any |= isOnSupportSurface(scene, state, 45, 0.01, 0.001); }),
            0);
  EXPECT_EQ(allocationsDuring([&] {
              any |= sweep.firstSceneCollision(qa, qb, held, scene, state, 0, 0.001).has_value();
            }),
            0);
  any |= sweep.selfCollides(qa, qb, held, 0, 0.001);  // grows the refinement buffers once
  EXPECT_EQ(allocationsDuring([&] { any |= sweep.selfCollides(qa, qb, held, 0, 0.001); }), 0);
  (void)any;
}

// A long search picks and places objects over and over. A pick (the object leaves the scene
// state, the robot holds it) and a place (back into the state at a new pose) change only the
// caller's state values: 10,000 cycles, with queries in between, allocate nothing and grow
// neither the robot model, the scene, the state nor the sweep.
TEST(NoAllocation, TenThousandPickAndPlaceCyclesKeepMemoryFlat) {
  const RobotCollisionModel robot = test::kr5AllowingHomeOverlaps();
  const CollisionScene scene =
      randomObstacleScene(Aabb{Vec3(-0.8, -1.2, -0.8), Vec3(0.8, 0.4, 0.8)}, 50, 12, 0.04, 3, 10);
  SceneState state = scene.initialState();
  const int palm = *robot.model().findLink("palm");
  std::mt19937_64 rng(5);
  std::vector<std::vector<double>> configurations;
  std::vector<std::vector<Pose>> poses;
  for (int c = 0; c < 16; ++c) {
    configurations.push_back(randomConfiguration(robot.model(), rng));
    poses.emplace_back(robot.model().links().size());
    robot.model().linkPoses(configurations.back(), poses.back());
  }
  std::vector<Attachment> held;
  held.reserve(1);
  const Pose grasp(Eigen::Translation3d(0.05, 0, 0));
  RobotSweep sweep(robot);
  // The sweep's buffers grow once, to the longest motion and the held object.
  held.push_back({scene.sharedBody(40), palm, grasp});
  for (std::size_t c = 0; c < configurations.size(); ++c) {
    const auto& next = configurations[(c + 1) % configurations.size()];
    sweep.firstSceneCollision(configurations[c], next, held, scene, state, 0, 0.005);
    sweep.selfCollides(configurations[c], next, held, 0, 0.005);
  }
  held.clear();
  const std::size_t parts = robot.partCount(), objects = scene.size();
  long hits = 0;
  const long counted = allocationsDuring([&] {
    for (std::size_t cycle = 0; cycle < 10000; ++cycle) {
      const std::size_t object = 40 + cycle % 10, c = cycle % poses.size();
      Placement& placement = state[scene.slot(object)];
      placement.present = false;
      held.push_back({scene.sharedBody(object), palm, grasp});
      hits += robot.firstSceneCollision(poses[c], held, scene, state, 0).has_value();
      hits += robot.selfCollides(poses[c], held, 0) ? 1 : 0;
      if (cycle % 100 == 0) {
        const auto& next = configurations[(c + 1) % configurations.size()];
        hits += sweep.firstSceneCollision(configurations[c], next, held, scene, state, 0, 0.005)
                    .has_value();
        hits += sweep.selfCollides(configurations[c], next, held, 0, 0.005) ? 1 : 0;
      }
      held.pop_back();
      placement = {test::randomPose(rng, 0.8), true};
      hits += robot.firstSceneCollision(poses[c], held, scene, state, 0).has_value();
    }
  });
  EXPECT_EQ(counted, 0);
  EXPECT_GT(hits, 0);
  EXPECT_EQ(robot.partCount(), parts);
  EXPECT_EQ(scene.size(), objects);
  EXPECT_EQ(state.size(), 10U);
  EXPECT_EQ(held.capacity(), 1U);
}

}  // namespace
}  // namespace kaboum::collision
