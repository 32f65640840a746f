// Inclusion (Definition 1 (4)) never says "inside" when a point is outside; isOnSupportSurface
// follows seed 003's heuristic.
#include <gtest/gtest.h>

#include "collision_test_support.hpp"
#include "kaboum/collision/predicates.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using test::boxBody;
using test::boxCorners;

bool insideContainer(const ConvexContainer& container, const Pose& containerPose, const Vec3& p) {
  const Vec3 local = containerPose.inverse() * p;
  for (const HullPlane& plane : container.planes()) {
    if (plane.normal.dot(local) > plane.offset) return false;
  }
  return true;
}

TEST(IsInside, BoxInTray) {
  const ConvexContainer tray(boxCorners(Vec3(0, 0, 0), Vec3(1, 1, 0.5)), "tray");
  const auto item = boxBody(Vec3::Constant(-0.1), Vec3::Constant(0.1));
  EXPECT_TRUE(isInside(*item, Pose(Eigen::Translation3d(0.5, 0.5, 0.2)), tray, Pose::Identity()));
  EXPECT_FALSE(isInside(*item, Pose(Eigen::Translation3d(0.95, 0.5, 0.2)), tray, Pose::Identity()));
  EXPECT_FALSE(isInside(*item, Pose(Eigen::Translation3d(3, 3, 3)), tray, Pose::Identity()));
  EXPECT_TRUE(isInside(*item, Pose(Eigen::Translation3d(10.5, 0.5, 0.2)), tray,
                       Pose(Eigen::Translation3d(10, 0, 0))));
  EXPECT_THROW(ConvexContainer(std::vector<Vec3>{Vec3::Zero()}, "dot"), InputError);
}

// Never "inside" when a sampled point of the real object (a mesh, bounded by its convex pieces)
// lies outside; and "inside" whenever the object is deep inside (exact beyond ε).
TEST(IsInside, NeverInsideWhenASampledPointIsOutside) {
  // The cow, centred and scaled to a radius of 0.3.
  TriangleMesh cow = readMesh(kaboum::testing::dataFile("meshes/cow.obj"));
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : cow.vertices) centre += v / static_cast<double>(cow.vertices.size());
  double radius = 0;
  for (const Vec3& v : cow.vertices) radius = std::max(radius, (v - centre).norm());
  for (Vec3& v : cow.vertices) v = 0.3 / radius * (v - centre);
  const CollisionBody body(std::vector<std::vector<Vec3>>{cow.vertices}, "cow");
  const auto samples = sampleSurface(cow, 5000, 3);
  const ConvexContainer container(boxCorners(Vec3(-0.6, -0.6, -0.6), Vec3(0.6, 0.6, 0.6)),
                                  "container");
  std::mt19937_64 rng(9);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Pose objectPose = test::randomPose(rng, 0.4);
    const Pose containerPose = test::randomPose(rng, 0.1);
    const bool answer = isInside(body, objectPose, container, containerPose);
    bool allInside = true;
    for (const Vec3& p : samples)
      allInside &= insideContainer(container, containerPose, objectPose * p);
    if (answer) {
      EXPECT_TRUE(allInside);
    }
    if (allInside) {
      EXPECT_TRUE(answer) << "the hull of a mesh is inside iff its vertices are";
    }
    (answer ? inside : outside) += 1;
  }
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 20);
}

class SupportSurface : public ::testing::Test {
 protected:
  void SetUp() override {
    table =
        scene.add(boxBody(Vec3(-0.5, -0.5, -0.05), Vec3(0.5, 0.5, 0)), Pose::Identity(), "table");
    can = scene.addMovable(boxBody(Vec3(-0.03, -0.03, 0), Vec3(0.03, 0.03, 0.1)), Pose::Identity(),
                           "can");
    state = scene.initialState();
  }
  bool onSurface(const Vec3& at) {
    state[scene.slot(can)].pose = Pose(Eigen::Translation3d(at));
    return isOnSupportSurface(scene, state, can, 0.005, 0.001);
  }
  CollisionScene scene;
  SceneState state;
  std::size_t table = 0, can = 0;
};

TEST_F(SupportSurface, RestingJustAboveTheTable) {
  EXPECT_TRUE(onSurface(Vec3(0, 0, 0.002)));
  EXPECT_FALSE(onSurface(Vec3(0, 0, 0.02))) << "floating";
  EXPECT_FALSE(onSurface(Vec3(0, 0, -0.01))) << "sunk into the table";
  EXPECT_FALSE(onSurface(Vec3(0.5, 0, 0.002))) << "over the edge";
  EXPECT_FALSE(onSurface(Vec3(3, 0, 0.002))) << "beside the table";
}

TEST_F(SupportSurface, StackedOnAnotherObject) {
  const auto box = scene.add(boxBody(Vec3(-0.05, -0.05, 0), Vec3(0.05, 0.05, 0.1)),
                             Pose(Eigen::Translation3d(0.2, 0, 0.001)), "box");
  EXPECT_TRUE(isOnSupportSurface(scene, state, box, 0.005, 0.001));
  EXPECT_TRUE(onSurface(Vec3(0.2, 0, 0.103)));
}

TEST_F(SupportSurface, AnAbsentObjectSupportsNothing) {
  const auto lid = scene.add(boxBody(Vec3(-0.03, -0.03, 0), Vec3(0.03, 0.03, 0.01)),
                             Pose(Eigen::Translation3d(0, 0, 0.102)), "lid");
  EXPECT_TRUE(isOnSupportSurface(scene, state, lid, 0.005, 0.001)) << "on the can";
  state[scene.slot(can)].present = false;
  EXPECT_FALSE(isOnSupportSurface(scene, state, lid, 0.005, 0.001)) << "the can is held";
}

}  // namespace
}  // namespace kaboum::collision
