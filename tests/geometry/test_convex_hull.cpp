#include <gtest/gtest.h>

#include <random>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::testing;

namespace {

TEST(ConvexHull, CubeCornersAmongInteriorPointsGiveSixFacesAndVolumeEight) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> inside(-0.9, 0.9);
  for (int i = 0; i < 200; ++i) points.emplace_back(inside(rng), inside(rng), inside(rng));

  const ConvexHull hull = convexHull(points);
  EXPECT_EQ(hull.mesh.vertexCount(), 8u);
  EXPECT_EQ(hull.planes.size(), 6u);  // coplanar triangles merged into one facet each
  const MeshAnalysis analysis = analyzeMesh(hull.mesh);
  EXPECT_TRUE(analysis.closed);
  EXPECT_TRUE(analysis.outwardOriented);
  EXPECT_NEAR(analysis.volume, 8.0, 1e-12);
  for (std::size_t v = 0; v < hull.mesh.vertexCount(); ++v) {
    EXPECT_EQ(hull.mesh.vertices[v], points[hull.inputIndex[v]]);
    EXPECT_LT(hull.inputIndex[v], 8u);
  }
}

TEST(ConvexHull, EveryInputPointSatisfiesEveryFacetPlane) {
  const TriangleMesh torus = makeTorus(1.0, 0.3, 24, 12);
  const ConvexHull hull = convexHull(torus.vertices, "torus");
  ASSERT_FALSE(hull.planes.empty());
  for (const HullPlane& plane : hull.planes) {
    EXPECT_NEAR(plane.normal.norm(), 1.0, 1e-12);
    for (const Vec3& p : torus.vertices) EXPECT_LE(plane.normal.dot(p), plane.offset + 1e-12);
  }
  const MeshAnalysis analysis = analyzeMesh(hull.mesh);
  EXPECT_TRUE(analysis.closed && analysis.edgeManifold && analysis.outwardOriented);
  EXPECT_EQ(analysis.degenerateTriangles, 0u);
}

TEST(ConvexHull, DegenerateInputIsAnInputErrorNamingThePoints) {
  const std::vector<Vec3> three{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW(convexHull(three, "piece 3"), InputError);
  const std::vector<Vec3> flat{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0),
                               Vec3(0.5, 0.2, 0)};
  try {
    convexHull(flat, "piece 3");
    FAIL() << "coplanar points gave a hull";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("piece 3"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("coplanar"), std::string::npos) << error.what();
  }
  std::vector<Vec3> notFinite = makeIcosphere(0).vertices;
  notFinite[2].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(convexHull(notFinite), InputError);
}

}  // namespace
}  // namespace kaboum::geometry
