#include <gtest/gtest.h>

#include <random>
#include <string>

#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/quick_hull.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

constexpr double kTolerance = 1e-10;

// What the decomposition relies on: a closed, outward, edge-manifold mesh over input points with
// qhull's volume; every input point is at most the tolerance outside the hull of its vertices, and
// those are at most 1000 tolerances above every triangle's plane (a sliver triangle's tilt).
void expectHullOf(const std::vector<Vec3>& points, const std::string& what) {
  SCOPED_TRACE(what);
  const std::optional<TriangleMesh> hull = quickHull(points, kTolerance);
  ASSERT_TRUE(hull.has_value());
  const MeshAnalysis analysis = analyzeMesh(*hull);
  EXPECT_TRUE(analysis.closed);
  EXPECT_TRUE(analysis.edgeManifold);
  EXPECT_TRUE(analysis.outwardOriented);
  EXPECT_EQ(analysis.components, 1u);
  const ConvexHull reference = convexHull(points);
  const double referenceVolume = analyzeMesh(reference.mesh).volume;
  EXPECT_NEAR(analysis.volume, referenceVolume, 1e-9 * referenceVolume);
  double worstAbove = 0.0;
  for (const Triangle& t : hull->triangles) {
    const Vec3& a = hull->vertices[t[0]];
    const Vec3 normal = (hull->vertices[t[1]] - a).cross(hull->vertices[t[2]] - a).normalized();
    for (const Vec3& p : points) worstAbove = std::max(worstAbove, normal.dot(p - a));
  }
  EXPECT_LE(worstAbove, 1001 * kTolerance);
  for (const Vec3& v : hull->vertices) {
    EXPECT_NE(std::find(points.begin(), points.end(), v), points.end()) << "not an input point";
  }
}

TEST(QuickHull, CubeCornersAmongInteriorPointsGiveTwelveTrianglesAndVolumeEight) {
  std::vector<Vec3> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> inside(-0.9, 0.9);
  for (int i = 0; i < 100; ++i) points.emplace_back(inside(rng), inside(rng), inside(rng));
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  const std::optional<TriangleMesh> hull = quickHull(points, kTolerance);
  ASSERT_TRUE(hull.has_value());
  EXPECT_EQ(hull->vertexCount(), 8u);
  EXPECT_EQ(hull->triangleCount(), 12u);
  EXPECT_NEAR(analyzeMesh(*hull).volume, 8.0, 1e-12);
  expectHullOf(points, "cube");
}

// Random sets of the kinds a decomposition meets: points in general position (on a sphere, so
// all are vertices), many coplanar ones (box faces, a grid with repeated points), and a real
// link's vertices with the crossings of its edges with a cut plane (coplanar, a rounding apart).
TEST(QuickHull, MatchesQhullOnRandomAndRealPointSets) {
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const std::size_t n : {5u, 40u, 400u}) {
    std::vector<Vec3> sphere, box, grid;
    for (std::size_t i = 0; i < n; ++i) {
      sphere.push_back(Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized());
      Vec3 b(unit(rng), unit(rng), unit(rng));
      b[static_cast<int>(i % 3)] = (i / 3) % 2 != 0 ? 1.0 : -1.0;
      box.push_back(b);
      grid.emplace_back(std::round(4 * unit(rng)) / 4, std::round(4 * unit(rng)) / 4,
                        std::round(4 * unit(rng)) / 4);
    }
    expectHullOf(sphere, "sphere " + std::to_string(n));
    expectHullOf(box, "box faces " + std::to_string(n));
    if (n > 5) expectHullOf(grid, "grid " + std::to_string(n));
  }
  const TriangleMesh wrist = readMesh(kaboum::testing::dataFile("meshes/kr5-wrist.stl"));
  expectHullOf(wrist.vertices, "KR5 wrist");
  const MeshAnalysis analysis = analyzeMesh(wrist);
  for (const double fraction : {0.3, 0.5, 0.7}) {
    const double cut = analysis.boxMin.z() + fraction * (analysis.boxMax.z() - analysis.boxMin.z());
    const std::vector<Vec3> below = pointsBelowCut(wrist, cut);
    expectHullOf(below, "KR5 wrist below a cut at " + std::to_string(fraction));
  }
}

// Near-degenerate sets (box faces jittered by less or a little more than the tolerance, points
// repeated): a hull, when there is one, is a valid one; where the tolerance cannot keep the surface
// one closed sheet there is none, and the decomposition falls back to qhull.
TEST(QuickHull, NearlyCoplanarPointsGiveAValidHullOrNone) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t hulls = 0;
  for (int set = 0; set < 200; ++set) {
    const double jitter = (set % 3 == 0 ? 0.5 : set % 3 == 1 ? 3.0 : 30.0) * kTolerance;
    std::vector<Vec3> points;
    for (int i = 0; i < 60; ++i) {
      Vec3 p(unit(rng), unit(rng), unit(rng));
      p[i % 3] = ((i / 3) % 2 != 0 ? 1.0 : -1.0) + jitter * unit(rng);
      points.push_back(p);
      if (i % 7 == 0) points.push_back(p);
    }
    if (quickHull(points, kTolerance)) {
      ++hulls;
      expectHullOf(points, "set " + std::to_string(set));
    }
  }
  EXPECT_GE(hulls, 180u);
}

TEST(QuickHull, SameInputSameMesh) {
  const TriangleMesh torus = makeTorus(1.0, 0.3, 24, 12);
  const std::optional<TriangleMesh> first = quickHull(torus.vertices, kTolerance);
  const std::optional<TriangleMesh> second = quickHull(torus.vertices, kTolerance);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(first->vertices, second->vertices);
  EXPECT_EQ(first->triangles, second->triangles);
}

TEST(QuickHull, PointsWithoutVolumeGiveNoHull) {
  EXPECT_FALSE(quickHull(std::vector<Vec3>{}, kTolerance));
  EXPECT_FALSE(
      quickHull(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, kTolerance));
  const std::vector<Vec3> same(10, Vec3(0.5, 0.5, 0.5));
  EXPECT_FALSE(quickHull(same, kTolerance));
  std::vector<Vec3> line, flat;
  for (int i = 0; i < 10; ++i) {
    line.emplace_back(i, 2 * i, 3 * i);
    flat.emplace_back(i % 3, i / 3, 0.0);
  }
  EXPECT_FALSE(quickHull(line, kTolerance));
  EXPECT_FALSE(quickHull(flat, kTolerance));
  // Flat up to the tolerance is flat too.
  flat.emplace_back(0.5, 0.5, 0.1 * kTolerance);
  EXPECT_FALSE(quickHull(flat, kTolerance));
  flat.back().z() = 1e-3;
  EXPECT_TRUE(quickHull(flat, kTolerance));
}

}  // namespace
}  // namespace kaboum::geometry
