// The collision module's hot paths allocate nothing per call (GJK boolean and distance, warm and
// cold; robot, scene, predicate and swept checks). Counts global operator new calls around each
// call; the one inclusion of allocation_counter.hpp in test_collision is here — add further
// collision hot paths to this file.
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

TEST(NoAllocation, CollisionHotPaths) {
  RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  const CollisionScene scene =
      randomObstacleScene(Aabb{Vec3(-0.8, -1.2, -0.8), Vec3(0.8, 0.4, 0.8)}, 50, 12, 0.04, 3);
  std::vector<Pose> poses(robot.model().links().size());
  const std::vector<double> qa{0.1, 0.2, -0.3, 0.4, 0.5, 0.6}, qb{0.9, -0.2, 0.3, 1.4, -0.5, 0.1};
  robot.model().linkPoses(qa, poses);
  const ConvexContainer container(test::boxCorners(Vec3::Constant(-1), Vec3::Constant(1)));
  RobotSweep sweep(robot);
  EXPECT_GT(allocationsDuring([&] { sweep.sweep(qa, qb, 0.001); }), 0);  // counter works
  bool any = false;
  EXPECT_EQ(
      allocationsDuring([&] { any |= robot.firstSceneCollision(poses, scene, 0).has_value(); }), 0);
  EXPECT_EQ(allocationsDuring([&] { any |= robot.selfCollides(poses, 0); }), 0);
  EXPECT_EQ(allocationsDuring([&] {
              any |= bodiesCollide(scene.body(0), scene.pose(0), scene.body(1), scene.pose(1), 0);
            }),
            0);
  EXPECT_EQ(allocationsDuring([&] {
              any |= isInside(scene.body(0), scene.pose(0), container, Pose::Identity());
            }),
            0);
  EXPECT_EQ(allocationsDuring([&] { any |= isOnSupportSurface(scene, 0, 0.01, 0.001); }), 0);
  EXPECT_EQ(allocationsDuring(
                [&] { any |= sweep.firstSceneCollision(qa, qb, scene, 0, 0.001).has_value(); }),
            0);
  any |= sweep.selfCollides(qa, qb, 0, 0.001);  // grows the refinement buffers once
  EXPECT_EQ(allocationsDuring([&] { any |= sweep.selfCollides(qa, qb, 0, 0.001); }), 0);
  CollisionScene moving = scene;
  EXPECT_EQ(allocationsDuring([&] { moving.setPose(3, Pose(Eigen::Translation3d(0.1, 0, 0))); }),
            0);
  (void)any;
}

}  // namespace
}  // namespace kaboum::collision
