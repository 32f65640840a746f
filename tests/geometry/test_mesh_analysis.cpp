// analyzeMesh on real models and robot links and on small shapes with one known defect each.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

TriangleMesh dataMesh(const std::string& name) {
  return readMesh(kaboum::testing::dataFile("meshes/" + name));
}

TriangleMesh reversed(TriangleMesh mesh) {
  for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

// `mesh` plus a copy of itself moved by `offset`.
TriangleMesh withCopy(const TriangleMesh& mesh, const Vec3& offset) {
  TriangleMesh both = mesh;
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) both.vertices.push_back(p + offset);
  for (Triangle t : mesh.triangles) {
    for (std::uint32_t& v : t) v += base;
    both.triangles.push_back(t);
  }
  return both;
}

class ClosedModel : public ::testing::TestWithParam<const char*> {};

TEST_P(ClosedModel, IsClosedEdgeManifoldAndOutward) {
  const TriangleMesh mesh = dataMesh(GetParam());
  const MeshAnalysis a = analyzeMesh(mesh);
  EXPECT_EQ(a.vertices, mesh.vertices.size());
  EXPECT_EQ(a.triangles, mesh.triangles.size());
  EXPECT_EQ(a.components, 1u);
  EXPECT_TRUE(a.closed);
  EXPECT_EQ(a.borderEdges, 0u);
  EXPECT_EQ(a.borderLoops, 0u);
  EXPECT_TRUE(a.edgeManifold);
  EXPECT_TRUE(a.consistentlyOriented);
  EXPECT_TRUE(a.outwardOriented);
  EXPECT_EQ(a.degenerateTriangles, 0u);
  EXPECT_GT(a.volume, 0.0);
  // A closed edge-manifold surface has 3F/2 edges, and a connected orientable one has
  // V - E + F = 2 - 2 genus, less one per pinched vertex.
  ASSERT_EQ(a.triangles % 2, 0u);
  const auto edges = static_cast<long>(3 * a.triangles / 2);
  const long euler = static_cast<long>(a.vertices) - edges + static_cast<long>(a.triangles) +
                     static_cast<long>(a.nonManifoldVertices);
  EXPECT_LE(euler, 2);
  EXPECT_EQ(euler % 2, 0);
}

INSTANTIATE_TEST_SUITE_P(RealData, ClosedModel,
                         ::testing::Values("cow.obj", "spot.obj", "fandisk.obj", "kr5-wrist.stl",
                                           "bimanual-assembly/tools/finger2.wrl"));

TEST(AnalyzeMesh, CowHasOnePinchedVertex) {
  // Vertex (-3.507689, 1.700214, 0) of the cow joins two separate triangle fans (checked
  // independently); the surface is still edge-manifold.
  const MeshAnalysis cow = analyzeMesh(dataMesh("cow.obj"));
  EXPECT_EQ(cow.nonManifoldVertices, 1u);
  EXPECT_TRUE(cow.edgeManifold);
  EXPECT_EQ(analyzeMesh(dataMesh("spot.obj")).nonManifoldVertices, 0u);
}

TEST(AnalyzeMesh, UnitCubeFigures) {
  const MeshAnalysis cube = analyzeMesh(dataMesh("cube.off"));
  EXPECT_EQ(cube.volume, 1.0);
  EXPECT_EQ(cube.boxMin, Vec3::Zero());
  EXPECT_EQ(cube.boxMax, Vec3::Ones());
  EXPECT_DOUBLE_EQ(cube.diagonal, std::sqrt(3.0));
  EXPECT_EQ(cube.nonManifoldVertices, 0u);
}

TEST(AnalyzeMesh, VolumeOfClosedMeshIgnoresWhereItIs) {
  const TriangleMesh cow = dataMesh("cow.obj");
  const double volume = analyzeMesh(cow).volume;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> offset(-1e3, 1e3);
  for (int trial = 0; trial < 5; ++trial) {
    TriangleMesh moved = cow;
    const Vec3 shift(offset(random), offset(random), offset(random));
    for (Vec3& p : moved.vertices) p += shift;
    EXPECT_NEAR(analyzeMesh(moved).volume, volume, 1e-9 * volume);
  }
}

TEST(AnalyzeMesh, InwardCowIsConsistentButNotOutward) {
  const TriangleMesh cow = dataMesh("cow.obj");
  const MeshAnalysis inward = analyzeMesh(reversed(cow));
  EXPECT_TRUE(inward.closed);
  EXPECT_TRUE(inward.consistentlyOriented);
  EXPECT_FALSE(inward.outwardOriented);
  EXPECT_EQ(inward.volume, -analyzeMesh(cow).volume);
}

TEST(AnalyzeMesh, OneFlippedFaceIsInconsistent) {
  TriangleMesh cube = dataMesh("cube.off");
  std::swap(cube.triangles[3][1], cube.triangles[3][2]);
  const MeshAnalysis a = analyzeMesh(cube);
  EXPECT_TRUE(a.closed);
  EXPECT_FALSE(a.consistentlyOriented);
  EXPECT_FALSE(a.outwardOriented);
}

TEST(AnalyzeMesh, RemovedFacesLeaveBorderLoops) {
  TriangleMesh open = dataMesh("cube.off");
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 2);  // the x = 0 side
  MeshAnalysis a = analyzeMesh(open);
  EXPECT_FALSE(a.closed);
  EXPECT_EQ(a.borderEdges, 4u);
  EXPECT_EQ(a.borderLoops, 1u);
  EXPECT_TRUE(a.consistentlyOriented);
  EXPECT_FALSE(a.outwardOriented);  // no closed component to judge by
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 2);  // and x = 1: a tube
  a = analyzeMesh(open);
  EXPECT_EQ(a.borderEdges, 8u);
  EXPECT_EQ(a.borderLoops, 2u);
  EXPECT_EQ(a.components, 1u);
}

class OpenRobotLink : public ::testing::TestWithParam<const char*> {};

TEST_P(OpenRobotLink, ReportsBorderLoops) {
  const MeshAnalysis a = analyzeMesh(dataMesh(GetParam()));
  EXPECT_FALSE(a.closed);
  EXPECT_GE(a.borderLoops, 1u);
  EXPECT_GE(a.borderEdges, 3 * a.borderLoops);  // a hole needs at least three edges
  EXPECT_FALSE(a.outwardOriented);
}

INSTANTIATE_TEST_SUITE_P(RealData, OpenRobotLink,
                         ::testing::Values("kr5-base-link.stl", "wam2.stl", "wam2.dae"));

TEST(AnalyzeMesh, ThreeTrianglesOnAnEdgeAreNonManifold) {
  TriangleMesh cube = dataMesh("cube.off");
  cube.vertices.emplace_back(-1.0, 0.0, 0.5);  // a fin on edge 0-4 of the cube
  cube.triangles.push_back({0, 8, 4});
  const MeshAnalysis a = analyzeMesh(cube);
  EXPECT_EQ(a.nonManifoldEdges, 1u);
  EXPECT_FALSE(a.edgeManifold);
  EXPECT_EQ(a.nonManifoldVertices, 2u);  // both ends of that edge
  EXPECT_EQ(a.borderEdges, 2u);          // the fin's free edges
  EXPECT_EQ(a.components, 1u);
}

TEST(AnalyzeMesh, CubesTouchingAtACornerPinchThatVertex) {
  const TriangleMesh cube = dataMesh("cube.off");
  TriangleMesh pair = withCopy(cube, Vec3::Ones());
  // Make the copy's corner (0,0,0) + (1,1,1) the original's vertex 7 = (1,1,1).
  for (Triangle& t : pair.triangles) {
    for (std::uint32_t& v : t) v = (v == 8) ? 7 : v;
  }
  const MeshAnalysis a = analyzeMesh(pair);
  EXPECT_EQ(a.components, 2u);
  EXPECT_TRUE(a.closed);
  EXPECT_TRUE(a.edgeManifold);
  EXPECT_EQ(a.nonManifoldVertices, 1u);
  EXPECT_TRUE(a.outwardOriented);
  EXPECT_EQ(a.volume, 2.0);
}

TEST(AnalyzeMesh, DegenerateTrianglesAreCounted) {
  TriangleMesh cube = dataMesh("cube.off");
  cube.vertices.emplace_back(0.5, 0.0, 0.0);
  cube.triangles.push_back({0, 8, 1});  // collinear
  cube.triangles.push_back({2, 2, 3});  // repeated index
  EXPECT_EQ(analyzeMesh(cube).degenerateTriangles, 2u);
  EXPECT_TRUE(isDegenerateTriangle(cube, {0, 8, 1}));
  EXPECT_FALSE(isDegenerateTriangle(cube, {0, 1, 2}));
}

TEST(AnalyzeMesh, ComponentsAndVolumesAddUp) {
  const MeshAnalysis two = analyzeMesh(withCopy(dataMesh("cube.off"), Vec3(3, 0, 0)));
  EXPECT_EQ(two.components, 2u);
  EXPECT_EQ(two.volume, 2.0);
  EXPECT_EQ(two.boxMax, Vec3(4, 1, 1));
  // One of two closed components inward: not outward oriented.
  TriangleMesh mixed = withCopy(dataMesh("cube.off"), Vec3(3, 0, 0));
  for (std::size_t t = 12; t < 24; ++t) std::swap(mixed.triangles[t][1], mixed.triangles[t][2]);
  const MeshAnalysis a = analyzeMesh(mixed);
  EXPECT_TRUE(a.consistentlyOriented);
  EXPECT_FALSE(a.outwardOriented);
  EXPECT_EQ(a.volume, 0.0);
}

TEST(AnalyzeMesh, EmptyMeshIsAllZero) {
  const MeshAnalysis a = analyzeMesh(TriangleMesh{});
  EXPECT_EQ(a.triangles, 0u);
  EXPECT_EQ(a.components, 0u);
  EXPECT_EQ(a.diagonal, 0.0);
  EXPECT_FALSE(a.closed);
}

TEST(FindEdgeNeighbors, PairsEveryCubeEdge) {
  const TriangleMesh cube = dataMesh("cube.off");
  const EdgeNeighbors n = findEdgeNeighbors(cube);
  ASSERT_EQ(n.across.size(), 36u);
  for (std::uint32_t id = 0; id < 36; ++id) {
    const std::uint32_t other = n.across[id];
    ASSERT_LT(other, 12u);
    // The neighbour runs the shared edge the other way.
    const Triangle& t = cube.triangles[id / 3];
    const std::uint32_t a = t[id % 3], b = t[(id % 3 + 1) % 3];
    const Triangle& o = cube.triangles[other];
    bool found = false;
    for (int k = 0; k < 3; ++k) found = found || (o[k] == b && o[(k + 1) % 3] == a);
    EXPECT_TRUE(found) << "edge " << id;
  }
  EXPECT_EQ(n.borderEdges, 0u);
  EXPECT_EQ(n.nonManifoldEdges, 0u);
  EXPECT_EQ(n.inconsistentEdges, 0u);
}

}  // namespace
}  // namespace kaboum::geometry
