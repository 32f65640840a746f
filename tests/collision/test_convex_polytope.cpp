// ConvexPolytope and TransformedSupport: the support mapping every narrow-phase query relies on.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/polytope_pairs.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

double maxDot(const std::vector<Vec3>& points, const Vec3& direction) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) best = std::max(best, direction.dot(p));
  return best;
}

Vec3 randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return {normal(rng), normal(rng), normal(rng)};
}

// Support by scanning or by climbing from any start vertex reaches the maximum over all points.
void expectExactSupport(const ConvexPolytope& polytope, const std::vector<Vec3>& points,
                        std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = randomDirection(rng);
    // Every other query cold, the others from a random vertex.
    ConvexPolytope::Hint hint;
    if (i % 2 == 1) hint.vertex = static_cast<std::uint32_t>(rng() % polytope.vertexCount());
    const Vec3 s = polytope.support(d, hint);
    ASSERT_NEAR(d.dot(s), maxDot(points, d), 1e-12 * (1 + d.norm()));
    EXPECT_EQ(polytope.vertices()[hint.vertex], s);
  }
}

TEST(ConvexPolytope, SupportIsTheMaximumOverAllPointsForEverySize) {
  for (const int n : {4, 8, 16, 32, 64, 65, 256}) {
    const auto pair = randomPolytopePairs(1, n, 100 + static_cast<std::uint64_t>(n)).front();
    const ConvexPolytope polytope(pair.localA);
    EXPECT_EQ(polytope.vertexCount(), static_cast<std::size_t>(n));
    expectExactSupport(polytope, pair.localA, static_cast<std::uint64_t>(n));
  }
}

TEST(ConvexPolytope, InteriorAndDuplicatedPointsAreDropped) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  points.insert(points.end(), points.begin(), points.end());  // every corner twice
  points.emplace_back(0.5, 0.5, 0.5);
  points.emplace_back(0.5, 0.5, 1.0);  // on a face
  const ConvexPolytope cube(points);
  EXPECT_EQ(cube.vertexCount(), 8U);
  EXPECT_TRUE(cube.center().isApprox(Vec3(0.5, 0.5, 0.5)));
  expectExactSupport(cube, points, 1);
}

TEST(ConvexPolytope, EdgeGraphIsSymmetricAndConnectsEveryVertex) {
  const auto pair = randomPolytopePairs(1, 40, 7).front();
  const ConvexPolytope polytope(pair.localA);
  for (std::uint32_t i = 0; i < polytope.vertexCount(); ++i) {
    const auto around = polytope.neighbors(i);
    EXPECT_GE(around.size(), 3U);
    for (const std::uint32_t j : around) {
      EXPECT_NE(i, j);
      const auto back = polytope.neighbors(j);
      EXPECT_NE(std::find(back.begin(), back.end(), i), back.end());
    }
  }
}

TEST(ConvexPolytope, BoundingBoxAndSphereContainEveryVertex) {
  const auto pair = randomPolytopePairs(1, 64, 3).front();
  const ConvexPolytope polytope(pair.localA);
  for (const Vec3& v : pair.localA) {
    EXPECT_TRUE(polytope.localBox().contains(v));
    EXPECT_LE((v - polytope.boundingSphereCenter()).norm(),
              polytope.boundingSphereRadius() + 1e-12);
  }
  EXPECT_LE(polytope.boundingSphereRadius(), 0.5 * polytope.localBox().diagonal().norm() + 1e-12);
}

// Farthest vertex from `c`.
double farthest(const std::vector<Vec3>& points, const Vec3& c) {
  double best = 0;
  for (const Vec3& p : points) best = std::max(best, (p - c).norm());
  return best;
}

// The pre-tests' spheres: the bounding sphere holds every vertex and is never looser than the
// one centred on the box; the inner ball stays behind every facet plane of an independently
// computed hull, on random shapes and real robot links.
TEST(ConvexPolytope, InnerBallIsInsideAndBoundingSphereHoldsEveryVertex) {
  std::vector<std::vector<Vec3>> shapes;
  for (const int n : {4, 8, 16, 64}) {
    for (const PolytopePair& pair : randomPolytopePairs(30, n, 17)) shapes.push_back(pair.localA);
  }
  for (const char* name : {"kr5-wrist.stl", "kr5-base-link.stl", "wam2.stl"}) {
    shapes.push_back(readMesh(kaboum::testing::dataFile(std::string("meshes/") + name)).vertices);
  }
  for (const auto& points : shapes) {
    const ConvexPolytope polytope(points);
    const double scale = polytope.localBox().diagonal().norm();
    EXPECT_LE(farthest(points, polytope.boundingSphereCenter()),
              polytope.boundingSphereRadius() + 1e-12 * scale);
    EXPECT_LE(polytope.boundingSphereRadius(),
              farthest(points, polytope.localBox().center()) + 1e-12 * scale);
    EXPECT_GT(polytope.innerSphereRadius(), 0.0);
    for (const HullPlane& plane : convexHull(points).planes) {
      EXPECT_LE(plane.normal.dot(polytope.innerSphereCenter()) + polytope.innerSphereRadius(),
                plane.offset + 1e-12 * scale);
    }
  }
}

// On shapes whose extreme spheres are known, the searched spheres come close to them.
TEST(ConvexPolytope, SpheresAreNearlyTheLargestInnerAndSmallestBoundingOnes) {
  // Tetrahedron: inradius 3 V / (total face area).
  const std::vector<Vec3> tetrahedron = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0),
                                         Vec3(0, 0, 0.5)};
  const ConvexPolytope tetra(tetrahedron);
  const Vec3 a = tetrahedron[1] - tetrahedron[0], b = tetrahedron[2] - tetrahedron[0],
             c = tetrahedron[3] - tetrahedron[0];
  const double volume = std::abs(a.dot(b.cross(c))) / 6;
  const double area =
      0.5 * (a.cross(b).norm() + b.cross(c).norm() + c.cross(a).norm() +
             (tetrahedron[2] - tetrahedron[1]).cross(tetrahedron[3] - tetrahedron[1]).norm());
  const double inradius = 3 * volume / area;
  EXPECT_LE(tetra.innerSphereRadius(), inradius + 1e-12);
  EXPECT_GE(tetra.innerSphereRadius(), 0.9 * inradius);
  // A cube with one corner pulled out: the smallest enclosing sphere is no longer centred on the
  // box (its centre moves towards the far corner), and the unit cube's inner ball has radius 0.5.
  std::vector<Vec3> cube;
  for (int i = 0; i < 8; ++i) cube.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const ConvexPolytope unit(cube);
  EXPECT_NEAR(unit.innerSphereRadius(), 0.5, 1e-9);
  EXPECT_NEAR(unit.boundingSphereRadius(), std::sqrt(3.0) / 2, 1e-9);
  // Points on a unit sphere plus one pole: the smallest enclosing sphere has radius 1.
  std::vector<Vec3> capped;
  for (int i = 0; i < 12; ++i) {
    const double angle = 2 * std::numbers::pi * i / 12;
    capped.emplace_back(std::cos(angle), std::sin(angle), 0.0);
  }
  capped.emplace_back(0, 0, 1);
  capped.emplace_back(0, 0, -0.2);
  const ConvexPolytope cap(capped);
  EXPECT_LE(cap.boundingSphereRadius(), 1.0 + 1e-3);
  EXPECT_LT(cap.boundingSphereRadius(), farthest(capped, cap.localBox().center()) - 0.01);
}

// Every scan implementation (the scalar one, and the AVX2 and AVX-512 ones where the CPU has
// them) returns a vertex at the maximum, the first one on exact ties (padding lanes repeat vertex
// 0), and a valid vertex for a NaN direction.
TEST(ConvexPolytope, EveryScanBuildFindsTheFirstMaximum) {
  using Scan = std::uint32_t (*)(const VertexChunk*, std::size_t, const Vec3&);
  std::vector<std::pair<std::string, Scan>> scans = {{"scalar", detail::scanVertexChunksScalar}};
  if (__builtin_cpu_supports("avx2")) scans.emplace_back("AVX2", detail::scanVertexChunksAvx2);
  if (__builtin_cpu_supports("avx512f")) {
    scans.emplace_back("AVX-512", detail::scanVertexChunksAvx512);
  }
  std::mt19937_64 rng(21);
  for (const int n : {4, 5, 8, 9, 15, 16, 17, 40, 64}) {
    const auto pair = randomPolytopePairs(1, n, 300 + static_cast<std::uint64_t>(n)).front();
    const ConvexPolytope polytope(pair.localA);
    const std::span<const VertexChunk> chunks = polytope.chunks();
    ASSERT_EQ(chunks.size(), (static_cast<std::size_t>(n) + kLaneWidth - 1) / kLaneWidth);
    for (const auto& [name, scan] : scans) {
      SCOPED_TRACE(name + " N=" + std::to_string(n));
      for (int i = 0; i < 1000; ++i) {
        const Vec3 d = randomDirection(rng);
        const std::uint32_t index = scan(chunks.data(), chunks.size(), d);
        ASSERT_LT(index, polytope.vertexCount());
        EXPECT_NEAR(d.dot(polytope.vertices()[index]), maxDot(polytope.vertices(), d),
                    1e-12 * (1 + d.norm()));
      }
      // Every vertex ties along the zero direction: the first wins.
      EXPECT_EQ(scan(chunks.data(), chunks.size(), Vec3::Zero()), 0U);
      const Vec3 nan = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
      EXPECT_LT(scan(chunks.data(), chunks.size(), nan), polytope.vertexCount());
    }
  }
  // A box's corners repeated in three chunks: exact ties between a vertex and its later copies
  // (in the same lane of later chunks, or other lanes) go to the first one.
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  std::array<VertexChunk, 3> repeated;
  for (VertexChunk& chunk : repeated) {
    for (std::size_t lane = 0; lane < kLaneWidth; ++lane) {
      const Vec3& corner = corners[(lane + 3) % kLaneWidth];
      chunk.x[lane] = corner.x();
      chunk.y[lane] = corner.y();
      chunk.z[lane] = corner.z();
    }
  }
  for (const auto& [name, scan] : scans) {
    for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(1, 1, 0), Vec3(0, 0, 0)}) {
      std::uint32_t first = 0;
      for (std::uint32_t v = 0; v < kLaneWidth; ++v) {
        if (d.dot(corners[(v + 3) % kLaneWidth]) > d.dot(corners[(first + 3) % kLaneWidth])) {
          first = v;
        }
      }
      EXPECT_EQ(scan(repeated.data(), 1, d), first) << name;
      EXPECT_EQ(scan(repeated.data(), repeated.size(), d), first) << name;
    }
  }
}

TEST(ConvexPolytope, TransformedSupportMatchesTransformedVertices) {
  for (const int n : {8, 64}) {
    const auto pair = randomPolytopePairs(1, n, 11).front();
    const ConvexPolytope polytope(pair.localA);
    const TransformedSupport placed(polytope, pair.poseA);
    const std::vector<Vec3> world = pair.worldA();
    std::mt19937_64 rng(5);
    TransformedSupport::Hint hint{};
    for (int i = 0; i < 1000; ++i) {
      const Vec3 d = randomDirection(rng);
      ASSERT_NEAR(d.dot(placed.support(d, hint)), maxDot(world, d), 1e-12 * (1 + d.norm()));
    }
    EXPECT_TRUE(placed.center().isApprox(pair.poseA * polytope.center()));
  }
}

TEST(ConvexPolytope, HullsOfRealRobotLinksSupportExactly) {
  for (const char* name : {"kr5-wrist.stl", "kr5-base-link.stl", "wam2.stl"}) {
    const TriangleMesh mesh = readMesh(kaboum::testing::dataFile(std::string("meshes/") + name));
    const ConvexPolytope polytope(mesh.vertices, name);
    // exercises hill climbing
    EXPECT_GT(polytope.vertexCount(), ConvexPolytope::kBruteForceMaxVertices) << name;
    expectExactSupport(polytope, mesh.vertices, 3);
  }
}

TEST(ConvexPolytope, RejectsPointSetsWithoutVolume) {
  const std::vector<Vec3> three = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()};
  EXPECT_THROW(ConvexPolytope(three, "three"), InputError);
  const std::vector<Vec3> flat = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3(1, 1, 0)};
  EXPECT_THROW(ConvexPolytope(flat, "flat"), InputError);
  std::vector<Vec3> nan = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  nan[2].x() = std::numeric_limits<double>::quiet_NaN();
  try {
    ConvexPolytope polytope(nan, "piece 3");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("piece 3"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace kaboum::collision
