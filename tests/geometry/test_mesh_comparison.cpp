#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::testing;

namespace {

constexpr std::size_t kRandomSamples = 3000;
constexpr std::uint64_t kSeed = 17;

double signedVolume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (const Triangle& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return volume;
}

// Smallest distance from the origin to the plane of a face of a mesh around the origin.
double smallestFaceDistance(const TriangleMesh& mesh) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    smallest = std::min(smallest, std::abs(a.dot((b - a).cross(c - a).normalized())));
  }
  return smallest;
}

// Reference for countSelfIntersections: every pair, same neighbour rules.
std::size_t bruteForceSelfIntersections(const TriangleMesh& mesh) {
  std::size_t pairs = 0;
  const auto at = [&](const Triangle& t, std::size_t k) -> const Vec3& {
    return mesh.vertices[t[k % 3]];
  };
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (std::size_t j = i + 1; j < mesh.triangles.size(); ++j) {
      const Triangle &a = mesh.triangles[i], &b = mesh.triangles[j];
      int shared = 0;
      std::size_t ka = 0, kb = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        for (std::size_t l = 0; l < 3; ++l) {
          if (a[k] == b[l]) {
            ++shared;
            ka = k;
            kb = l;
          }
        }
      }
      if (shared == 0) {
        pairs += trianglesIntersect(at(a, 0), at(a, 1), at(a, 2), at(b, 0), at(b, 1), at(b, 2));
      } else if (shared == 1) {
        pairs += trianglesMeetBesideSharedVertex(at(a, ka), at(a, ka + 1), at(a, ka + 2),
                                                 at(b, kb + 1), at(b, kb + 2));
      }
    }
  }
  return pairs;
}

TEST(TestShapes, AreClosedOutwardAndOfTheExpectedVolume) {
  EXPECT_NEAR(signedVolume(makeBox(Vec3(0, 0, 0), Vec3(1, 2, 3), 3)), 6.0, 1e-12);
  EXPECT_NEAR(signedVolume(makeLPrism(0.5)), 1.5, 1e-12);
  const double sphere = signedVolume(makeIcosphere(4));
  EXPECT_LT(sphere, 4.0 / 3.0 * std::numbers::pi);
  EXPECT_GT(sphere, 0.99 * 4.0 / 3.0 * std::numbers::pi);
  const double torus = 2.0 * std::numbers::pi * std::numbers::pi * 0.09;  // 2 pi^2 R r^2
  EXPECT_LT(signedVolume(makeTorus(1.0, 0.3, 64, 32)), torus);
  EXPECT_GT(signedVolume(makeTorus(1.0, 0.3, 64, 32)), 0.99 * torus);
  // Two cones of height 1 on a regular 64-gon of circumradius 1: 2/3 of the polygon's area.
  EXPECT_NEAR(signedVolume(makeDoubleCone(64)),
              2.0 / 3.0 * 32.0 * std::sin(2.0 * std::numbers::pi / 64.0), 1e-12);
  EXPECT_LT(signedVolume(flipMesh(makeIcosphere(1))), 0.0);
  for (const TriangleMesh& closed : {makeIcosphere(2), makeTorus(1.0, 0.3, 12, 6), makeLPrism(),
                                     makeBox(Vec3::Zero(), Vec3::Ones(), 2), makeDoubleCone(16)}) {
    EXPECT_TRUE(verifyContainment(closed, closed, BoundSide::Outer, 10, 1).defined);
  }
}

TEST(MeasureHausdorff, OfAMeshWithItselfIsZero) {
  const TriangleMesh torus = makeTorus(1.0, 0.35, 40, 20);
  const HausdorffReport report = measureHausdorff(torus, torus, kRandomSamples, kSeed);
  EXPECT_LE(report.originalToResult.max, 1e-12);
  EXPECT_LE(report.resultToOriginal.max, 1e-12);
  EXPECT_EQ(report.samples, 2 * sampleSurface(torus, kRandomSamples, kSeed).size());
  EXPECT_NEAR(report.diagonal, std::sqrt(2.7 * 2.7 * 2 + 0.7 * 0.7), 0.05);
}

TEST(MeasureHausdorff, OfConcentricSpheresIsTheRadiusOffset) {
  // P and 1.1 P with P between the spheres of radius h and 1: every distance, both ways, lies
  // between 1.1 h - 1 and 0.1 (distance of x to 1.1 x).
  const TriangleMesh sphere = makeIcosphere(4);
  const TriangleMesh larger = transformMesh(sphere, 1.1, Vec3::Zero());
  const double h = smallestFaceDistance(sphere);
  ASSERT_GT(h, 0.99);
  const HausdorffReport report = measureHausdorff(sphere, larger, kRandomSamples, kSeed);
  for (const DistanceStats& stats : {report.originalToResult, report.resultToOriginal}) {
    EXPECT_GE(stats.min, 1.1 * h - 1.0 - 1e-12);
    EXPECT_LE(stats.max, 0.1 + 1e-12);
    EXPECT_LE(stats.min, stats.mean);
    EXPECT_LE(stats.mean, stats.max);
    EXPECT_NEAR(stats.mean, 0.1, 0.1 * (1.0 - h) + 1e-3);
  }
  EXPECT_NEAR(report.diagonal, 2.0 * std::sqrt(3.0), 0.1);
}

TEST(MeasureHausdorff, OfAShiftedMeshIsTheShift) {
  // Every point of P is within |s| of P + s, and the extreme vertex in the shift direction is
  // exactly |s| away: both one-sided maxima equal |s|.
  const TriangleMesh sphere = makeIcosphere(3);
  const TriangleMesh shifted = transformMesh(sphere, 1.0, Vec3::Zero(), Vec3(0.1, 0, 0));
  const HausdorffReport report = measureHausdorff(sphere, shifted, kRandomSamples, kSeed);
  EXPECT_NEAR(report.originalToResult.max, 0.1, 1e-12);
  EXPECT_NEAR(report.resultToOriginal.max, 0.1, 1e-12);
}

// One meter, several results: each report is the shift's exact distance, and `within` says
// whether both one-sided maxima stay within the limit.
TEST(HausdorffMeter, MeasuresEachResultAgainstTheSameOriginal) {
  const TriangleMesh sphere = makeIcosphere(3);
  const HausdorffMeter meter(sphere, kRandomSamples, kSeed);
  for (const double shift : {0.3, 0.05, 0.2}) {
    const TriangleMesh shifted = transformMesh(sphere, 1.0, Vec3::Zero(), Vec3(0, shift, 0));
    const HausdorffReport report = meter.measure(shifted);
    EXPECT_NEAR(report.originalToResult.max, shift, 1e-12);
    EXPECT_NEAR(report.resultToOriginal.max, shift, 1e-12);
    EXPECT_FALSE(meter.within(shifted, 0.99 * shift));
    EXPECT_TRUE(meter.within(shifted, 1.01 * shift));
  }
  // Each direction on its own: a cap of the sphere is near it but leaves the rest far away; the
  // sphere with a far box added is near the original but not the other way round.
  TriangleMesh cap = sphere;
  std::erase_if(cap.triangles, [&](const Triangle& t) { return sphere.vertices[t[0]].z() < 0.5; });
  const HausdorffReport capReport = meter.measure(cap);
  EXPECT_LT(capReport.resultToOriginal.max, 1e-12);
  EXPECT_GT(capReport.originalToResult.max, 1.0);
  EXPECT_FALSE(meter.within(cap, 0.5 * capReport.originalToResult.max));
  EXPECT_TRUE(meter.within(cap, 1.0001 * capReport.originalToResult.max));
  TriangleMesh withBox = sphere;
  const TriangleMesh box = makeBox(Vec3::Constant(4.0), Vec3::Constant(5.0));
  const auto offset = static_cast<std::uint32_t>(withBox.vertices.size());
  withBox.vertices.insert(withBox.vertices.end(), box.vertices.begin(), box.vertices.end());
  for (const Triangle& t : box.triangles) {
    withBox.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  const HausdorffReport boxReport = meter.measure(withBox);
  EXPECT_LT(boxReport.originalToResult.max, 1e-12);
  EXPECT_GT(boxReport.resultToOriginal.max, 4.0);
  EXPECT_FALSE(meter.within(withBox, 0.5 * boxReport.resultToOriginal.max));
  EXPECT_TRUE(meter.within(withBox, 1.0001 * boxReport.resultToOriginal.max));
}

TEST(MeasureHausdorff, RejectsEmptyMeshesByRole) {
  const TriangleMesh sphere = makeIcosphere(1);
  try {
    (void)measureHausdorff(sphere, TriangleMesh{}, 10, 1);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "result mesh has no triangles");
  }
  const HausdorffMeter meter(sphere, 10, 1);
  try {
    (void)meter.within(TriangleMesh{}, 1.0);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "result mesh has no triangles");
  }
  EXPECT_THROW((void)verifyContainment(TriangleMesh{}, sphere, BoundSide::Inner, 10, 1),
               InputError);
}

TEST(VerifyContainment, ScaledUpSphereIsAnOuterBound) {
  const TriangleMesh sphere = makeIcosphere(3);
  const ContainmentReport report = verifyContainment(
      sphere, transformMesh(sphere, 1.1, Vec3::Zero()), BoundSide::Outer, kRandomSamples, kSeed);
  EXPECT_TRUE(report.defined);
  EXPECT_TRUE(report.note.empty());
  EXPECT_EQ(report.checked, sampleSurface(sphere, kRandomSamples, kSeed).size());
  EXPECT_EQ(report.violations, 0u);
  EXPECT_EQ(report.worstViolation, 0.0);
  EXPECT_EQ(report.selfIntersectingPairs, 0u);
}

TEST(VerifyContainment, ScaledDownSphereIsAnInnerBound) {
  const TriangleMesh sphere = makeIcosphere(3);
  const TriangleMesh smaller = transformMesh(sphere, 0.9, Vec3::Zero());
  const ContainmentReport report =
      verifyContainment(sphere, smaller, BoundSide::Inner, kRandomSamples, kSeed);
  EXPECT_TRUE(report.defined);
  EXPECT_EQ(report.checked, sampleSurface(smaller, kRandomSamples, kSeed).size());
  EXPECT_EQ(report.violations, 0u);
  EXPECT_EQ(report.selfIntersectingPairs, 0u);
  // The wrong side is caught both ways.
  EXPECT_GT(verifyContainment(sphere, smaller, BoundSide::Outer, kRandomSamples, kSeed).violations,
            0u);
  EXPECT_EQ(verifyContainment(sphere, smaller, BoundSide::Outer, kRandomSamples, kSeed).checked,
            sampleSurface(sphere, kRandomSamples, kSeed).size());
}

TEST(VerifyContainment, ConcaveAndHoledShapes) {
  // The L-prism is star-shaped around (0.5, 0.5, 0.5): scaling about it nests the copies.
  const TriangleMesh prism = makeLPrism();
  const Vec3 kernel(0.5, 0.5, 0.5);
  EXPECT_EQ(verifyContainment(prism, transformMesh(prism, 1.2, kernel), BoundSide::Outer,
                              kRandomSamples, kSeed)
                .violations,
            0u);
  EXPECT_EQ(verifyContainment(prism, transformMesh(prism, 0.8, kernel), BoundSide::Inner,
                              kRandomSamples, kSeed)
                .violations,
            0u);
  // A thicker torus around the same core circle contains the thinner one.
  const TriangleMesh thin = makeTorus(1.0, 0.3, 48, 24), thick = makeTorus(1.0, 0.4, 48, 24);
  EXPECT_EQ(verifyContainment(thin, thick, BoundSide::Outer, kRandomSamples, kSeed).violations, 0u);
  EXPECT_EQ(verifyContainment(thick, thin, BoundSide::Inner, kRandomSamples, kSeed).violations, 0u);
  EXPECT_GT(verifyContainment(thick, thin, BoundSide::Outer, kRandomSamples, kSeed).violations, 0u);
}

TEST(VerifyContainment, ConvexHullIsNoInnerBoundOfTheLPrism) {
  // The square [0,2]^2 x [0,1] claimed inside the L: its corner (2, 2) is 1 away from the L.
  const TriangleMesh prism = makeLPrism();
  const TriangleMesh hull = makeBox(Vec3(0, 0, 0), Vec3(2, 2, 1), 4);
  const ContainmentReport report =
      verifyContainment(prism, hull, BoundSide::Inner, kRandomSamples, kSeed);
  EXPECT_TRUE(report.defined);
  EXPECT_GT(report.violations, 0u);
  EXPECT_NEAR(report.worstViolation, 1.0, 1e-12);
  EXPECT_EQ(verifyContainment(prism, hull, BoundSide::Outer, kRandomSamples, kSeed).violations, 0u);
}

TEST(VerifyContainment, ShiftedSphereViolatesByTheShift) {
  const TriangleMesh sphere = makeIcosphere(3);
  const TriangleMesh shifted = transformMesh(sphere, 1.0, Vec3::Zero(), Vec3(0.1, 0, 0));
  const HausdorffReport distances = measureHausdorff(sphere, shifted, kRandomSamples, kSeed);
  for (const BoundSide side : {BoundSide::Outer, BoundSide::Inner}) {
    const ContainmentReport report =
        verifyContainment(sphere, shifted, side, kRandomSamples, kSeed);
    EXPECT_TRUE(report.defined);
    EXPECT_GT(report.violations, report.checked / 10);
    EXPECT_LT(report.violations, report.checked);
    EXPECT_NEAR(report.worstViolation, 0.1, 1e-12);
    EXPECT_EQ(report.worstViolation, side == BoundSide::Outer ? distances.originalToResult.max
                                                              : distances.resultToOriginal.max);
  }
}

TEST(VerifyContainment, ToleranceAcceptsNearSurfaceSamples) {
  const TriangleMesh sphere = makeIcosphere(3);
  const TriangleMesh barelySmaller = transformMesh(sphere, 1.0 - 1e-7, Vec3::Zero());
  EXPECT_GT(verifyContainment(sphere, barelySmaller, BoundSide::Outer, 500, kSeed).violations, 0u);
  EXPECT_EQ(verifyContainment(sphere, barelySmaller, BoundSide::Outer, 500, kSeed, 1e-6).violations,
            0u);
}

TEST(VerifyContainment, AnInsideOutMeshIsAViolation) {
  // A larger sphere encloses the smaller one, but with its faces turned inward it is no bound.
  const TriangleMesh sphere = makeIcosphere(2);
  const TriangleMesh larger = transformMesh(sphere, 1.2, Vec3::Zero(), Vec3::Zero());
  const ContainmentReport good = verifyContainment(sphere, larger, BoundSide::Outer, 200, kSeed);
  EXPECT_FALSE(good.insideOut);
  EXPECT_EQ(good.violations, 0u);
  const ContainmentReport flipped =
      verifyContainment(sphere, flipMesh(larger), BoundSide::Outer, 200, kSeed);
  EXPECT_TRUE(flipped.defined);
  EXPECT_TRUE(flipped.insideOut);
  EXPECT_NE(flipped.note.find("result is inside out"), std::string::npos) << flipped.note;
  const ContainmentReport flippedInner =
      verifyContainment(flipMesh(larger), sphere, BoundSide::Inner, 200, kSeed);
  EXPECT_TRUE(flippedInner.insideOut);
  EXPECT_NE(flippedInner.note.find("original is inside out"), std::string::npos);
}

TEST(VerifyContainment, IsUndefinedForOpenContainers) {
  const TriangleMesh open = makeOpenBox(Vec3(0, 0, 0), Vec3(1, 1, 1), 2);
  const TriangleMesh closed = makeBox(Vec3(-1, -1, -1), Vec3(2, 2, 2));
  for (const BoundSide side : {BoundSide::Outer, BoundSide::Inner}) {
    const ContainmentReport report = verifyContainment(open, closed, side, 100, kSeed);
    EXPECT_FALSE(report.defined);
    EXPECT_EQ(report.note,
              "the original is not closed (8 border or inconsistently oriented edges): "
              "containment is only defined for closed meshes");
    EXPECT_EQ(report.checked, 0u);
  }
  const ContainmentReport openResult =
      verifyContainment(closed, open, BoundSide::Outer, 100, kSeed);
  EXPECT_FALSE(openResult.defined);
  EXPECT_NE(openResult.note.find("the result is not closed"), std::string::npos);
  // An inner result only needs a closed original.
  EXPECT_TRUE(verifyContainment(closed, open, BoundSide::Inner, 100, kSeed).defined);
  // A flipped triangle breaks orientation consistency.
  TriangleMesh inconsistent = makeIcosphere(1);
  std::swap(inconsistent.triangles[0][1], inconsistent.triangles[0][2]);
  EXPECT_FALSE(verifyContainment(inconsistent, closed, BoundSide::Inner, 100, kSeed).defined);
}

TEST(CountSelfIntersections, CleanShapesHaveNone) {
  EXPECT_EQ(countSelfIntersections(makeTorus(1.0, 0.35, 40, 20)), 0u);
  EXPECT_EQ(countSelfIntersections(makeIcosphere(3)), 0u);
  EXPECT_EQ(countSelfIntersections(makeLPrism()), 0u);
  EXPECT_EQ(countSelfIntersections(makeBox(Vec3::Zero(), Vec3::Ones(), 4)), 0u);
  EXPECT_EQ(countSelfIntersections(TriangleMesh{}), 0u);
}

TEST(CountSelfIntersections, MatchesBruteForceOnIntersectingMeshes) {
  const TriangleMesh spheres =
      mergeMeshes(makeIcosphere(2), makeIcosphere(2, 0.7, Vec3(0.8, 0.2, 0.1)));
  const std::size_t overlapping = countSelfIntersections(spheres);
  EXPECT_GT(overlapping, 20u);
  EXPECT_EQ(overlapping, bruteForceSelfIntersections(spheres));

  // A vertex pushed through the far side drags its fan of triangles across the opposite surface.
  TriangleMesh dented = makeIcosphere(2);
  dented.vertices[0] *= -1.3;
  const std::size_t crossings = countSelfIntersections(dented);
  EXPECT_GT(crossings, 5u);
  EXPECT_EQ(crossings, bruteForceSelfIntersections(dented));
}

TEST(CountSelfIntersections, FindsFoldsThroughASharedVertex) {
  TriangleMesh fold;
  fold.vertices = {Vec3(0, 0, 0),     Vec3(1, 0, 0),      Vec3(0, 1, 0),
                   Vec3(0.5, 0.2, 1), Vec3(0.2, 0.5, -1), Vec3(0.2, 0.5, 2)};
  fold.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(countSelfIntersections(fold), 1u);
  fold.triangles = {{0, 1, 2}, {0, 3, 5}};
  EXPECT_EQ(countSelfIntersections(fold), 0u);
}

}  // namespace
}  // namespace kaboum::geometry
