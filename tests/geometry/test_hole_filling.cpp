// Hole filling: open meshes become closed (every directed edge matched), keeping the original
// surface as it was, on procedural shapes and on the open robot links shipped in data/.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "kaboum/geometry/hole_filling.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

// Directed edges (a, b) whose count differs from that of (b, a): zero for a closed mesh.
std::size_t unmatchedDirectedEdges(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> balance;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ++balance[{a, b}];
      --balance[{b, a}];
    }
  }
  return static_cast<std::size_t>(std::count_if(
      balance.begin(), balance.end(), [](const auto& entry) { return entry.second != 0; }));
}

double signedVolume(const TriangleMesh& mesh) {
  double six = 0.0;
  for (const Triangle& t : mesh.triangles) {
    six += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return six / 6.0;
}

// The original vertices and triangles are an unchanged prefix of the filled mesh.
void expectOriginalKept(const TriangleMesh& original, const TriangleMesh& filled) {
  ASSERT_GE(filled.vertexCount(), original.vertexCount());
  ASSERT_GE(filled.triangleCount(), original.triangleCount());
  EXPECT_TRUE(
      std::equal(original.vertices.begin(), original.vertices.end(), filled.vertices.begin()));
  EXPECT_TRUE(
      std::equal(original.triangles.begin(), original.triangles.end(), filled.triangles.begin()));
}

TEST(HoleFilling, OpenBoxGetsItsTopBackWithTheBoxVolume) {
  const TriangleMesh open = makeOpenBox(Vec3(0, 0, 0), Vec3(2, 3, 1), 2);
  TriangleMesh filled = open;
  const HoleFillingReport report = fillHoles(filled);
  EXPECT_EQ(report.loops, 1u);
  EXPECT_EQ(report.addedVertices, 1u);  // the loop has 8 edges: a centroid fan
  EXPECT_EQ(report.addedTriangles, 8u);
  expectOriginalKept(open, filled);
  const MeshAnalysis analysis = analyzeMesh(filled);
  EXPECT_TRUE(analysis.closed);
  EXPECT_TRUE(analysis.consistentlyOriented);
  EXPECT_TRUE(analysis.outwardOriented);
  EXPECT_NEAR(analysis.volume, 6.0, 1e-12);
  // The cap lies in the missing face: its centroid is the face's centre.
  EXPECT_TRUE(filled.vertices.back().isApprox(Vec3(1, 1.5, 1), 1e-12));
}

TEST(HoleFilling, ClosedMeshIsLeftAlone) {
  TriangleMesh mesh = makeTorus(1.0, 0.3, 16, 8);
  const TriangleMesh before = mesh;
  const HoleFillingReport report = fillHoles(mesh);
  EXPECT_EQ(report.loops, 0u);
  EXPECT_EQ(report.addedTriangles, 0u);
  EXPECT_EQ(mesh.vertices, before.vertices);
  EXPECT_EQ(mesh.triangles, before.triangles);
}

TEST(HoleFilling, TriangularHoleGetsOneTriangle) {
  TriangleMesh mesh = makeIcosphere(1);
  const Triangle removed = mesh.triangles.back();
  mesh.triangles.pop_back();
  const TriangleMesh open = mesh;
  const HoleFillingReport report = fillHoles(mesh);
  EXPECT_EQ(report.loops, 1u);
  EXPECT_EQ(report.addedVertices, 0u);
  ASSERT_EQ(report.addedTriangles, 1u);
  expectOriginalKept(open, mesh);
  // The same triangle, possibly starting at another corner.
  Triangle cap = mesh.triangles.back();
  while (cap[0] != removed[0]) std::rotate(cap.begin(), cap.begin() + 1, cap.end());
  EXPECT_EQ(cap, removed);
}

TEST(HoleFilling, NonManifoldFinIsClosedInTheDirectedEdgeSense) {
  // A closed box with an extra triangle hanging off one of its edges (three triangles on it).
  TriangleMesh mesh = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const Triangle& first = mesh.triangles.front();
  mesh.vertices.emplace_back(-1, -1, -1);
  mesh.triangles.push_back(
      {first[0], first[1], static_cast<std::uint32_t>(mesh.vertices.size() - 1)});
  ASSERT_GT(unmatchedDirectedEdges(mesh), 0u);
  const TriangleMesh before = mesh;
  const HoleFillingReport report = fillHoles(mesh);
  EXPECT_GE(report.loops, 1u);
  expectOriginalKept(before, mesh);
  EXPECT_EQ(unmatchedDirectedEdges(mesh), 0u);
}

TEST(HoleFilling, OpenRobotLinksInDataBecomeClosedKeepingTheirSurfaceAndVolume) {
  for (const std::string name : {"kr5-base-link.stl", "wam2.stl", "wam2.dae"}) {
    SCOPED_TRACE(name);
    TriangleMesh mesh = readMesh(kaboum::testing::dataFile(std::string("meshes/") + name));
    bool flipped = false;
    ASSERT_TRUE(orientOutward(mesh, flipped));
    const MeshAnalysis before = analyzeMesh(mesh);
    ASSERT_FALSE(before.closed);
    const TriangleMesh open = mesh;
    const HoleFillingReport report = fillHoles(mesh);
    EXPECT_GE(report.loops, before.borderLoops > 0 ? 1u : 0u);
    EXPECT_EQ(report.addedTriangles, mesh.triangleCount() - open.triangleCount());
    expectOriginalKept(open, mesh);
    EXPECT_EQ(unmatchedDirectedEdges(mesh), 0u);
    const MeshAnalysis after = analyzeMesh(mesh);
    EXPECT_EQ(after.borderEdges, 0u);
    // Outward orientation survives: the capped solid has positive volume.
    EXPECT_GT(signedVolume(mesh), 0.0);
  }
}

TEST(HoleFilling, IsDeterministic) {
  TriangleMesh a = readMesh(kaboum::testing::dataFile("meshes/kr5-base-link.stl"));
  TriangleMesh b = a;
  fillHoles(a);
  fillHoles(b);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
}

}  // namespace
}  // namespace kaboum::geometry
