// Bodies of convex pieces, the scene broad phase and the robot collision model: single-sided
// against an exact reference, brute force agreement, filtering and attached objects.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "collision_test_support.hpp"
#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/collision/scene.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/robot_collision_models.hpp"

namespace kaboum::collision {

using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

using test::boxBody;
using test::randomPose;

TEST(CollisionBody, RejectsEmptyAndFlatPieces) {
  EXPECT_THROW(CollisionBody({}, "nothing"), InputError);
  const std::vector<std::vector<Vec3>> flat{
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}};
  try {
    CollisionBody body(flat, "flat thing");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("flat thing piece 0"), std::string::npos)
        << error.what();
  }
}

TEST(CollisionBody, BoundsContainEveryVertex) {
  std::mt19937_64 rng(11);
  const CollisionBody body(test::randomConvexSets(rng, 5, 12, 0.3), "random");
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    for (const Vec3& v : body.piece(p).vertices()) {
      EXPECT_LE((v - body.pieceBounds(p).centre).norm(), body.pieceBounds(p).radius + 1e-12);
      EXPECT_LE((v - body.bounds().centre).norm(), body.bounds().radius + 1e-12);
      EXPECT_LE(v.norm(), body.reach() + 1e-12);
    }
  }
}

// Single-sided ε semantics of Definition 1 (1): never free at distance <= margin, exact beyond.
TEST(CollisionBody, CollisionAgreesWithExactDistance) {
  std::mt19937_64 rng(5);
  const double margin = 0.01;
  int near = 0, overlapping = 0, apart = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const CollisionBody a(test::randomConvexSets(rng, 3, 10, 0.2), "a");
    const CollisionBody b(test::randomConvexSets(rng, 3, 10, 0.2), "b");
    const Pose poseA = randomPose(rng, 0.3), poseB = randomPose(rng, 0.3);
    const double distance = test::exactDistance(a, poseA, b, poseB);
    const bool collides = bodiesCollide(a, poseA, b, poseB, margin);
    if (distance <= margin) {
      EXPECT_TRUE(collides) << "missed at distance " << distance;
      (distance == 0 ? overlapping : near) += 1;
    } else if (distance > margin + 1e-9) {
      EXPECT_FALSE(collides) << "false alarm at distance " << distance;
      ++apart;
    }
  }
  EXPECT_GT(overlapping, 40);
  EXPECT_GT(apart, 40);
}

TEST(CollisionScene, BroadPhaseAgreesWithBruteForce) {
  std::mt19937_64 rng(21);
  CollisionScene scene;
  for (int i = 0; i < 60; ++i) {
    auto body = std::make_shared<const CollisionBody>(
        test::randomConvexSets(rng, 1 + static_cast<int>(rng() % 4), 8, 0.05), "obstacle");
    const Pose pose = randomPose(rng, 1.0);
    // A third of the objects are movable: fixed obstacles and placements of a state both count.
    if (i % 3 == 1) {
      scene.addMovable(std::move(body), pose, "object " + std::to_string(i));
    } else {
      scene.add(std::move(body), pose, "obstacle " + std::to_string(i));
    }
  }
  SceneState state = scene.initialState();
  state[scene.slot(7)].present = false;
  int hits = 0;
  for (int q = 0; q < 300; ++q) {
    // Movable objects move now and then (the state changes, the scene does not).
    if (q % 5 == 0) state[rng() % state.size()].pose = randomPose(rng, 1.0);
    const CollisionBody probe(test::randomConvexSets(rng, 3, 8, 0.1), "probe");
    const Pose pose = randomPose(rng, 1.0);
    bool expected = false;
    for (std::size_t o = 0; o < scene.size(); ++o) {
      expected |= o != 7 && bodiesCollide(probe, pose, scene.body(o), scene.pose(o, state), 0.02);
    }
    const auto hit = scene.firstCollision(state, probe, pose, 0.02);
    ASSERT_EQ(hit.has_value(), expected);
    if (hit) {
      EXPECT_NE(*hit, 7U);
      EXPECT_TRUE(bodiesCollide(probe, pose, scene.body(*hit), scene.pose(*hit, state), 0.02));
      if (const auto other = scene.firstCollision(state, probe, pose, 0.02, *hit)) {
        EXPECT_NE(*other, *hit) << "ignored object reported";
        EXPECT_TRUE(
            bodiesCollide(probe, pose, scene.body(*other), scene.pose(*other, state), 0.02));
      }
      ++hits;
    }
  }
  EXPECT_GT(hits, 20);
  EXPECT_LT(hits, 280);
}

TEST(CollisionScene, MovedObjectsAreFoundWhereTheyAre) {
  CollisionScene scene;
  const auto id = scene.addMovable(boxBody(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1)),
                                   Pose(Eigen::Translation3d(5, 0, 0)), "crate");
  const auto probe = boxBody(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1));
  SceneState state = scene.initialState();
  EXPECT_FALSE(scene.firstCollision(state, *probe, Pose::Identity(), 0));
  state[scene.slot(id)].pose = Pose(Eigen::Translation3d(0.15, 0, 0));
  EXPECT_EQ(scene.firstCollision(state, *probe, Pose::Identity(), 0), id);
  EXPECT_EQ(scene.name(id), "crate");
  state[scene.slot(id)].present = false;
  EXPECT_FALSE(scene.present(id, state));
  EXPECT_FALSE(scene.firstCollision(state, *probe, Pose::Identity(), 0));
}

// A state belongs to its scene: one placement per movable object, and only movable objects have
// a slot.
TEST(CollisionScene, StatesMustMatchTheScene) {
  CollisionScene scene;
  const auto wall =
      scene.add(boxBody(Vec3::Constant(-0.1), Vec3::Constant(0.1)), Pose::Identity(), "wall");
  const auto crate = scene.addMovable(boxBody(Vec3::Constant(-0.1), Vec3::Constant(0.1)),
                                      Pose(Eigen::Translation3d(1, 0, 0)), "crate");
  EXPECT_FALSE(scene.movable(wall));
  EXPECT_TRUE(scene.movable(crate));
  EXPECT_THROW((void)scene.slot(wall), std::invalid_argument);
  EXPECT_EQ(scene.slot(crate), 0U);
  const SceneState state = scene.initialState();
  ASSERT_EQ(state.size(), 1U);
  EXPECT_TRUE(state[0].pose.isApprox(Pose(Eigen::Translation3d(1, 0, 0))));
  EXPECT_TRUE(scene.present(wall, state));
  const auto probe = boxBody(Vec3::Constant(-0.1), Vec3::Constant(0.1));
  EXPECT_EQ(scene.firstCollision(state, *probe, Pose::Identity(), 0), wall);
  EXPECT_THROW((void)scene.firstCollision({}, *probe, Pose::Identity(), 0), std::invalid_argument);
  const SceneState tooLong(2);
  EXPECT_THROW((void)scene.pose(crate, tooLong), std::invalid_argument);
}

class Kr5Collision : public ::testing::Test {
 protected:
  RobotCollisionModel robot = kaboum::testing::robotCollisionModel(test::kKr5);
  std::vector<Pose> poses = std::vector<Pose>(robot.model().links().size());
  std::vector<double> q = std::vector<double>(6, 0.0);
  int palm = *robot.model().findLink("palm");
};

TEST_F(Kr5Collision, OnePartPerLinkWithGeometryAndAdjacentLinksFiltered) {
  EXPECT_EQ(robot.partCount(), 7U);
  for (std::size_t i = 0; i + 1 < robot.partCount(); ++i) {
    EXPECT_TRUE(robot.filter().allowed(i, i + 1)) << "links of a serial chain are adjacent";
    if (i + 2 < robot.partCount()) {
      EXPECT_FALSE(robot.filter().allowed(i, i + 2));
    }
  }
  robot.model().linkPoses(q, poses);
  // The hulls of forearm and palm overlap around the short wrist at home; allow that pair.
  EXPECT_TRUE(robot.selfCollides(poses, {}, 0.0));
  EXPECT_EQ(robot.allowPairsCollidingAt(poses), 1U);
  EXPECT_TRUE(robot.filter().allowed(4, 6));
  EXPECT_FALSE(robot.selfCollides(poses, {}, 0.0)) << "the home pose is free";
}

TEST_F(Kr5Collision, SelfCollisionFollowsTheFilter) {
  // Fold the elbow back onto the base: some non-adjacent pair collides somewhere on the way.
  robot.model().linkPoses(q, poses);
  robot.allowPairsCollidingAt(poses);
  bool folded = false;
  for (double q2 = 0; q2 < 2.7 && !folded; q2 += 0.1) {
    q = {0, 1.5, q2, 0, 0, 0};
    robot.model().linkPoses(q, poses);
    folded = robot.selfCollides(poses, {}, 0.0);
  }
  ASSERT_TRUE(folded);
  for (std::size_t i = 0; i < robot.partCount(); ++i) {
    for (std::size_t j = i + 1; j < robot.partCount(); ++j) robot.filter().allow(i, j);
  }
  EXPECT_FALSE(robot.selfCollides(poses, {}, 0.0)) << "every pair allowed";
}

TEST_F(Kr5Collision, SceneAndAttachedObjects) {
  robot.model().linkPoses(q, poses);
  const Vec3 tool = poses[static_cast<std::size_t>(palm)].translation();
  CollisionScene scene;
  // A small cube 0.3 m beyond the tool along the palm's x axis: only a long held object reaches.
  const Vec3 reachAxis = poses[static_cast<std::size_t>(palm)].linear().col(0);
  const auto cube = scene.addMovable(boxBody(Vec3::Constant(-0.02), Vec3::Constant(0.02)),
                                     Pose(Eigen::Translation3d(tool + 0.3 * reachAxis)), "cube");
  SceneState state = scene.initialState();
  EXPECT_FALSE(robot.firstSceneCollision(poses, {}, scene, state, 0.0));
  const std::vector<Attachment> held{
      {boxBody(Vec3(0, -0.01, -0.01), Vec3(0.35, 0.01, 0.01)), palm, Pose::Identity()}};
  const std::size_t rod = robot.partCount();
  EXPECT_FALSE(robot.checksPair(rod, robot.partCount() - 1, held)) << "held by the palm";
  EXPECT_EQ(robot.firstSceneCollision(poses, held, scene, state, 0.0), cube);
  EXPECT_FALSE(robot.firstSceneCollision(poses, {}, scene, state, 0.0)) << "put down";
  state[scene.slot(cube)].pose = Pose(Eigen::Translation3d(tool));
  EXPECT_EQ(robot.firstSceneCollision(poses, {}, scene, state, 0.0), cube);
}

// A held object is checked against every other link, and against objects held by other links,
// but not against its own link nor the other objects that link holds.
TEST_F(Kr5Collision, HeldObjectsFollowTheFilteringRules) {
  robot.model().linkPoses(q, poses);
  robot.allowPairsCollidingAt(poses);
  const Pose& palmPose = poses[static_cast<std::size_t>(palm)];
  const auto cube = boxBody(Vec3::Constant(-0.03), Vec3::Constant(0.03));
  const auto heldAt = [&](const BodyPtr& body, int link, const Vec3& world) {
    return Attachment{
        body, link,
        poses[static_cast<std::size_t>(link)].inverse() * Pose(Eigen::Translation3d(world))};
  };
  // A bead around the palm's vertex farthest along its x axis (away from the wrist).
  const auto& palmVertices = robot.part(6).body->piece(0).vertices();
  const Vec3 tip = *std::max_element(palmVertices.begin(), palmVertices.end(),
                                     [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  const auto bead = boxBody(Vec3::Constant(-0.01), Vec3::Constant(0.01));
  const std::vector<Attachment> atTheTip{heldAt(bead, palm, palmPose * (tip + Vec3(0.005, 0, 0)))};
  ASSERT_TRUE(bodiesCollide(*robot.part(6).body, robot.partPose(6, poses), *bead,
                            robot.partPose(robot.partCount(), poses, atTheTip), 0.0));
  EXPECT_FALSE(robot.selfCollides(poses, atTheTip, 0.0)) << "overlaps only its own link";
  const Vec3 inTheBase =
      robot.partPose(0, poses) * robot.part(0).body->piece(0).innerSphereCenter();
  const std::vector<Attachment> atTheBase{heldAt(cube, palm, inTheBase)};
  EXPECT_TRUE(robot.selfCollides(poses, atTheBase, 0.0)) << "held by the palm, inside the base";
  const Vec3 away = palmPose.translation() + Vec3(0, 0, 1);
  const std::vector<Attachment> sameLink{heldAt(cube, palm, away), heldAt(cube, palm, away)};
  EXPECT_FALSE(robot.selfCollides(poses, sameLink, 0.0)) << "both held by the palm";
  const int forearm = robot.part(4).link;
  const std::vector<Attachment> twoLinks{heldAt(cube, palm, away), heldAt(cube, forearm, away)};
  EXPECT_TRUE(robot.selfCollides(poses, twoLinks, 0.0)) << "held by two links, overlapping";
  const std::vector<Attachment> noLink{{cube, 99, Pose::Identity()}};
  EXPECT_THROW((void)robot.selfCollides(poses, noLink, 0.0), std::out_of_range);
}

TEST(RobotCollisionModel, PrimitiveShapesAreBounded) {
  std::mt19937_64 rng(4);
  CollisionShape sphere;
  sphere.kind = CollisionShape::Kind::Sphere;
  sphere.radius = 0.3;
  CollisionShape cylinder;
  cylinder.kind = CollisionShape::Kind::Cylinder;
  cylinder.radius = 0.2;
  cylinder.length = 0.5;
  cylinder.origin = randomPose(rng, 1.0);
  for (const CollisionShape& shape : {sphere, cylinder}) {
    const auto pieces = shapeConvexPieces(shape, {});
    ASSERT_EQ(pieces.size(), 1U);
    const ConvexHull hull = convexHull(pieces[0]);
    for (int i = 0; i < 2000; ++i) {
      // A random point on the exact surface, in the link frame, must be in the polytope.
      const Vec3 d = test::randomPoint(rng, 1.0).normalized();
      Vec3 local;
      if (shape.kind == CollisionShape::Kind::Sphere) {
        local = shape.radius * d;
      } else {
        const Vec3 radial = Vec3(d.x(), d.y(), 0).normalized();
        local = shape.radius * radial + Vec3(0, 0, shape.length * (uniformUnit(rng) - 0.5));
      }
      const Vec3 p = shape.origin * local;
      for (const HullPlane& plane : hull.planes)
        EXPECT_LE(plane.normal.dot(p), plane.offset + 1e-12);
    }
  }
}

TEST(RobotCollisionModel, UnreadableLinkMeshIsAnInputError) {
  const std::string urdf = R"(<robot name="r"><link name="a"><collision><geometry>
      <mesh filename="missing.stl"/></geometry></collision></link></robot>)";
  EXPECT_THROW(readCollisionMeshes(parseUrdf(urdf, "r.urdf", "/nonexistent")), InputError);
}

// Collision reads no files: a mesh shape whose mesh the caller did not supply is an InputError
// that names the path.
TEST(RobotCollisionModel, AMeshNotSuppliedIsAnInputErrorNamingIt) {
  const std::string mesh = kaboum::testing::dataFile("meshes/kr5-wrist.stl");
  const std::string urdf = R"(<robot name="r"><link name="a"><collision><geometry>
      <mesh filename=")" + mesh +
                           R"("/></geometry></collision></link></robot>)";
  try {
    const RobotCollisionModel robot(parseUrdf(urdf, "r.urdf", "."), {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(mesh + ": collision mesh not loaded"), std::string::npos)
        << e.what();
  }
}

// Link meshes through the bounding convex decomposition: several pieces whose union still holds
// every vertex of the original mesh (in the link frame, after the collision origin).
TEST(RobotCollisionModel, DecomposedLinksContainTheirMeshes) {
  const std::string mesh = kaboum::testing::dataFile("meshes/kr5-wrist.stl");
  const std::string urdf = R"(<robot name="r"><link name="wrist"><collision>
      <origin xyz="0.1 0 0" rpy="0 0.5 0"/><geometry><mesh filename=")" +
                           mesh + R"("/></geometry></collision></link></robot>)";
  LinkPieceOptions options;
  options.decompose = true;
  options.decomposition.epsilonPercent = 2;
  const RobotCollisionModel robot =
      kaboum::testing::robotCollisionModel(parseUrdf(urdf, "r.urdf", "."), options);
  ASSERT_EQ(robot.partCount(), 1U);
  const CollisionBody& body = *robot.part(0).body;
  EXPECT_GT(body.pieceCount(), 1U);
  std::vector<ConvexHull> hulls;
  for (std::size_t p = 0; p < body.pieceCount(); ++p)
    hulls.push_back(convexHull(body.piece(p).vertices()));
  const Pose origin = robot.model().links()[0].collisions[0].origin;
  for (const Vec3& v : readMesh(mesh).vertices) {
    const Vec3 inLink = origin * v;
    const bool covered = std::any_of(hulls.begin(), hulls.end(), [&](const ConvexHull& hull) {
      return std::all_of(hull.planes.begin(), hull.planes.end(), [&](const HullPlane& plane) {
        return plane.normal.dot(inLink) <= plane.offset + 1e-9;
      });
    });
    ASSERT_TRUE(covered) << v.transpose();
  }
}

}  // namespace
}  // namespace kaboum::collision
