// Bounding convex decomposition (§4.4.2): the union of the pieces contains the input surface and
// solid on dense samples, every piece is convex, ε and the piece limit hold, results repeat; on
// procedural shapes and the real robot links and tools in data/ (closed and open).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/convex_decomposition.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

TriangleMesh dataMesh(const std::string& name) {
  return readMesh(kaboum::testing::dataFile("meshes/" + name));
}

// Containment tolerance: pieces may lose points by a rounding-level snap (convex_decomposition).
double tolerance(const TriangleMesh& mesh) {
  return 1e-7 * boundingBoxDiagonal(mesh);
}

bool inAnyPiece(const std::vector<ConvexPiece>& pieces, const Vec3& p, double tol) {
  return std::any_of(pieces.begin(), pieces.end(),
                     [&](const ConvexPiece& piece) { return piece.contains(p, tol); });
}

// Surface samples of `surface` (every vertex, edge midpoint and 20000 random points) outside every
// piece.
std::size_t uncoveredSurfaceSamples(const TriangleMesh& surface,
                                    const std::vector<ConvexPiece>& pieces) {
  std::size_t uncovered = 0;
  for (const Vec3& p : sampleSurface(surface, 20000, 7)) {
    if (!inAnyPiece(pieces, p, tolerance(surface))) ++uncovered;
  }
  return uncovered;
}

// Random points inside the closed mesh's solid that are outside every piece; `inside` receives
// how many inside points were tried.
std::size_t uncoveredSolidSamples(const TriangleMesh& closed,
                                  const std::vector<ConvexPiece>& pieces, std::size_t& inside) {
  const TriangleBvh bvh(closed);
  const MeshAnalysis analysis = analyzeMesh(closed);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t uncovered = 0;
  inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 t(unit(rng), unit(rng), unit(rng));
    const Vec3 p = analysis.boxMin + t.cwiseProduct(analysis.boxMax - analysis.boxMin);
    if (!bvh.contains(p)) continue;
    ++inside;
    if (!inAnyPiece(pieces, p, tolerance(closed))) ++uncovered;
  }
  return uncovered;
}

// Every piece is convex and has only hull vertices: qhull finds all of them again, and every
// vertex is on the inner side of every facet plane.
void expectConvexPieces(const Decomposition& result) {
  const double tol = 1e-9 * result.stats.diagonal;
  for (std::size_t i = 0; i < result.pieces.size(); ++i) {
    SCOPED_TRACE("piece " + std::to_string(i));
    const ConvexPiece& piece = result.pieces[i];
    const ConvexHull hull = convexHull(piece.vertices());
    EXPECT_EQ(hull.mesh.vertexCount(), piece.vertices().size());
    ASSERT_FALSE(piece.planes.empty());
    for (const HullPlane& plane : piece.planes) {
      for (const Vec3& v : piece.vertices()) EXPECT_LE(plane.normal.dot(v), plane.offset + tol);
    }
    const MeshAnalysis analysis = analyzeMesh(piece.mesh);
    EXPECT_TRUE(analysis.closed && analysis.outwardOriented);
  }
}

// The checks every decomposition must pass, on `original` as given (open or closed).
void expectBoundingDecomposition(const TriangleMesh& original, const Decomposition& result,
                                 std::size_t maxPieces) {
  ASSERT_FALSE(result.pieces.empty());
  EXPECT_LE(result.pieces.size(), maxPieces);
  expectConvexPieces(result);
  EXPECT_EQ(uncoveredSurfaceSamples(original, result.pieces), 0u);
  EXPECT_EQ(uncoveredSurfaceSamples(result.closedInput, result.pieces), 0u);
  std::size_t inside = 0;
  EXPECT_EQ(uncoveredSolidSamples(result.closedInput, result.pieces, inside), 0u);
  EXPECT_GT(inside, 100u);
  std::size_t total = 0;
  for (const ConvexPiece& piece : result.pieces) total += piece.vertices().size();
  EXPECT_EQ(total, result.stats.totalVertices);
  EXPECT_LE(result.stats.totalVertices, result.stats.hullVertices);
}

TEST(ConvexDecomposition, ConcaveLPrismSplitsWithinEpsilonAndContainsIt) {
  const TriangleMesh prism = makeLPrism(1.0);
  DecompositionOptions options;
  options.epsilonPercent = 1.0;
  const Decomposition result = decomposeBounding(prism, options);
  expectBoundingDecomposition(prism, result, options.maxPieces);
  EXPECT_EQ(result.stats.stopReason, "within epsilon");
  EXPECT_GE(result.pieces.size(), 2u);  // one convex piece would be 0.7 away at the notch
  const DecompositionQuality quality = measureDecomposition(prism, result.pieces, 20000, 3);
  EXPECT_EQ(quality.uncovered, 0u);
  EXPECT_LE(quality.approximationToOriginal.max, result.stats.epsilon);
}

TEST(ConvexDecomposition, ConvexInputIsOnePieceWithFewerVerticesWithinEpsilon) {
  const TriangleMesh sphere = makeIcosphere(3);  // 642 vertices
  DecompositionOptions options;
  options.epsilonPercent = 2.0;
  const Decomposition result = decomposeBounding(sphere, options);
  expectBoundingDecomposition(sphere, result, 1);
  EXPECT_LT(result.pieces.front().vertices().size(), 321u);  // half the input
  const DecompositionQuality quality = measureDecomposition(sphere, result.pieces, 20000, 3);
  EXPECT_LE(quality.approximationToOriginal.max, result.stats.epsilon);
}

TEST(ConvexDecomposition, TorusSolidIsContainedAndItsHoleIsCarvedOut) {
  const TriangleMesh torus = makeTorus(1.0, 0.3, 32, 12);
  DecompositionOptions options;
  options.epsilonPercent = 5.0;
  options.maxPieces = 24;
  const Decomposition result = decomposeBounding(torus, options);
  expectBoundingDecomposition(torus, result, options.maxPieces);
  // The centre of the hole is 0.7 from the torus: no piece may cover it at 5% of the diagonal.
  EXPECT_FALSE(inAnyPiece(result.pieces, Vec3::Zero(), 0.0));
}

TEST(ConvexDecomposition, RealLinksAndToolsClosedAndOpenAreContained) {
  for (const std::string name :
       {"kr5-wrist.stl", "kr5-base-link.stl", "wam2.stl", "bimanual-assembly/tools/finger2.wrl"}) {
    SCOPED_TRACE(name);
    const TriangleMesh mesh = dataMesh(name);
    const DecompositionOptions options;
    const Decomposition result = decomposeBounding(mesh, options);
    expectBoundingDecomposition(mesh, result, options.maxPieces);
    const bool open = !analyzeMesh(mesh).closed;
    EXPECT_EQ(result.stats.holesFilled > 0, open);
    // Vertex counts drop well below the hulls' (Table 4.3: ~8-25 vertices per convex).
    EXPECT_LT(static_cast<double>(result.stats.totalVertices),
              0.8 * static_cast<double>(result.stats.hullVertices));
    const DecompositionQuality quality =
        measureDecomposition(result.closedInput, result.pieces, 20000, 5);
    EXPECT_EQ(quality.uncovered, 0u);
    EXPECT_LE(quality.approximationToOriginal.max, result.stats.estimatedError * 1.5 + 1e-12);
  }
}

// With a piece budget that allows it, a real link (KR5 base, with bores and pockets that need
// cuts through their axes) is decomposed within the requested ε, measured on the union's boundary.
TEST(ConvexDecomposition, RealLinkReachesTheRequestedEpsilonWhenThePieceBudgetAllows) {
  const TriangleMesh mesh = dataMesh("kr5-base-link.stl");
  DecompositionOptions options;
  options.epsilonPercent = 4.0;
  options.maxPieces = 30;
  const Decomposition result = decomposeBounding(mesh, options);
  expectBoundingDecomposition(mesh, result, options.maxPieces);
  EXPECT_EQ(result.stats.stopReason, "within epsilon");
  const DecompositionQuality quality =
      measureDecomposition(result.closedInput, result.pieces, 20000, 5);
  EXPECT_EQ(quality.uncovered, 0u);
  EXPECT_LE(quality.approximationToOriginal.max, result.stats.epsilon);
}

// At the defaults (3%, at most 11 pieces) the piece limit stops the splitting of the KR5 elbow
// before ε; it is still tighter than the reference decomposition's best figure on these links
// (3.7% of the diagonal, docs/benchmarks.md), which greedy merging alone missed (4.28%: the
// look-ahead over the last forced merges chooses other pairs), and the reported estimate does not
// understate it.
TEST(ConvexDecomposition, RealLinkAtTheDefaultsIsTighterThanTheReference) {
  const TriangleMesh mesh = dataMesh("kr5-elbow.stl");
  const Decomposition result = decomposeBounding(mesh, {});
  EXPECT_LE(result.pieces.size(), 11u);
  EXPECT_EQ(result.stats.stopReason, "piece limit reached");
  const DecompositionQuality quality =
      measureDecomposition(result.closedInput, result.pieces, 20000, 5);
  EXPECT_EQ(quality.uncovered, 0u);
  EXPECT_LT(quality.approximationToOriginal.max, 0.037 * quality.diagonal);
  EXPECT_LE(quality.approximationToOriginal.max, result.stats.estimatedError);
}

// After merging, re-cutting the worst piece (with a neighbour, or alone and merging another pair)
// keeps only moves that lower the largest concavity: on the KR5 wrist, where every merge order
// leaves a loose piece, some moves are kept, the estimate drops, and the pieces still contain the
// input.
TEST(ConvexDecomposition, ReCutsAfterMergingLowerTheWorstConcavityAndStillContain) {
  const TriangleMesh mesh = dataMesh("kr5-wrist.stl");
  DecompositionOptions merged;
  merged.refineRounds = 0;
  DecompositionOptions refined;
  refined.refineRounds = 10;
  const Decomposition before = decomposeBounding(mesh, merged);
  const Decomposition after = decomposeBounding(mesh, refined);
  EXPECT_EQ(before.stats.refinements, 0u);
  EXPECT_GT(after.stats.refinements, 0u);
  EXPECT_LE(after.stats.refinements, refined.refineRounds);
  EXPECT_EQ(after.pieces.size(), before.pieces.size());
  EXPECT_LT(after.stats.estimatedError, before.stats.estimatedError);
  expectBoundingDecomposition(mesh, after, DecompositionOptions{}.maxPieces);
  const DecompositionQuality quality =
      measureDecomposition(after.closedInput, after.pieces, 20000, 5);
  EXPECT_EQ(quality.uncovered, 0u);
  EXPECT_LE(quality.approximationToOriginal.max, after.stats.estimatedError);
}

TEST(ConvexDecomposition, PieceLimitIsRespected) {
  const TriangleMesh mesh = dataMesh("kr5-wrist.stl");
  for (const std::size_t limit : {1u, 3u}) {
    DecompositionOptions options;
    options.epsilonPercent = 0.5;  // unreachable with so few pieces
    options.maxPieces = limit;
    const Decomposition result = decomposeBounding(mesh, options);
    expectBoundingDecomposition(mesh, result, limit);
    EXPECT_EQ(result.stats.stopReason, "piece limit reached");
  }
}

TEST(ConvexDecomposition, SmallerEpsilonGivesATighterResult) {
  const TriangleMesh prism = makeLPrism(0.5);
  double previous = std::numeric_limits<double>::infinity();
  for (const double percent : {8.0, 2.0, 0.5}) {
    DecompositionOptions options;
    options.epsilonPercent = percent;
    options.maxPieces = 40;
    const Decomposition result = decomposeBounding(prism, options);
    const DecompositionQuality quality = measureDecomposition(prism, result.pieces, 20000, 3);
    EXPECT_LE(quality.approximationToOriginal.max, result.stats.epsilon) << percent;
    EXPECT_LE(quality.approximationToOriginal.max, previous + 1e-12) << percent;
    previous = quality.approximationToOriginal.max;
  }
}

TEST(ConvexDecomposition, IsDeterministic) {
  const TriangleMesh mesh = dataMesh("kr5-base-link.stl");
  const Decomposition a = decomposeBounding(mesh, {});
  const Decomposition b = decomposeBounding(mesh, {});
  ASSERT_EQ(a.pieces.size(), b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    EXPECT_EQ(a.pieces[i].mesh.vertices, b.pieces[i].mesh.vertices);
    EXPECT_EQ(a.pieces[i].mesh.triangles, b.pieces[i].mesh.triangles);
  }
}

TEST(ConvexDecomposition, EachMeshOfARobotOnTwoThreadsEqualsOneByOne) {
  const std::vector<TriangleMesh> links{dataMesh("kr5-wrist.stl"), makeLPrism(),
                                        dataMesh("wam2.stl")};
  const std::vector<Decomposition> together = decomposeBoundingEach(links, {}, 2);
  ASSERT_EQ(together.size(), links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Decomposition alone = decomposeBounding(links[i], {});
    ASSERT_EQ(together[i].pieces.size(), alone.pieces.size()) << i;
    for (std::size_t k = 0; k < alone.pieces.size(); ++k) {
      EXPECT_EQ(together[i].pieces[k].mesh.vertices, alone.pieces[k].mesh.vertices);
    }
  }
  std::vector<TriangleMesh> withBad = links;
  withBad[1] = TriangleMesh{};
  try {
    decomposeBoundingEach(withBad, {}, 2);
    FAIL() << "an empty mesh was decomposed";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("mesh 1"), std::string::npos) << error.what();
  }
}

TEST(ConvexDecomposition, MeasurementSeesPiecesThatDoNotContainTheInput) {
  const TriangleMesh prism = makeLPrism();
  Decomposition result = decomposeBounding(prism, {});
  // Shrink every piece towards its centroid: the surface is no longer covered.
  for (ConvexPiece& piece : result.pieces) {
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& v : piece.mesh.vertices) centroid += v;
    centroid /= static_cast<double>(piece.mesh.vertexCount());
    for (Vec3& v : piece.mesh.vertices) v = centroid + 0.9 * (v - centroid);
    for (HullPlane& plane : piece.planes) {
      plane.offset = plane.normal.dot(centroid) + 0.9 * (plane.offset - plane.normal.dot(centroid));
    }
  }
  const DecompositionQuality quality = measureDecomposition(prism, result.pieces, 5000, 3);
  EXPECT_GT(quality.uncovered, 0u);
  EXPECT_GT(quality.worstUncovered, 0.0);
}

// Bad input: one InputError each, never a crash.
TEST(ConvexDecomposition, BadInputIsAnInputError) {
  EXPECT_THROW(decomposeBounding(TriangleMesh{}, {}), InputError);

  TriangleMesh notFinite = makeIcosphere(1);
  notFinite.vertices[3].y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(decomposeBounding(notFinite, {}), InputError);

  TriangleMesh badIndex = makeIcosphere(1);
  badIndex.triangles[0][1] = 10000;
  EXPECT_THROW(decomposeBounding(badIndex, {}), InputError);

  // A flat square: its hole filling gives a closed surface without volume.
  TriangleMesh square;
  square.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  try {
    decomposeBounding(square, {});
    FAIL() << "a flat mesh was decomposed";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("volume"), std::string::npos) << error.what();
  }

  // A Möbius strip cannot be oriented.
  TriangleMesh moebius;
  const int segments = 12;
  for (int i = 0; i < segments; ++i) {
    const double u = 2.0 * M_PI * i / segments;
    for (const double s : {-0.3, 0.3}) {
      moebius.vertices.emplace_back((1 + s * std::cos(u / 2)) * std::cos(u),
                                    (1 + s * std::cos(u / 2)) * std::sin(u), s * std::sin(u / 2));
    }
  }
  for (std::uint32_t i = 0; i < segments; ++i) {
    const std::uint32_t a = 2 * i, b = 2 * i + 1;
    const bool last = i + 1 == segments;
    const std::uint32_t c = last ? 1 : 2 * i + 2, d = last ? 0 : 2 * i + 3;  // the half twist
    moebius.triangles.push_back({a, c, b});
    moebius.triangles.push_back({b, c, d});
  }
  EXPECT_THROW(decomposeBounding(moebius, {}), InputError);

  DecompositionOptions zeroPieces;
  zeroPieces.maxPieces = 0;
  EXPECT_THROW(decomposeBounding(makeLPrism(), zeroPieces), InputError);
  DecompositionOptions noEpsilon;
  noEpsilon.epsilonPercent = 0.0;
  EXPECT_THROW(decomposeBounding(makeLPrism(), noEpsilon), InputError);
  DecompositionOptions nanEpsilon;
  nanEpsilon.epsilon = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(decomposeBounding(makeLPrism(), nanEpsilon), InputError);
}

}  // namespace
}  // namespace kaboum::geometry
