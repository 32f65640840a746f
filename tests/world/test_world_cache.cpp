// A World's mesh decompositions from the cache on disk and the ε each body reaches (§6.1.1): a
// second load reads every decomposition, concurrent processes share one directory, `kaboum scene`
// reports the cache and ε per body, and a reported collision is never farther apart than the two
// bodies' reached ε.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::world {

using namespace kaboum::testing;

namespace {

std::string bimanualCell() {
  return exampleFile("scenes/bimanual-cell.yaml");
}

WorldOptions cachedIn(const std::string& directory) {
  WorldOptions options;
  options.cacheDirectory = directory;
  return options;
}

// Two movable mesh objects of the repository's data (a KR5 wrist, a Comau finger with its adapter)
// at ε = 5 mm, far apart.
SceneDescription twoMeshes() {
  return parseSceneText(
      "settings: {epsilon: 0.005}\n"
      "objects:\n"
      "  - name: wrist\n"
      "    geometry: {mesh: {file: kr5-wrist.stl}}\n"
      "    movable: true\n"
      "  - name: finger\n"
      "    geometry: {mesh: {file: bimanual-assembly/tools/finger2-with-adapter.wrl}}\n"
      "    pose: {position: [2, 0, 0]}\n"
      "    movable: true\n",
      "scene.yaml", dataFile("meshes"));
}

// Every vertex of every piece of every body, in order.
std::vector<Vec3> allPieceVertices(const World& world) {
  std::vector<Vec3> vertices;
  const auto add = [&](const CollisionBody& body) {
    for (std::size_t p = 0; p < body.pieceCount(); ++p) {
      const auto& piece = body.piece(p).vertices();
      vertices.insert(vertices.end(), piece.begin(), piece.end());
    }
  };
  for (const WorldRobot& robot : world.robots()) {
    for (std::size_t i = 0; i < robot.collision.partCount(); ++i)
      add(*robot.collision.part(i).body);
  }
  for (std::size_t o = 0; o < world.scene().size(); ++o) add(world.scene().body(o));
  return vertices;
}

std::size_t entriesIn(const std::string& directory) {
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    EXPECT_EQ(entry.path().extension(), ".decomposition") << entry.path();
    ++count;
  }
  return count;
}

TEST(WorldCache, ASecondLoadReadsEveryDecompositionFromTheCache) {
  const test::ScratchDir dir;
  const World cold(readSceneFile(bimanualCell()), cachedIn(dir.file("cache")));
  EXPECT_EQ(cold.cacheReport().misses, 3U);  // two hand meshes and the tabletop
  EXPECT_EQ(cold.cacheReport().hits, 0U);
  const World warm(readSceneFile(bimanualCell()), cachedIn(dir.file("cache")));
  EXPECT_EQ(warm.cacheReport().hits, 3U);
  EXPECT_EQ(warm.cacheReport().misses, 0U);
  EXPECT_EQ(warm.cacheReport().rebuilt, 0U);
  const std::vector<Vec3> coldVertices = allPieceVertices(cold);
  const std::vector<Vec3> warmVertices = allPieceVertices(warm);
  ASSERT_EQ(coldVertices.size(), warmVertices.size());
  EXPECT_EQ(std::memcmp(coldVertices.data(), warmVertices.data(), coldVertices.size() * 24), 0);
  const World uncached(readSceneFile(bimanualCell()));
  EXPECT_EQ(uncached.cacheReport().hits + uncached.cacheReport().misses, 0U);
  EXPECT_EQ(allPieceVertices(uncached).size(), coldVertices.size());
}

TEST(WorldCache, AChangedEpsilonMisses) {
  const test::ScratchDir dir;
  (void)World(readSceneFile(bimanualCell()), cachedIn(dir.file("cache")));
  SceneDescription finer = readSceneFile(bimanualCell());
  finer.settings.epsilon = 0.004;
  const World world(finer, cachedIn(dir.file("cache")));
  EXPECT_EQ(world.cacheReport().hits, 0U);
  EXPECT_GE(world.cacheReport().misses, 3U);
}

TEST(WorldCache, ACacheDirectoryThatCannotBeCreatedIsAnInputError) {
  const test::ScratchDir dir;
  const std::string blocked = dir.write("file", "x") + "/cache";
  EXPECT_THROW(World(readSceneFile(bimanualCell()), cachedIn(blocked)), InputError);
}

TEST(WorldEpsilon, EveryBodyOfTheBimanualCellReachesTheScenesEpsilon) {
  const World world(readSceneFile(bimanualCell()));
  for (const WorldRobot& robot : world.robots()) {
    ASSERT_EQ(robot.partEpsilon.size(), robot.collision.partCount());
    for (const BodyEpsilon& epsilon : robot.partEpsilon) {
      EXPECT_EQ(epsilon.asked, 0.005);
      EXPECT_GT(epsilon.reached, 0);
      EXPECT_TRUE(epsilon.met()) << robot.name << ": " << epsilon.reached;
    }
    ASSERT_EQ(robot.handShapeEpsilon.size(), 1U);
    ASSERT_EQ(robot.handShapeEpsilon[0].size(), 1U);
    EXPECT_EQ(robot.handShapeEpsilon[0][0], robot.partEpsilon[0].reached);
  }
  for (const BodyEpsilon& epsilon : world.objectEpsilon()) EXPECT_TRUE(epsilon.met());
  // The cylinders' 16-sided prisms reach r (1 / cos(π/16) − 1) beyond them.
  const std::size_t bearing = world.find("bearing")->index;
  EXPECT_NEAR(world.objectEpsilon()[bearing].reached, 0.03 * (1 / std::cos(M_PI / 16) - 1), 1e-12);
}

TEST(WorldEpsilon, ThePieceLimitIsRaisedUntilEpsilonIsReached) {
  // The KR5 wrist at 5 mm stops at the default 11 pieces at about 8 mm.
  const World world(twoMeshes());
  const std::size_t wrist = world.find("wrist")->index;
  EXPECT_TRUE(world.objectEpsilon()[wrist].met()) << world.objectEpsilon()[wrist].reached;
  EXPECT_GT(world.scene().body(wrist).pieceCount(), DecompositionOptions{}.maxPieces);

  LinkPieceOptions once;
  once.decompose = true;
  once.decomposition.epsilon = 0.005;
  const BoundingPieces limited =
      boundingMeshPieces(readMesh(dataFile("meshes/kr5-wrist.stl")), "wrist", once);
  EXPECT_EQ(limited.pieces.size(), DecompositionOptions{}.maxPieces);
  EXPECT_GT(limited.boundingError, 0.005) << "kept and recorded where ε is not reached";
}

// ---- the bounded predicate's false alarms stay within the bodies' reached ε ----

TriangleMesh posed(TriangleMesh mesh, const Pose& pose) {
  for (Vec3& v : mesh.vertices) v = pose * v;
  return mesh;
}

// Squared distance between segments pq and rs (Ericson, Real-Time Collision Detection, 5.1.9).
double segmentDistanceSquared(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  const Vec3 d1 = q - p, d2 = s - r, w = p - r;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(w);
  double t1 = 0, t2 = 0;
  if (a <= 1e-30 && e <= 1e-30) return w.squaredNorm();
  if (a <= 1e-30) {
    t2 = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(w);
    if (e <= 1e-30) {
      t1 = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denominator = a * e - b * b;
      t1 = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t2 = (b * t1 + f) / e;
      if (t2 < 0) {
        t2 = 0;
        t1 = std::clamp(-c / a, 0.0, 1.0);
      } else if (t2 > 1) {
        t2 = 1;
        t1 = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p + t1 * d1) - (r + t2 * d2)).squaredNorm();
}

// Whether the solids of closed meshes a and b come within `bound` of each other, exactly: they
// overlap (a triangle crossing, or one inside the other), or a vertex–triangle or edge–edge pair
// is within `bound` (together the triangle–triangle distance).
bool solidsWithin(const TriangleMesh& a, const TriangleMesh& b, double bound) {
  const TriangleBvh treeA(a), treeB(b);
  if (treeB.containsInClosedMesh(a.vertices[0]) || treeA.containsInClosedMesh(b.vertices[0])) {
    return true;
  }
  for (const Vec3& v : a.vertices) {
    if (treeB.hasTriangleWithin(v, bound)) return true;
  }
  for (const Vec3& v : b.vertices) {
    if (treeA.hasTriangleWithin(v, bound)) return true;
  }
  for (const Triangle& t : a.triangles) {
    const Vec3 &t0 = a.vertices[t[0]], &t1 = a.vertices[t[1]], &t2 = a.vertices[t[2]];
    if (treeB.intersectsTriangle(t0, t1, t2)) return true;
    bool within = false;
    const Vec3 pad = Vec3::Constant(bound);
    treeB.forEachTriangleOverlapping(
        t0.cwiseMin(t1).cwiseMin(t2) - pad, t0.cwiseMax(t1).cwiseMax(t2) + pad,
        [&](std::uint32_t u) {
          for (int i = 0; i < 3 && !within; ++i) {
            for (int j = 0; j < 3 && !within; ++j) {
              within =
                  segmentDistanceSquared(a.vertices[t[i]], a.vertices[t[(i + 1) % 3]],
                                         b.vertices[b.triangles[u][j]],
                                         b.vertices[b.triangles[u][(j + 1) % 3]]) <= bound * bound;
            }
          }
          return !within;
        });
    if (within) return true;
  }
  return false;
}

TEST(WorldEpsilon, ReportedCollisionsAreWithinTheBodiesReachedEpsilon) {
  const World world(twoMeshes());
  const std::size_t wrist = world.find("wrist")->index, finger = world.find("finger")->index;
  const double bound = world.objectEpsilon()[wrist].reached + world.objectEpsilon()[finger].reached;
  const SceneDescription& scene = world.description();
  const TriangleMesh wristMesh = readMesh(scene.objects[wrist].geometry.shape.meshPath);
  const TriangleMesh fingerMesh = readMesh(scene.objects[finger].geometry.shape.meshPath);

  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> offset(-0.12, 0.12);
  std::size_t reported = 0, apart = 0;
  for (int trial = 0; trial < 300; ++trial) {
    GeometricState state = world.initialState();
    const Eigen::Quaterniond rotation =
        Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random))
            .normalized();
    Pose pose = Pose::Identity();
    pose.linear() = rotation.toRotationMatrix();
    pose.translation() = Vec3(offset(random), offset(random), offset(random));
    state.placements[world.scene().slot(finger)].pose = pose;
    const auto collision = world.firstCollision(state);
    if (!collision) continue;
    ++reported;
    const Pose wristPose = world.scene().pose(wrist, state.placements);
    const TriangleMesh a = posed(wristMesh, wristPose), b = posed(fingerMesh, pose);
    EXPECT_TRUE(solidsWithin(a, b, bound))
        << "trial " << trial << ": reported farther than " << bound << " apart";
    if (!solidsWithin(a, b, 0.0)) ++apart;
  }
  std::cout << reported << " collisions reported, " << apart << " of them between meshes apart\n";
  EXPECT_GT(reported, 20U);
  EXPECT_GT(apart, 0U) << "no false alarm tested";
}

// ---- the `kaboum scene` verb with its cache options ----

TEST(SceneCacheCli, ReportsMissesThenHitsAndEpsilonPerBody) {
  const test::ScratchDir dir;
  const std::string arguments = "scene --cache-dir '" + dir.file("cache") + "' '" + bimanualCell();
  test::CliResult result = test::runCli(dir, arguments + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("cache:         0 hit(s), 3 miss(es), 0 rebuilt"), std::string::npos)
      << result.out;
  for (const char* line : {"link body6: 5 piece(s), ε 4.27 mm", "hand shape of left-gripper: ε",
                           "bearing: movable, 1 piece(s), 32 vertices, ε 0.588 mm"}) {
    EXPECT_NE(result.out.find(line), std::string::npos) << line << "\n" << result.out;
  }
  result = test::runCli(dir, arguments + "' --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  EXPECT_EQ(report["cache"]["hits"], 3);
  EXPECT_EQ(report["cache"]["misses"], 0);
  EXPECT_EQ(report["cache"]["directory"], dir.file("cache"));
  EXPECT_EQ(report["robots"][0]["parts"][0]["link"], "body6");
  EXPECT_EQ(report["robots"][0]["parts"][0]["epsilon"]["met"], true);
  EXPECT_EQ(report["robots"][0]["hands"][0]["tool"], "left-gripper");
  EXPECT_EQ(report["objects"][0]["epsilon"]["asked"], 0.005);
}

TEST(SceneCacheCli, TwoProcessesFillingOneDirectoryBothSucceed) {
  const test::ScratchDir dir;
  const std::string run = "'" + std::string(KABOUM_CLI) + "' scene --quiet --cache-dir '" +
                          dir.file("cache") + "' '" + bimanualCell() + "'";
  const test::CliResult result =
      test::runProgram("/bin/sh", dir, "-c \"" + run + " & " + run + " & wait %1 && wait %2\"");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "initial state: collision-free\ninitial state: collision-free\n");
  EXPECT_EQ(entriesIn(dir.file("cache")), 3U);
  const World world(readSceneFile(bimanualCell()), cachedIn(dir.file("cache")));
  EXPECT_EQ(world.cacheReport().hits, 3U);
}

TEST(SceneCacheCli, NoCacheWritesNothing) {
  const test::ScratchDir dir;
  const test::CliResult result =
      test::runProgram("/usr/bin/env", dir,
                       "KABOUM_CACHE_DIR='" + dir.file("cache") + "' '" + KABOUM_CLI +
                           "' scene --no-cache '" + bimanualCell() + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("cache:         off"), std::string::npos) << result.out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("cache")));
}

TEST(SceneCacheCli, TheDefaultDirectoryComesFromTheEnvironment) {
  const test::ScratchDir dir;
  const std::string scene =
      " '" + std::string(KABOUM_CLI) + "' scene --quiet '" + bimanualCell() + "'";
  test::CliResult result =
      test::runProgram("/usr/bin/env", dir, "KABOUM_CACHE_DIR='" + dir.file("own") + "'" + scene);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(entriesIn(dir.file("own")), 3U);
  result = test::runProgram("/usr/bin/env", dir,
                            "-u KABOUM_CACHE_DIR XDG_CACHE_HOME='" + dir.file("xdg") + "'" + scene);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(entriesIn(dir.file("xdg/kaboum")), 3U);
  result = test::runProgram(
      "/usr/bin/env", dir,
      "-u KABOUM_CACHE_DIR -u XDG_CACHE_HOME HOME='" + dir.file("home") + "'" + scene);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(entriesIn(dir.file("home/.cache/kaboum")), 3U);
}

TEST(SceneCacheCli, ACorruptEntryGivesOneWarningAndIsRebuilt) {
  const test::ScratchDir dir;
  const std::string arguments = "scene --cache-dir '" + dir.file("cache") + "' '" + bimanualCell();
  ASSERT_EQ(test::runCli(dir, arguments + "'").exitCode, 0);
  const auto entry = *std::filesystem::directory_iterator(dir.file("cache"));
  std::filesystem::resize_file(entry.path(), 100);
  test::CliResult result = test::runCli(dir, arguments + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(test::lineCount(result.err), 1U) << result.err;
  EXPECT_NE(result.err.find("kaboum: warning: " + entry.path().string()), std::string::npos)
      << result.err;
  EXPECT_NE(result.out.find("2 hit(s), 0 miss(es), 1 rebuilt"), std::string::npos) << result.out;
  std::filesystem::resize_file(entry.path(), 100);
  result = test::runCli(dir, arguments + "' --quiet");
  EXPECT_EQ(result.err, "");
  result = test::runCli(dir, arguments + "'");
  EXPECT_NE(result.out.find("3 hit(s)"), std::string::npos) << result.out;
}

TEST(SceneCacheCli, ACacheDirectoryThatCannotBeCreatedExitsWithTwo) {
  const test::ScratchDir dir;
  const std::string blocked = dir.write("file", "x") + "/cache";
  const test::CliResult result =
      test::runCli(dir, "scene --cache-dir '" + blocked + "' '" + bimanualCell() + "'");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(test::lineCount(result.err), 1U) << result.err;
  EXPECT_NE(result.err.find(blocked + ": cannot create the cache directory"), std::string::npos)
      << result.err;
}

}  // namespace

}  // namespace kaboum::world
