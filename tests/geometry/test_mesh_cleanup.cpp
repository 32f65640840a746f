// weldVertices, removeUnreferencedVertices and repairOrientation: exactness, tolerance, order,
// and orientation repair on real meshes with random damage.
#include <gtest/gtest.h>

#include <random>

#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

TriangleMesh dataMesh(const std::string& name) {
  return readMesh(kaboum::testing::dataFile("meshes/" + name));
}

// Every triangle with its own three vertices, as STL stores it.
TriangleMesh triangleSoup(const TriangleMesh& mesh) {
  TriangleMesh soup;
  for (const Triangle& t : mesh.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.vertices.size());
    for (const std::uint32_t v : t) soup.vertices.push_back(mesh.vertices[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  return soup;
}

void expectSameTrianglePositions(const TriangleMesh& actual, const TriangleMesh& expected) {
  ASSERT_EQ(actual.triangles.size(), expected.triangles.size());
  for (std::size_t t = 0; t < expected.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(actual.vertices[actual.triangles[t][k]],
                expected.vertices[expected.triangles[t][k]])
          << "triangle " << t;
    }
  }
}

TEST(WeldVertices, TriangleSoupWeldsBackToTheSharedMesh) {
  for (const char* name : {"cow.obj", "fandisk.obj"}) {
    const TriangleMesh mesh = dataMesh(name);
    TriangleMesh soup = triangleSoup(mesh);
    weldVertices(soup);
    EXPECT_EQ(soup.vertices.size(), mesh.vertices.size()) << name;
    expectSameTrianglePositions(soup, mesh);
  }
}

TEST(WeldVertices, KeepsFirstOccurrenceOrderAndIsIdempotent) {
  TriangleMesh mesh;
  mesh.vertices = {Vec3(9, 9, 9), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0)};
  mesh.triangles = {{1, 4, 3}, {2, 1, 3}};
  weldVertices(mesh);  // (9,9,9) is unreferenced, vertex 4 repeats vertex 2
  EXPECT_EQ(mesh.vertices, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}, {1, 0, 2}}));
  const TriangleMesh once = mesh;
  weldVertices(mesh);
  EXPECT_EQ(mesh.vertices, once.vertices);
  EXPECT_EQ(mesh.triangles, once.triangles);
}

TEST(WeldVertices, ExactMeansExact) {
  TriangleMesh mesh;
  const double next = std::nextafter(1.0, 2.0);
  mesh.vertices = {Vec3(0.0, 0, 0), Vec3(-0.0, 0, 0), Vec3(1, 0, 0), Vec3(next, 0, 0),
                   Vec3(0, 1, 0)};
  mesh.triangles = {{0, 2, 4}, {1, 3, 4}};
  weldVertices(mesh);
  // -0 and +0 are one position; 1 and the next double are two.
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.triangles[1][0], mesh.triangles[0][0]);
  EXPECT_NE(mesh.triangles[1][1], mesh.triangles[0][1]);
}

TEST(WeldVertices, ToleranceMergesNearCopiesOnly) {
  const TriangleMesh cow = dataMesh("cow.obj");
  const double tolerance = 1e-6;
  TriangleMesh soup = triangleSoup(cow);
  std::mt19937 random(9);
  std::uniform_real_distribution<double> jitter(-tolerance / 4, tolerance / 4);
  for (Vec3& p : soup.vertices) p += Vec3(jitter(random), jitter(random), jitter(random));
  TriangleMesh exact = soup;
  weldVertices(exact);
  EXPECT_GT(exact.vertices.size(), 3 * cow.vertices.size());  // jitter defeats exact welding
  weldVertices(soup, tolerance);
  EXPECT_EQ(soup.vertices.size(), cow.vertices.size());
  for (std::size_t t = 0; t < cow.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE((soup.vertices[soup.triangles[t][k]] - cow.vertices[cow.triangles[t][k]]).norm(),
                tolerance);
    }
  }
  // Points 2 tolerances apart stay apart; 0.9 tolerances apart merge into the earlier one.
  TriangleMesh pair;
  pair.vertices = {Vec3(0, 0, 0), Vec3(2e-6, 0, 0), Vec3(0, 0.9e-6, 0)};
  pair.triangles = {{0, 1, 2}};
  weldVertices(pair, tolerance);
  EXPECT_EQ(pair.vertices, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(2e-6, 0, 0)}));
  EXPECT_EQ(pair.triangles, (std::vector<Triangle>{{0, 1, 0}}));
}

TEST(RemoveUnreferencedVertices, DropsOnlyUnusedVertices) {
  const TriangleMesh cube = dataMesh("cube.off");
  TriangleMesh padded;
  for (const Vec3& p : cube.vertices) {
    padded.vertices.push_back(Vec3(7, 7, 7));
    padded.vertices.push_back(p);
  }
  for (Triangle t : cube.triangles) {
    for (std::uint32_t& v : t) v = 2 * v + 1;
    padded.triangles.push_back(t);
  }
  removeUnreferencedVertices(padded);
  EXPECT_EQ(padded.vertices, cube.vertices);
  EXPECT_EQ(padded.triangles, cube.triangles);
}

TEST(RepairOrientation, CubeWithOneFlippedFace) {
  const TriangleMesh cube = dataMesh("cube.off");
  TriangleMesh damaged = cube;
  std::swap(damaged.triangles[5][1], damaged.triangles[5][2]);
  EXPECT_TRUE(repairOrientation(damaged));
  EXPECT_EQ(damaged.triangles, cube.triangles);
}

TEST(RepairOrientation, InwardCowTurnsOutward) {
  const TriangleMesh cow = dataMesh("cow.obj");
  TriangleMesh inward = cow;
  for (Triangle& t : inward.triangles) std::swap(t[0], t[1]);
  ASSERT_FALSE(analyzeMesh(inward).outwardOriented);
  EXPECT_TRUE(repairOrientation(inward));
  const MeshAnalysis repaired = analyzeMesh(inward);
  EXPECT_TRUE(repaired.outwardOriented);
  EXPECT_NEAR(repaired.volume, analyzeMesh(cow).volume, 1e-12);
  for (std::size_t t = 0; t < cow.triangles.size(); ++t) {
    // Same triangle, same cyclic order as the original.
    const Triangle& a = inward.triangles[t];
    const Triangle& b = cow.triangles[t];
    EXPECT_TRUE((a == b || a == Triangle{b[1], b[2], b[0]} || a == Triangle{b[2], b[0], b[1]}));
  }
}

// Random flips on closed and open real meshes: repair restores every original triangle (open
// meshes keep the orientation most triangles had, so fewer than half are flipped).
TEST(RepairOrientation, UndoesRandomFlips) {
  std::mt19937 random(13);
  for (const char* name : {"spot.obj", "fandisk.obj", "kr5-base-link.stl", "wam2.stl"}) {
    const TriangleMesh original = dataMesh(name);
    for (int trial = 0; trial < 3; ++trial) {
      TriangleMesh damaged = original;
      std::bernoulli_distribution flip(0.3);
      for (Triangle& t : damaged.triangles) {
        if (flip(random)) std::swap(t[1], t[2]);
      }
      EXPECT_TRUE(repairOrientation(damaged)) << name;
      EXPECT_EQ(damaged.triangles, original.triangles) << name;
    }
  }
}

TEST(RepairOrientation, MoebiusStripCannotBeOrientedAndStaysUnchanged) {
  // Four quads around a loop, the last one joined with a half twist.
  TriangleMesh strip;
  constexpr int kSegments = 4;
  for (int i = 0; i < kSegments; ++i) {
    const double angle = 2.0 * 3.141592653589793 * i / kSegments;
    strip.vertices.emplace_back(std::cos(angle), std::sin(angle), -0.2);
    strip.vertices.emplace_back(std::cos(angle), std::sin(angle), 0.2);
  }
  for (std::uint32_t i = 0; i < kSegments; ++i) {
    const std::uint32_t a = 2 * i, b = 2 * i + 1;
    const bool last = i + 1 == kSegments;
    const std::uint32_t c = last ? 1 : 2 * i + 2, d = last ? 0 : 2 * i + 3;  // twist
    strip.triangles.push_back({a, c, d});
    strip.triangles.push_back({a, d, b});
  }
  ASSERT_EQ(analyzeMesh(strip).nonManifoldEdges, 0u);
  const TriangleMesh before = strip;
  EXPECT_FALSE(repairOrientation(strip));
  EXPECT_EQ(strip.triangles, before.triangles);
}

TEST(RepairOrientation, NonManifoldComponentStaysWhileOthersAreRepaired) {
  const TriangleMesh cube = dataMesh("cube.off");
  TriangleMesh mesh = cube;
  mesh.vertices.emplace_back(-1.0, 0.0, 0.5);
  mesh.triangles.push_back({0, 8, 4});  // a fin: edge 0-4 now has three triangles
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
  // A second, separate cube turned inside out.
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (const Vec3& p : cube.vertices) mesh.vertices.push_back(p + Vec3(5, 0, 0));
  for (Triangle t : cube.triangles) {
    mesh.triangles.push_back({t[0] + base, t[2] + base, t[1] + base});
  }
  const TriangleMesh before = mesh;
  EXPECT_FALSE(repairOrientation(mesh));
  for (std::size_t t = 0; t < 13; ++t) EXPECT_EQ(mesh.triangles[t], before.triangles[t]);
  for (std::size_t t = 0; t < 12; ++t) {
    const Triangle& c = cube.triangles[t];
    EXPECT_EQ(mesh.triangles[13 + t], (Triangle{c[0] + base, c[1] + base, c[2] + base}));
  }
}

}  // namespace
}  // namespace kaboum::geometry
