// Property tests of the polish pass on real meshes: the side is kept (containment / inclusion), the
// mesh stays closed, manifold, oriented and free of new self-intersections, borders stay fixed,
// neither Hausdorff maximum rises, and the cow's outer 10% bound falls below the reference's.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/bounding_polish.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

namespace fs = std::filesystem;

TriangleMesh loadOriented(const fs::path& path) {
  TriangleMesh mesh = readMesh(path.string());
  bool changed = false;
  EXPECT_TRUE(orientOutward(mesh, changed)) << path;
  return mesh;
}

// Fewer samples and sweeps than the default: the guarantees are the same, the tests faster.
PolishOptions quickPolish(BoundSide side) {
  PolishOptions options;
  options.side = side;
  options.samples = 5000;
  options.maxSweeps = 2;
  options.sumSweeps = 1;
  options.relocations = 2;
  return options;
}

TriangleMesh boundAt(const TriangleMesh& mesh, BoundSide side, double ratio) {
  BoundingMeshOptions options;
  options.side = side;
  options.targetVertices =
      static_cast<std::size_t>(ratio * static_cast<double>(mesh.vertices.size()));
  return simplifyBounding(mesh, options).mesh;
}

const fs::path kRobots = kaboum::testing::dartUrdfDir();

TEST(BoundingPolish, KeepsTheSideAndTheShapeAndRaisesNeitherMaximum) {
  std::size_t relocations = 0;
  const std::vector<fs::path> meshes = {
      fs::path(kaboum::testing::dataFile("meshes/spot.obj")), kRobots / "KR5/meshes/forearm.STL",
      kRobots / "KR5/meshes/palm.STL", kRobots / "wam/meshes/wam/wam_base.STL"};
  for (const fs::path& path : meshes) {
    const TriangleMesh mesh = loadOriented(path);
    ASSERT_TRUE(analyzeMesh(mesh).closed) << path;
    for (const BoundSide side : {BoundSide::Outer, BoundSide::Inner}) {
      const std::string what =
          path.filename().string() + (side == BoundSide::Outer ? " outer" : " inner");
      const TriangleMesh before = boundAt(mesh, side, 0.1);
      TriangleMesh after = before;
      const PolishStats stats = polishBoundingMesh(mesh, after, quickPolish(side));
      relocations += stats.relocations;
      EXPECT_GT(stats.moves, 0u) << what;
      EXPECT_EQ(after.vertices.size(), before.vertices.size()) << what;
      EXPECT_EQ(after.triangles.size(), before.triangles.size()) << what;
      const MeshAnalysis a = analyzeMesh(after);
      EXPECT_TRUE(a.closed && a.edgeManifold && a.consistentlyOriented) << what;
      EXPECT_EQ(a.degenerateTriangles, 0u) << what;
      EXPECT_LE(countSelfIntersections(after), countSelfIntersections(before)) << what;
      const ContainmentReport check = verifyContainment(mesh, after, side, 20000, 11);
      EXPECT_TRUE(check.defined) << what;
      EXPECT_EQ(check.violations, 0u) << what << " worst " << check.worstViolation;
      // Measured on other samples than the pass scored on: allow 1% of the maximum.
      const HausdorffReport h0 = measureHausdorff(mesh, before, 20000, 2);
      const HausdorffReport h1 = measureHausdorff(mesh, after, 20000, 2);
      EXPECT_LE(h1.originalToResult.max, 1.01 * h0.originalToResult.max) << what;
      EXPECT_LE(h1.resultToOriginal.max, 1.01 * h0.resultToOriginal.max) << what;
      EXPECT_LT(h1.originalToResult.mean + h1.resultToOriginal.mean,
                h0.originalToResult.mean + h0.resultToOriginal.mean)
          << what;
    }
  }
  EXPECT_GT(relocations, 0u);  // the relocations were tried and kept somewhere
}

// The reference implementation's figures, outer 10% of the cow: 1.74% / 2.29% of the diagonal
// (original→result / result→original). Algorithm 2 alone gives 2.13% / 3.43%, the sweeps 1.748%
// / 1.979%, the relocations 1.363% / 1.928%.
TEST(BoundingPolish, BringsTheCowsOuterTenPercentBoundBelowTheReference) {
  const TriangleMesh mesh = loadOriented(fs::path(kaboum::testing::dataFile("meshes/cow.obj")));
  BoundingMeshOptions options;
  options.targetVertices = 291;
  options.polish = true;
  const BoundingMeshResult result = simplifyBounding(mesh, options);
  EXPECT_GT(result.stats.polishMoves, 0u);
  EXPECT_GT(result.stats.polishRelocations, 0u);
  EXPECT_EQ(result.mesh.vertices.size(), 291u);
  const HausdorffReport h = measureHausdorff(mesh, result.mesh, 200000, 1);
  EXPECT_LE(h.originalToResult.max, 0.0174 * h.diagonal);
  EXPECT_LE(h.resultToOriginal.max, 0.0229 * h.diagonal);
  EXPECT_EQ(verifyContainment(mesh, result.mesh, BoundSide::Outer, 50000, 4).violations, 0u);
}

TEST(BoundingPolish, OpenMeshBordersStayWhereTheyAre) {
  const TriangleMesh mesh = loadOriented(kRobots / "wam/meshes/wam/wam5.STL");
  ASSERT_FALSE(analyzeMesh(mesh).closed);
  const TriangleMesh before = boundAt(mesh, BoundSide::Outer, 0.1);
  TriangleMesh after = before;
  const PolishStats stats = polishBoundingMesh(mesh, after, quickPolish(BoundSide::Outer));
  EXPECT_GT(stats.moves, 0u);
  // Border vertices: ends of directed edges without a reverse.
  std::set<std::pair<std::uint32_t, std::uint32_t>> directed;
  for (const Triangle& t : before.triangles) {
    for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
  }
  std::size_t borderVertices = 0;
  for (const auto& [a, b] : directed) {
    if (directed.count({b, a}) == 0) {
      ++borderVertices;
      EXPECT_EQ(after.vertices[a], before.vertices[a]);
      EXPECT_EQ(after.vertices[b], before.vertices[b]);
    }
  }
  EXPECT_GT(borderVertices, 0u);
  const MeshAnalysis a = analyzeMesh(after), b = analyzeMesh(before);
  EXPECT_EQ(a.edgeManifold, b.edgeManifold);
  EXPECT_EQ(a.consistentlyOriented, b.consistentlyOriented);
  EXPECT_EQ(a.borderLoops, b.borderLoops);
  EXPECT_EQ(a.borderEdges, b.borderEdges);
  EXPECT_EQ(a.degenerateTriangles, 0u);
}

TEST(BoundingPolish, IsDeterministic) {
  const TriangleMesh mesh =
      loadOriented(fs::path(kaboum::testing::dataFile("meshes/kr5-wrist.stl")));
  const TriangleMesh before = boundAt(mesh, BoundSide::Outer, 0.1);
  TriangleMesh first = before, second = before;
  polishBoundingMesh(mesh, first, quickPolish(BoundSide::Outer));
  polishBoundingMesh(mesh, second, quickPolish(BoundSide::Outer));
  EXPECT_EQ(first.vertices, second.vertices);
  EXPECT_EQ(first.triangles, second.triangles);
}

}  // namespace
}  // namespace kaboum::geometry
