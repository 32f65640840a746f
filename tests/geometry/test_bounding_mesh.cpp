// Property tests of the bounding mesh algorithm on real meshes: containment (outer) and inclusion
// (inner), manifold non-degenerate results, fixed borders on open meshes, and the defects measured
// in the reference implementation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/geometry/separation_certificate.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/geometry/triangle_grid.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

namespace fs = std::filesystem;

const fs::path kRobots = kaboum::testing::dartUrdfDir();

// Closed shared meshes shipped in data/meshes, and every KR5/WAM link from dart-doc.
std::vector<fs::path> realMeshes() {
  std::vector<fs::path> paths = {fs::path(kaboum::testing::dataFile("meshes/cow.obj")),
                                 fs::path(kaboum::testing::dataFile("meshes/spot.obj")),
                                 fs::path(kaboum::testing::dataFile("meshes/fandisk.obj")),
                                 fs::path(kaboum::testing::dataFile("meshes/rocker-arm.obj"))};
  for (const fs::path& dir : {kRobots / "KR5/meshes", kRobots / "wam/meshes/wam"}) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (entry.path().extension() == ".STL" && name.find("collision") == std::string::npos) {
        paths.push_back(entry.path());
      }
    }
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

TriangleMesh loadOriented(const fs::path& path) {
  TriangleMesh mesh = readMesh(path.string());
  bool changed = false;
  EXPECT_TRUE(orientOutward(mesh, changed)) << path;
  return mesh;
}

// The result keeps what the input has: edge-manifoldness, orientation, no degenerate faces, no
// isolated vertices, and no more self-intersecting triangle pairs than the input.
void expectWellFormed(const TriangleMesh& input, const TriangleMesh& result,
                      const std::string& what) {
  const MeshAnalysis a = analyzeMesh(result);
  EXPECT_GT(result.triangles.size(), 0u) << what;
  if (analyzeMesh(input).edgeManifold) {
    EXPECT_TRUE(a.edgeManifold) << what;
  }
  EXPECT_LE(countSelfIntersections(result), countSelfIntersections(input)) << what;
  EXPECT_TRUE(a.consistentlyOriented) << what;
  EXPECT_EQ(a.degenerateTriangles, 0u) << what;
  // No isolated vertices: every output vertex is used by a triangle.
  std::vector<bool> used(result.vertices.size(), false);
  for (const Triangle& t : result.triangles) {
    for (std::uint32_t v : t) used[v] = true;
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; })) << what;
}

TEST(BoundingMesh, ClosedRealMeshesAreBoundedOnBothSidesAtSeveralTargets) {
  int closedCount = 0;
  for (const fs::path& path : realMeshes()) {
    const TriangleMesh mesh = loadOriented(path);
    const MeshAnalysis input = analyzeMesh(mesh);
    if (!input.closed || !input.edgeManifold) continue;
    ++closedCount;
    for (const BoundSide side : {BoundSide::Outer, BoundSide::Inner}) {
      for (const double ratio : {0.5, 0.1}) {
        BoundingMeshOptions options;
        options.side = side;
        options.targetVertices =
            static_cast<std::size_t>(ratio * static_cast<double>(mesh.vertices.size()));
        const BoundingMeshResult result = simplifyBounding(mesh, options);
        const std::string what = path.filename().string() +
                                 (side == BoundSide::Outer ? " outer " : " inner ") +
                                 std::to_string(ratio);
        expectWellFormed(mesh, result.mesh, what);
        const MeshAnalysis out = analyzeMesh(result.mesh);
        EXPECT_TRUE(out.closed) << what;
        EXPECT_EQ(out.components, input.components) << what;
        EXPECT_LT(result.mesh.vertices.size(), mesh.vertices.size()) << what;
        // Inner never silently produces an outer mesh, nor the reverse.
        if (side == BoundSide::Outer) {
          EXPECT_GE(out.volume, input.volume) << what;
        } else {
          EXPECT_LE(out.volume, input.volume) << what;
        }
        const ContainmentReport check = verifyContainment(mesh, result.mesh, side, 20000, 3);
        EXPECT_TRUE(check.defined) << what;
        EXPECT_EQ(check.violations, 0u) << what << " worst " << check.worstViolation;
      }
    }
  }
  EXPECT_GE(closedCount, 4);  // at least the four closed shared meshes
}

TEST(BoundingMesh, ReachesTheVertexTargetOnSmoothClosedMeshes) {
  const TriangleMesh mesh = loadOriented(fs::path(kaboum::testing::dataFile("meshes/spot.obj")));
  BoundingMeshOptions options;
  options.targetVertices = 293;
  const BoundingMeshResult result = simplifyBounding(mesh, options);
  EXPECT_EQ(result.mesh.vertices.size(), 293u);
  EXPECT_EQ(result.stats.stopReason, "vertex target reached");
  EXPECT_EQ(result.stats.contractions, mesh.vertices.size() - 293);
}

TEST(BoundingMesh, OpenMeshesKeepTheirBordersAndContainmentIsReportedUndefined) {
  int openCount = 0;
  for (const fs::path& path : realMeshes()) {
    const TriangleMesh mesh = loadOriented(path);
    const MeshAnalysis input = analyzeMesh(mesh);
    if (input.closed) continue;
    ++openCount;
    // Border edges of the input, as coordinate pairs.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse;
    for (const Triangle& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        edgeUse[std::minmax(t[k], t[(k + 1) % 3])]++;
      }
    }
    BoundingMeshOptions options;
    options.targetVertices = mesh.vertices.size() / 4;
    const BoundingMeshResult result = simplifyBounding(mesh, options);
    expectWellFormed(mesh, result.mesh, path.filename().string());
    std::set<std::array<double, 6>> resultEdges;
    for (const Triangle& t : result.mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = result.mesh.vertices[t[k]];
        const Vec3& q = result.mesh.vertices[t[(k + 1) % 3]];
        resultEdges.insert({p.x(), p.y(), p.z(), q.x(), q.y(), q.z()});
        resultEdges.insert({q.x(), q.y(), q.z(), p.x(), p.y(), p.z()});
      }
    }
    for (const auto& [edge, uses] : edgeUse) {
      if (uses != 1) continue;
      const Vec3& p = mesh.vertices[edge.first];
      const Vec3& q = mesh.vertices[edge.second];
      EXPECT_TRUE(resultEdges.count({p.x(), p.y(), p.z(), q.x(), q.y(), q.z()}))
          << path.filename() << ": border edge lost";
    }
    const ContainmentReport check = verifyContainment(mesh, result.mesh, BoundSide::Outer, 1000, 1);
    EXPECT_FALSE(check.defined) << path.filename();
    EXPECT_NE(check.note.find("closed"), std::string::npos) << check.note;
  }
  EXPECT_GE(openCount, 1);
}

TEST(BoundingMesh, QuadricErrorLimitIsADistanceAndIsRespected) {
  const TriangleMesh mesh =
      loadOriented(fs::path(kaboum::testing::dataFile("meshes/rocker-arm.obj")));
  BoundingMeshOptions options;
  options.maxError = 0.01 * analyzeMesh(mesh).diagonal;
  const BoundingMeshResult result = simplifyBounding(mesh, options);
  EXPECT_LE(result.stats.quadricError, options.maxError);
  EXPECT_GT(result.stats.quadricError, 0.5 * options.maxError);
  EXPECT_EQ(result.stats.stopReason, "no contraction left within the error limit");
}

TEST(BoundingMesh, DistanceLimitHoldsAndShrinksLargeMeshesTenfold) {
  const TriangleMesh mesh =
      loadOriented(fs::path(kaboum::testing::dataFile("meshes/rocker-arm.obj")));
  const double epsilon = 0.01 * analyzeMesh(mesh).diagonal;
  HausdorffReport measured;
  const BoundingMeshResult result =
      simplifyBoundingWithin(mesh, BoundingMeshOptions{}, epsilon, 20000, measured);
  EXPECT_LE(std::max(measured.originalToResult.max, measured.resultToOriginal.max), epsilon);
  // An independent, denser measurement agrees (sampling may miss a little of the true maximum).
  const HausdorffReport check = measureHausdorff(mesh, result.mesh, 200000, 99);
  EXPECT_LE(std::max(check.originalToResult.max, check.resultToOriginal.max), 1.05 * epsilon);
  // At 1% of the diagonal a closed input above 10^4 vertices shrinks at least 10×.
  EXPECT_LE(result.mesh.vertices.size() * 10, mesh.vertices.size());
  const ContainmentReport contained =
      verifyContainment(mesh, result.mesh, BoundSide::Outer, 20000, 5);
  EXPECT_EQ(contained.violations, 0u);
}

TEST(BoundingMesh, InnerDistanceSearchStaysInsideAndWithinTheLimit) {
  // Each run of the search goes on from the last one that fitted: the result must still be a
  // valid inner bound, within the limit, and simpler than the input.
  const TriangleMesh mesh = loadOriented(fs::path(kaboum::testing::dataFile("meshes/spot.obj")));
  const double epsilon = 0.01 * analyzeMesh(mesh).diagonal;
  BoundingMeshOptions options;
  options.side = BoundSide::Inner;
  HausdorffReport measured;
  const BoundingMeshResult result = simplifyBoundingWithin(mesh, options, epsilon, 20000, measured);
  EXPECT_GE(result.stats.runs, 3);
  EXPECT_LE(std::max(measured.originalToResult.max, measured.resultToOriginal.max), epsilon);
  // The quadric error overestimates the distance, so the search gets further than one run at ε/2.
  options.maxError = 0.5 * epsilon;
  EXPECT_LT(result.mesh.vertices.size(), simplifyBounding(mesh, options).mesh.vertices.size());
  const MeshAnalysis report = analyzeMesh(result.mesh);
  EXPECT_TRUE(report.closed && report.edgeManifold && report.consistentlyOriented);
  EXPECT_EQ(verifyContainment(mesh, result.mesh, BoundSide::Inner, 20000, 5).violations, 0u);
  EXPECT_EQ(countSelfIntersections(result.mesh), 0u);
}

TEST(BoundingMesh, AtTenPercentTheDistanceStaysBelowOnePercentOfTheDiagonal) {
  const TriangleMesh mesh =
      loadOriented(fs::path(kaboum::testing::dataFile("meshes/rocker-arm.obj")));
  BoundingMeshOptions options;
  options.targetVertices = mesh.vertices.size() / 10;
  const BoundingMeshResult result = simplifyBounding(mesh, options);
  const HausdorffReport h = measureHausdorff(mesh, result.mesh, 50000, 2);
  EXPECT_LE(h.originalToResult.max, 0.01 * h.diagonal);
  EXPECT_LE(h.resultToOriginal.max, 0.01 * h.diagonal);
}

TEST(BoundingMesh, AllQuadricMergesAndCostsKeepTheGuarantee) {
  const TriangleMesh mesh = loadOriented(fs::path(kaboum::testing::dataFile("meshes/cow.obj")));
  for (const ContractionCost cost : {ContractionCost::Planes, ContractionCost::Triangles}) {
    for (const QuadricMerge merge :
         {QuadricMerge::Sum, QuadricMerge::Constant, QuadricMerge::Full}) {
      BoundingMeshOptions options;
      options.cost = cost;
      options.merge = merge;
      options.targetVertices = mesh.vertices.size() / 5;
      const BoundingMeshResult result = simplifyBounding(mesh, options);
      expectWellFormed(mesh, result.mesh, "cow");
      const ContainmentReport check =
          verifyContainment(mesh, result.mesh, BoundSide::Outer, 5000, 4);
      EXPECT_EQ(check.violations, 0u);
    }
  }
}

TEST(BoundingMesh, IsDeterministic) {
  const TriangleMesh mesh = loadOriented(fs::path(kaboum::testing::dataFile("meshes/fandisk.obj")));
  BoundingMeshOptions options;
  options.targetVertices = 500;
  const BoundingMeshResult a = simplifyBounding(mesh, options);
  const BoundingMeshResult b = simplifyBounding(mesh, options);
  ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  for (std::size_t i = 0; i < a.mesh.vertices.size(); ++i) {
    EXPECT_EQ(a.mesh.vertices[i], b.mesh.vertices[i]);
  }
}

// The lazy queue solves an edge only when it reaches the top, yet must contract exactly the edges
// the eager queue (every queued edge solved at once) contracts, in the same order: same output
// bits, same counts, on both sides, with a vertex target, with an error limit, and with each merge.
TEST(BoundingMesh, LazyQueueGivesTheEagerQueuesResultBitForBit) {
  struct Case {
    const char* mesh;
    BoundSide side;
    double ratio, maxErrorOfDiagonal;
    QuadricMerge merge;
  };
  const double noLimit = std::numeric_limits<double>::infinity();
  for (const Case& k :
       {Case{"spot.obj", BoundSide::Outer, 0.1, noLimit, QuadricMerge::Constant},
        Case{"spot.obj", BoundSide::Inner, 0.1, noLimit, QuadricMerge::Constant},
        Case{"cow.obj", BoundSide::Outer, 0.05, noLimit, QuadricMerge::Full},
        Case{"cow.obj", BoundSide::Inner, 0.2, noLimit, QuadricMerge::Sum},
        Case{"fandisk.obj", BoundSide::Outer, 0.0, 0.01, QuadricMerge::Constant},
        Case{"kr5-wrist.stl", BoundSide::Inner, 0.0, 0.02, QuadricMerge::Constant}}) {
    const TriangleMesh mesh = loadOriented(fs::path(kaboum::testing::dataFile("meshes")) / k.mesh);
    BoundingMeshOptions options;
    options.side = k.side;
    options.merge = k.merge;
    options.targetVertices =
        static_cast<std::size_t>(k.ratio * static_cast<double>(mesh.vertices.size()));
    options.maxError = k.maxErrorOfDiagonal * analyzeMesh(mesh).diagonal;
    const BoundingMeshResult lazy = simplifyBounding(mesh, options);
    options.lazyQueue = false;
    const BoundingMeshResult eager = simplifyBounding(mesh, options);
    const std::string what =
        std::string(k.mesh) + (k.side == BoundSide::Outer ? " outer" : " inner");
    EXPECT_GT(lazy.stats.contractions, mesh.vertices.size() / 4) << what;
    EXPECT_EQ(lazy.stats.contractions, eager.stats.contractions) << what;
    EXPECT_EQ(lazy.stats.rejectedTopology, eager.stats.rejectedTopology) << what;
    EXPECT_EQ(lazy.stats.rejectedGeometry, eager.stats.rejectedGeometry) << what;
    EXPECT_EQ(lazy.stats.rejectedCrossing, eager.stats.rejectedCrossing) << what;
    EXPECT_EQ(lazy.stats.quadricError, eager.stats.quadricError) << what;
    EXPECT_EQ(lazy.mesh.triangles, eager.mesh.triangles) << what;
    EXPECT_EQ(lazy.mesh.vertices, eager.mesh.vertices) << what;
  }
}

// The high-valence case: contractions next to vertices of valence 600–2,000 (the double
// cone's apexes, the fan centres of a cylinder's caps) go through the angular index of their stars
// and keep every guarantee.
TEST(BoundingMesh, HighValenceStarsKeepEveryGuarantee) {
  const std::pair<TriangleMesh, std::string> inputs[] = {{makeDoubleCone(2000), "double cone"},
                                                         {makeFannedCylinder(600, 3), "cylinder"}};
  for (const auto& [mesh, name] : inputs) {
    for (const BoundSide side : {BoundSide::Outer, BoundSide::Inner}) {
      BoundingMeshOptions options;
      options.side = side;
      options.targetVertices = mesh.vertices.size() / 5;
      const BoundingMeshResult result = simplifyBounding(mesh, options);
      const std::string what = name + (side == BoundSide::Outer ? " outer" : " inner");
      EXPECT_GT(result.stats.contractions, mesh.vertices.size() / 2) << what;
      expectWellFormed(mesh, result.mesh, what);
      EXPECT_EQ(countSelfIntersections(result.mesh), 0u) << what;
      const ContainmentReport check = verifyContainment(mesh, result.mesh, side, 20000, 5);
      EXPECT_TRUE(check.defined) << what;
      EXPECT_EQ(check.violations, 0u) << what << " worst " << check.worstViolation;
    }
  }
}

TEST(BoundingMesh, InconsistentOrientationIsAnInputError) {
  TriangleMesh mesh = makeIcosphere(1);
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
  EXPECT_THROW(simplifyBounding(mesh, BoundingMeshOptions{}), InputError);
}

TEST(BoundingMesh, KnifeEdgesAreNeverContractedThroughThemselves) {
  // A thin closed sliver (two triangles back to back, slightly apart): no feasible outer point
  // exists for edges across it, so it must stay a valid closed mesh containing the input.
  const TriangleMesh slab = makeBox(Vec3(0, 0, 0), Vec3(1.0, 1.0, 1e-4), 4);
  BoundingMeshOptions options;
  options.targetVertices = 4;
  const BoundingMeshResult result = simplifyBounding(slab, options);
  expectWellFormed(slab, result.mesh, "slab");
  const ContainmentReport check = verifyContainment(slab, result.mesh, BoundSide::Outer, 2000, 1);
  EXPECT_EQ(check.violations, 0u);
}

// The guard clears a pair with certainlyApart only where the exact predicate would answer "apart":
// pairs sharing a vertex or nothing, with the far corners at heights from 1e-9 to 1e-2 of the size
// above or below the other's plane, straddling the certificate's margins.
TEST(SeparationCertificate, NeverClearsAPairThePredicateFindsMeeting) {
  std::mt19937_64 engine(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto inPlane = [&](const Vec3& around, const Vec3& u, const Vec3& w, double scale) {
    return Vec3(around + scale * (unit(engine) * u + unit(engine) * w));
  };
  const auto planed = [](const std::array<Vec3, 3>& c, const Triangle& ids) {
    const Vec3 cross = (c[1] - c[0]).cross(c[2] - c[0]);
    const double longest = std::max(
        {(c[1] - c[0]).squaredNorm(), (c[2] - c[1]).squaredNorm(), (c[0] - c[2]).squaredNorm()});
    return PlanedTriangle{{&c[0], &c[1], &c[2]}, ids, cross.normalized(), cross.norm(), longest};
  };
  std::size_t cleared = 0, meeting = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const double scale = std::pow(10.0, 2.0 * unit(engine));
    const Vec3 origin =
        Vec3(5.0, -3.0, 8.0) + 10.0 * Vec3(unit(engine), unit(engine), unit(engine));
    const std::array<Vec3, 3> t{origin, origin + scale * Vec3(1.0, 0.1 * unit(engine), 0.0),
                                origin + scale * Vec3(0.2 * unit(engine), 1.0, 0.1 * unit(engine))};
    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    const Vec3 u = (t[1] - t[0]).normalized(), w = n.cross(u);
    const double side = unit(engine) < 0.6 ? 1.0 : -1.0;
    const auto height = [&] {
      const double sign = unit(engine) < 0.4 ? side : -side;
      return sign * scale * std::pow(10.0, -2.0 - 7.0 * 0.5 * (unit(engine) + 1.0));
    };
    const int kind = trial % 3;  // 0: shared vertex, 1: disjoint, 2: shared edge
    const Triangle tIds{0, 1, 2};
    Triangle uIds{3, 4, 5};
    std::array<Vec3, 3> other;
    if (kind == 0) {
      uIds = {0, 4, 5};
      other = {t[0], inPlane(t[0], u, w, scale) + height() * n,
               inPlane(t[0], u, w, scale) + height() * n};
    } else if (kind == 1) {
      for (Vec3& p : other) p = inPlane(t[0], u, w, scale) + height() * n;
    } else {
      uIds = {1, 0, 5};
      other = {t[1], t[0], inPlane(t[0], u, w, scale) + height() * n};
    }
    const bool meet = meshTrianglesIntersect(t, tIds, other, uIds);
    const bool apart = certainlyApart(planed(t, tIds), planed(other, uIds));
    ASSERT_FALSE(apart && meet) << "trial " << trial;
    if (kind == 2) {
      ASSERT_TRUE(apart && !meet) << "trial " << trial;  // shared edges never meet
    }
    cleared += apart && kind != 2 ? 1 : 0;
    meeting += meet ? 1 : 0;
  }
  std::printf("cleared %zu meeting %zu\n", cleared, meeting);
  EXPECT_GT(cleared, 1000u);  // it clears many separated pairs that share no edge
  EXPECT_GT(meeting, 3000u);  // and is tested against many pairs that do meet
}

// The guard's single-precision boxes must contain their triangles exactly (else a crossing pair
// could be skipped): corners at every scale from 1e-30 to 1e30, of both signs, and zero.
TEST(SeparationCertificate, TriangleBoxesContainTheirCornersAtEveryScale) {
  std::mt19937_64 engine(32);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 20000; ++trial) {
    std::array<Vec3, 3> corners;
    for (Vec3& p : corners) {
      for (int k = 0; k < 3; ++k)
        p[k] = trial % 7 == 0 ? 0.0 : unit(engine) * std::pow(10.0, 30.0 * unit(engine));
    }
    const Box3 box = triangleBox(corners[0], corners[1], corners[2]);
    for (const Vec3& p : corners) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_LE(static_cast<double>(box.lo[k]), p[k]) << "trial " << trial;
        ASSERT_GE(static_cast<double>(box.hi[k]), p[k]) << "trial " << trial;
      }
    }
    const double longest =
        std::max({(corners[1] - corners[0]).squaredNorm(), (corners[2] - corners[1]).squaredNorm(),
                  (corners[0] - corners[2]).squaredNorm()});
    ASSERT_GE(box.diagonalSquared(), longest) << "trial " << trial;
  }
}

}  // namespace
}  // namespace kaboum::geometry
