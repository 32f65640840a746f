// A World's meshes decomposed in parallel (§6.1.1 pre-processing): the same World on one thread and
// on two, equal to decomposing each shape on its own, and each distinct mesh decomposed once
// however many robots, hands and objects have it. Small meshes only (a KR5 link costs seconds).
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::world {

using namespace kaboum::testing;

namespace {

WorldOptions onThreads(unsigned threads) {
  WorldOptions options;
  options.threads = threads;
  return options;
}

// The bytes of every vertex of every piece of every body, in order.
std::string pieceBytes(const World& world) {
  std::string bytes;
  const auto add = [&](const CollisionBody& body) {
    for (std::size_t p = 0; p < body.pieceCount(); ++p) {
      const auto& piece = body.piece(p).vertices();
      bytes.append(reinterpret_cast<const char*>(piece.data()), piece.size() * sizeof(Vec3));
    }
  };
  for (const WorldRobot& robot : world.robots()) {
    for (std::size_t i = 0; i < robot.collision.partCount(); ++i) {
      add(*robot.collision.part(i).body);
    }
  }
  for (std::size_t o = 0; o < world.scene().size(); ++o) add(world.scene().body(o));
  return bytes;
}

TEST(WorldParallel, TwoThreadsBuildTheSameWorldAsOne) {
  // Two hand meshes and the tabletop at 5 mm.
  const std::string file = exampleFile("scenes/bimanual-cell.yaml");
  const World one(readSceneFile(file), onThreads(1));
  const World two(readSceneFile(file), onThreads(2));
  EXPECT_EQ(one.decompositions().threads, 1U);
  EXPECT_EQ(two.decompositions().threads, 2U);
  ASSERT_EQ(two.decompositions().meshes.size(), 3U);
  EXPECT_EQ(pieceBytes(one), pieceBytes(two));
  ASSERT_EQ(one.robots().size(), two.robots().size());
  for (std::size_t r = 0; r < one.robots().size(); ++r) {
    const WorldRobot &a = one.robots()[r], &b = two.robots()[r];
    ASSERT_EQ(a.partEpsilon.size(), b.partEpsilon.size());
    for (std::size_t i = 0; i < a.partEpsilon.size(); ++i) {
      EXPECT_EQ(a.partEpsilon[i].reached, b.partEpsilon[i].reached);
    }
    EXPECT_EQ(a.handShapeEpsilon, b.handShapeEpsilon);
  }
  for (std::size_t o = 0; o < one.objectEpsilon().size(); ++o) {
    EXPECT_EQ(one.objectEpsilon()[o].reached, two.objectEpsilon()[o].reached);
  }
  EXPECT_EQ(one.restingLift(), two.restingLift());

  // And equal to decomposing the tabletop on its own, as bodies were built one by one.
  const SceneDescription scene = readSceneFile(file);
  const std::size_t tabletop = two.find("tabletop")->index;
  const CollisionShape& shape = scene.objects[tabletop].geometry.shape;
  LinkPieceOptions pieces;
  pieces.decompose = true;
  pieces.decomposition.epsilon = 0.005;
  pieces.pieceLimitDoublings = 3;
  const BoundingPieces alone =
      boundingShapePieces(shape, {{shape.meshPath, readMesh(shape.meshPath)}}, pieces);
  const CollisionBody body(alone.pieces, "tabletop");
  const CollisionBody& built = two.scene().body(tabletop);
  ASSERT_EQ(built.pieceCount(), body.pieceCount());
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    const auto &expected = body.piece(p).vertices(), &actual = built.piece(p).vertices();
    ASSERT_EQ(actual.size(), expected.size());
    EXPECT_EQ(std::memcmp(actual.data(), expected.data(), expected.size() * sizeof(Vec3)), 0);
  }
  EXPECT_EQ(two.objectEpsilon()[tabletop].reached, alone.boundingError);
}

// Two robots of one URDF (a finger adapter and a finger, meshes of the Bimanual Assembly tools),
// two objects with the finger's mesh and one with it twice as large.
SceneDescription sharedMeshes(const test::ScratchDir& dir) {
  const std::string tools = dataFile("meshes/bimanual-assembly/tools/");
  const std::string urdf =
      dir.write("gripper.urdf", R"(<robot name="gripper">
  <link name="adapter">
    <collision><geometry><mesh filename=")" +
                                    tools + R"(finger-adapter.wrl"/></geometry></collision>
  </link>
  <link name="finger">
    <collision><geometry><mesh filename=")" +
                                    tools + R"(finger2.wrl"/></geometry></collision>
  </link>
  <joint name="slide" type="prismatic">
    <parent link="adapter"/><child link="finger"/><origin xyz="0.1 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.05" effort="10" velocity="0.1"/>
  </joint>
</robot>
)");
  return parseSceneText(
      "settings: {epsilon: 0.005}\n"
      "robots:\n"
      "  - {name: a, urdf: '" +
          urdf +
          "'}\n"
          "  - {name: b, urdf: '" +
          urdf +
          "', base_pose: {position: [0, 1, 0]}}\n"
          "objects:\n"
          "  - name: f1\n"
          "    geometry: {mesh: {file: finger2.wrl}}\n"
          "    pose: {position: [1, 0, 0]}\n"
          "  - name: f2\n"
          "    geometry: {mesh: {file: finger2.wrl}}\n"
          "    pose: {position: [1, 1, 0]}\n"
          "  - name: large\n"
          "    geometry: {mesh: {file: finger2.wrl, scale: 2}}\n"
          "    pose: {position: [2, 0, 0]}\n",
      "scene.yaml", tools);
}

TEST(WorldParallel, IdenticalMeshesAreDecomposedOnce) {
  const test::ScratchDir dir;
  WorldOptions options = onThreads(2);
  options.cacheDirectory = dir.file("cache");
  const World world(sharedMeshes(dir), options);
  const std::vector<MeshDecomposition>& meshes = world.decompositions().meshes;
  ASSERT_EQ(meshes.size(), 3U);  // the adapter, the finger, the large finger
  EXPECT_NE(meshes[0].mesh.find("finger-adapter.wrl"), std::string::npos) << meshes[0].mesh;
  EXPECT_EQ(meshes[0].shapes, 2U);
  EXPECT_NE(meshes[1].mesh.find("finger2.wrl"), std::string::npos) << meshes[1].mesh;
  EXPECT_EQ(meshes[1].shapes, 4U);  // both robots' fingers and two objects
  EXPECT_EQ(meshes[2].shapes, 1U);
  std::size_t attempts = 0;
  for (const MeshDecomposition& mesh : meshes) {
    EXPECT_GE(mesh.attempts, 1U);
    EXPECT_GT(mesh.triangles, 0U);
    attempts += mesh.attempts;
  }
  // Every decomposition made once: each a miss of the cache, none read back in the same load.
  EXPECT_EQ(world.cacheReport().misses, attempts);
  EXPECT_EQ(world.cacheReport().hits, 0U);

  // The second robot and the second object have the first's pieces.
  const auto bodyBytes = [](const CollisionBody& body) {
    std::string bytes;
    for (std::size_t p = 0; p < body.pieceCount(); ++p) {
      const auto& piece = body.piece(p).vertices();
      bytes.append(reinterpret_cast<const char*>(piece.data()), piece.size() * sizeof(Vec3));
    }
    return bytes;
  };
  const RobotCollisionModel &a = world.robots()[0].collision, &b = world.robots()[1].collision;
  ASSERT_EQ(a.partCount(), 2U);
  ASSERT_EQ(b.partCount(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(bodyBytes(*a.part(i).body), bodyBytes(*b.part(i).body));
  }
  EXPECT_EQ(bodyBytes(world.scene().body(0)), bodyBytes(world.scene().body(1)));
  EXPECT_EQ(bodyBytes(world.scene().body(0)), bodyBytes(*a.part(1).body));

  // Read back by a second load, on one thread: the same pieces.
  const World again(sharedMeshes(dir), [&] {
    WorldOptions one = options;
    one.threads = 1;
    return one;
  }());
  EXPECT_EQ(again.cacheReport().hits, attempts);
  EXPECT_EQ(again.cacheReport().misses, 0U);
  EXPECT_EQ(pieceBytes(again), pieceBytes(world));
}

TEST(WorldParallel, HullsDecomposeNothing) {
  const test::ScratchDir dir;
  WorldOptions options;
  options.pieces = MeshPieces::Hulls;
  const World world(sharedMeshes(dir), options);
  EXPECT_TRUE(world.decompositions().meshes.empty());
  EXPECT_EQ(world.scene().body(0).pieceCount(), 1U);
}

TEST(WorldParallel, SceneReportsTheDistinctMeshesAndThreads) {
  const test::ScratchDir dir;
  const std::string file = exampleFile("scenes/bimanual-cell.yaml");
  test::CliResult result = test::runCli(dir, "scene --no-cache --threads 1 '" + file + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("meshes:        3 distinct of 3 mesh shape(s) decomposed, 1 thread(s)"),
            std::string::npos)
      << result.out;
  result = test::runCli(dir, "scene --no-cache --threads 2 --json '" + file + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  EXPECT_EQ(report["threads"], 2);
  ASSERT_EQ(report["meshes"].size(), 3U);
  for (const auto& mesh : report["meshes"]) {
    EXPECT_EQ(mesh["shapes"], 1);
    EXPECT_GE(mesh["attempts"], 1);
    EXPECT_GT(mesh["triangles"], 0);
    EXPECT_GE(mesh["seconds"], 0.0);
  }
}

}  // namespace

}  // namespace kaboum::world
