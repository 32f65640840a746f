// GJK against the exact reference (hull of the Minkowski difference): no missed overlap, no
// distance above the truth, witness points on the shapes, on random, degenerate and real pairs.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/gjk.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/minkowski_reference.hpp"
#include "kaboum/testing/polytope_pairs.hpp"

namespace kaboum::collision {

using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

// The reference's own rounding (qhull planes, closest point on a triangle) on unit-size shapes.
constexpr double kReferenceRounding = 1e-12;
constexpr double kMargin = 0.05;

// Largest distance above `margin` at which intersects() may still answer true (its header).
double trueBand(double margin, double distance, const GjkTolerance& tolerance = {}) {
  return margin + 2 * tolerance.absolute + tolerance.relative * distance + kReferenceRounding;
}

// Largest violation of "inside the hull of `points`" by `p` (<= 0 when inside).
double outsideBy(const ConvexHull& hull, const Vec3& p) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const HullPlane& plane : hull.planes)
    worst = std::max(worst, plane.normal.dot(p) - plane.offset);
  return worst;
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

struct Tally {
  int pairs = 0;
  int overlapping = 0;
  int missedOverlaps = 0;   // intersects() false while the distance is <= margin
  int falseAlarms = 0;      // intersects() true beyond the stated band
  int overestimates = 0;    // distance() above the true distance
  int looseDistances = 0;   // distance() below the truth by more than the tolerance
  int witnessesOff = 0;     // a witness point off its shape, or |pA - pB| != distance
  int wrongVerdicts = 0;    // sphereVerdict() or portalIntersects() contradicting the reference
  int portalQueries = 0;    // portalIntersects() calls (both margins)
  int portalUndecided = 0;  // ... that answered `unknown`
  int fanQueries = 0;       // detail::fanPretest() calls on pairs the sphere tests leave
  int fanDecided = 0;       // ... that answered `separated` or `intersecting`
  std::string firstFailure;

  void fail(int& counter, const std::string& what) {
    ++counter;
    if (firstFailure.empty()) firstFailure = what;
  }
  void expectClean() const {
    EXPECT_EQ(missedOverlaps, 0) << firstFailure;
    EXPECT_EQ(falseAlarms, 0) << firstFailure;
    EXPECT_EQ(overestimates, 0) << firstFailure;
    EXPECT_EQ(looseDistances, 0) << firstFailure;
    EXPECT_EQ(witnessesOff, 0) << firstFailure;
    EXPECT_EQ(wrongVerdicts, 0) << firstFailure;
  }
};

// The reference's answers for one pair: the true signed distance and both hulls.
struct Truth {
  Truth(const std::vector<Vec3>& worldA, const std::vector<Vec3>& worldB)
      : signedDistance(minkowskiReference(worldA, worldB).signedDistance),
        hullA(convexHull(worldA)),
        hullB(convexHull(worldB)) {}
  double signedDistance;
  ConvexHull hullA, hullB;
};

// One implementation's answers on one pair, checked against the reference: `intersectsAt(margin)`
// and `distanceOf()` (witness points in the world frame).
template <class Intersects, class Distance>
void checkAnswers(const Intersects& intersectsAt, const Distance& distanceOf, const Truth& truth,
                  Tally& tally, const std::string& context) {
  for (const double margin : {0.0, kMargin}) {
    const bool hit = intersectsAt(margin);
    if (!hit && truth.signedDistance <= margin + kReferenceRounding) {
      tally.fail(tally.missedOverlaps, context + ": missed at margin " + number(margin));
    }
    if (hit && truth.signedDistance > trueBand(margin, truth.signedDistance)) {
      tally.fail(tally.falseAlarms, context + ": false alarm at margin " + number(margin));
    }
  }

  const DistanceResult result = distanceOf();
  const double clamped = std::max(truth.signedDistance, 0.0);
  const GjkTolerance tolerance;
  if (result.distance > clamped + kReferenceRounding) {
    tally.fail(tally.overestimates, context + ": distance " + number(result.distance));
  }
  if (result.distance <
      clamped - tolerance.absolute - tolerance.relative * clamped - kReferenceRounding) {
    tally.fail(tally.looseDistances, context + ": distance " + number(result.distance));
  }
  const double gap = (result.pointA - result.pointB).norm();
  const bool onShapes = outsideBy(truth.hullA, result.pointA) <= 1e-9 &&
                        outsideBy(truth.hullB, result.pointB) <= 1e-9;
  const bool consistent = result.intersecting
                              ? gap <= 1e-9
                              : gap >= result.distance - kReferenceRounding &&
                                    gap <= result.distance + tolerance.absolute +
                                               tolerance.relative * gap + kReferenceRounding;
  if (!onShapes || !consistent) {
    tally.fail(tally.witnessesOff, context + ": witness gap " + number(gap));
  }
}

std::string describe(const std::string& label, const Tally& tally, double truth) {
  std::ostringstream context;
  context.precision(17);
  context << label << " pair " << tally.pairs << " true signed distance " << truth;
  return context.str();
}

// Every query kind on one placed pair, checked against the reference.
template <SupportMapping A, SupportMapping B>
void checkPair(const A& a, const B& b, const std::vector<Vec3>& worldA,
               const std::vector<Vec3>& worldB, Tally& tally, const std::string& label) {
  const Truth truth(worldA, worldB);
  ++tally.pairs;
  if (truth.signedDistance <= 0) ++tally.overlapping;
  checkAnswers([&](double margin) { return intersects(a, b, margin); },
               [&] { return distance(a, b); }, truth, tally,
               describe(label, tally, truth.signedDistance));
}

// A verdict may be `separated` only beyond margin and `intersecting` only within the band.
void checkVerdict(PairVerdict verdict, double truth, double margin, Tally& tally,
                  const std::string& what) {
  if (verdict == PairVerdict::separated && truth <= margin + kReferenceRounding) {
    tally.fail(tally.wrongVerdicts, what + ": separated at true distance " + number(truth));
  }
  if (verdict == PairVerdict::intersecting && truth > trueBand(margin, truth)) {
    tally.fail(tally.wrongVerdicts, what + ": intersecting at true distance " + number(truth));
  }
}

// The public queries (checkPair); the conservative tests they start with, each on its own
// (sphereVerdict(), the AVX-512 build's fan test and portalIntersects() in a's frame); and, for
// pairs the scan handles, every build of the placed queries (scalar, and AVX2 / AVX-512 where the
// CPU has them), whatever this CPU picks.
void checkPolytopePair(const PolytopePair& pair, Tally& tally, const std::string& label) {
  const ConvexPolytope polytopeA(pair.localA);
  const ConvexPolytope polytopeB(pair.localB);
  const std::vector<Vec3> worldA = pair.worldA();
  const std::vector<Vec3> worldB = pair.worldB();
  const Truth reference(worldA, worldB);
  const double truth = reference.signedDistance;
  ++tally.pairs;
  if (truth <= 0) ++tally.overlapping;
  const std::string context = describe(label, tally, truth);
  const TransformedSupport a(polytopeA, pair.poseA);
  const TransformedSupport b(polytopeB, pair.poseB);
  checkAnswers([&](double margin) { return intersects(a, b, margin); },
               [&] { return distance(a, b); }, reference, tally, context);
  const TransformedSupport bInA(polytopeB, pair.poseA.inverse() * pair.poseB);
  const auto inWorld = [&pair](DistanceResult result) {
    result.pointA = pair.poseA * result.pointA;
    result.pointB = pair.poseA * result.pointB;
    return result;
  };
  if (detail::scansBoth(polytopeA, polytopeB)) {
    checkAnswers(
        [&](double margin) {
          return detail::intersectsPlacedScalar(polytopeA, bInA, margin, GjkTolerance{});
        },
        [&] {
          return inWorld(detail::distancePlacedScalar(polytopeA, bInA, nullptr, GjkTolerance{}));
        },
        reference, tally, context + " (scalar build)");
    if (__builtin_cpu_supports("avx2")) {
      checkAnswers(
          [&](double margin) {
            return detail::intersectsPlacedAvx2(polytopeA, bInA, margin, GjkTolerance{});
          },
          [&] {
            return inWorld(detail::distancePlacedAvx2(polytopeA, bInA, nullptr, GjkTolerance{}));
          },
          reference, tally, context + " (AVX2 build)");
    }
    if (__builtin_cpu_supports("avx512f")) {
      checkAnswers(
          [&](double margin) {
            return detail::intersectsPlacedAvx512(polytopeA, bInA, margin, GjkTolerance{});
          },
          [&] {
            return inWorld(detail::distancePlacedAvx512(polytopeA, bInA, nullptr, GjkTolerance{}));
          },
          reference, tally, context + " (AVX-512 build)");
    }
  }
  for (const double margin : {0.0, kMargin}) {
    const std::string what = label + " margin " + number(margin);
    checkVerdict(sphereVerdict(polytopeA, bInA, margin), truth, margin, tally, what + " spheres");
    const PairVerdict portal = portalIntersects(polytopeA, bInA, margin);
    checkVerdict(portal, truth, margin, tally, what + " portal");
    ++tally.portalQueries;
    if (portal == PairVerdict::unknown) ++tally.portalUndecided;
    const PairVerdict fan = detail::fanPretest(polytopeA, bInA, margin, GjkTolerance{});
    checkVerdict(fan, truth, margin, tally, what + " fan");
    if (sphereVerdict(polytopeA, bInA, margin) == PairVerdict::unknown) {
      ++tally.fanQueries;
      if (fan != PairVerdict::unknown) ++tally.fanDecided;
    }
  }
}

TEST(Gjk, AgreesWithTheExactReferenceOnRandomPolytopes) {
  for (const auto& [n, count] : {std::pair{8, 4000}, {16, 3000}, {32, 1500}, {64, 500}}) {
    Tally tally;
    for (const PolytopePair& pair : randomPolytopePairs(static_cast<std::size_t>(count), n, 42)) {
      checkPolytopePair(pair, tally, "N=" + std::to_string(n));
    }
    SCOPED_TRACE("N=" + std::to_string(n));
    tally.expectClean();
    // The portal test leaves GJK only the pairs it cannot certify (near contact, degenerate).
    EXPECT_LT(tally.portalUndecided, tally.portalQueries / 20);
    // Where the fan test runs (AVX-512, up to 16 vertices), it decides most pairs the sphere
    // tests leave (the rest go to the portal test).
    if (__builtin_cpu_supports("avx512f") && n <= 16) {
      EXPECT_GT(tally.fanDecided, tally.fanQueries * 4 / 5);
    }
    // The workload is the issue's: about 40% of the pairs overlap.
    EXPECT_NEAR(static_cast<double>(tally.overlapping) / tally.pairs, 0.4, 0.08);
  }
}

// B moved so that the pair touches (closest points coincide), then pushed off or into contact by
// a few tiny gaps: the hardest cases for termination tolerances.
TEST(Gjk, TouchingAndNearlyTouchingPairsAreNeverMissed) {
  Tally tally;
  int separated = 0;
  for (const int n : {8, 16, 32}) {
    for (PolytopePair pair : randomPolytopePairs(150, n, 7)) {
      const MinkowskiReference reference = minkowskiReference(pair.worldA(), pair.worldB());
      if (reference.signedDistance <= 0.01) continue;
      ++separated;
      const Vec3 normal = reference.closestPoint.normalized();
      const Vec3 original = pair.poseB.translation();
      for (const double gap : {0.0, 1e-13, -1e-13, 1e-10, -1e-10, 1e-9, 1e-7, -1e-7}) {
        pair.poseB.translation() = original + reference.closestPoint - gap * normal;
        checkPolytopePair(pair, tally, "gap " + number(gap));
      }
    }
  }
  EXPECT_GT(separated, 150);
  tally.expectClean();
}

std::vector<Vec3> box(const Vec3& low, const Vec3& high) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back(i & 1 ? high.x() : low.x(), i & 2 ? high.y() : low.y(),
                         i & 4 ? high.z() : low.z());
  }
  return corners;
}

PolytopePair placedPair(std::vector<Vec3> a, std::vector<Vec3> b, const Eigen::Isometry3d& poseB) {
  PolytopePair pair;
  pair.localA = std::move(a);
  pair.localB = std::move(b);
  pair.poseB = poseB;
  return pair;
}

Eigen::Isometry3d translation(double x, double y, double z) {
  return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
}

TEST(Gjk, DegenerateConfigurationsAreAnsweredSafely) {
  Tally tally;
  const std::vector<Vec3> unit = box(Vec3::Zero(), Vec3::Ones());
  // Coplanar faces: boxes face to face, edge to edge and corner to corner, exactly touching and
  // at tiny gaps and overlaps.
  for (const double gap : {0.0, 1e-12, -1e-12, 1e-9, 1e-6, -1e-6}) {
    checkPolytopePair(placedPair(unit, unit, translation(1 + gap, 0, 0)), tally, "face");
    checkPolytopePair(placedPair(unit, unit, translation(1 + gap, 0.5, 0.25)), tally,
                      "face shifted");
    checkPolytopePair(placedPair(unit, unit, translation(1 + gap, 1 + gap, 0)), tally, "edge");
    checkPolytopePair(placedPair(unit, unit, translation(1 + gap, 1 + gap, 1 + gap)), tally,
                      "corner");
  }
  // Identical shapes at the same pose, and a shape deep inside another.
  checkPolytopePair(placedPair(unit, unit, Eigen::Isometry3d::Identity()), tally, "identical");
  const auto random = randomPolytopePairs(1, 32, 9).front();
  checkPolytopePair(placedPair(random.localA, random.localA, Eigen::Isometry3d::Identity()), tally,
                    "identical random");
  checkPolytopePair(placedPair(unit, box(Vec3::Constant(0.4), Vec3::Constant(0.6)),
                               Eigen::Isometry3d::Identity()),
                    tally, "nested");
  // Thin slivers, crossing and parallel, and duplicated vertices.
  const std::vector<Vec3> sliver = box(Vec3(0, 0, 0), Vec3(2, 1, 1e-6));
  const Eigen::Isometry3d turned(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
  for (const double z : {1e-6, 1e-6 + 1e-9, 1e-6 + 1e-12, 0.5e-6, 2e-6}) {
    checkPolytopePair(placedPair(sliver, sliver, translation(0.5, 0.2, z)), tally,
                      "slivers stacked");
    Eigen::Isometry3d crossing = turned;
    crossing.translation() = Vec3(0.5, 0.5, z - 0.5);
    checkPolytopePair(placedPair(sliver, sliver, crossing), tally, "slivers crossing");
  }
  std::vector<Vec3> doubled = random.localB;
  doubled.insert(doubled.end(), random.localB.begin(), random.localB.end());
  checkPolytopePair(placedPair(random.localA, doubled, random.poseB), tally, "duplicates");
  tally.expectClean();
}

// Pose after pose of a slowly moving pair, one cache: the same answers as cold queries, and the
// warm start pays off where both run GJK to a distance (a cold query on overlapping polytopes
// may be decided by the fan test in one round instead).
TEST(Gjk, WarmStartGivesTheSameAnswersInFewerIterations) {
  for (const int n : {8, 64}) {
    const auto pair = randomPolytopePairs(1, n, 21).front();
    const ConvexPolytope polytopeA(pair.localA);
    const ConvexPolytope polytopeB(pair.localB);
    const TransformedSupport a(polytopeA, Eigen::Isometry3d::Identity());
    GjkCache<TransformedSupport, TransformedSupport> booleanCache;
    GjkCache<TransformedSupport, TransformedSupport> distanceCache;
    int warmIterations = 0;
    int coldIterations = 0;
    int hits = 0;
    for (int step = 0; step <= 400; ++step) {
      Eigen::Isometry3d poseB(Eigen::AngleAxisd(0.01 * step, Vec3(1, 2, 3).normalized()));
      poseB.translation() = Vec3(3.0 - 0.01 * step, 0.2, 0.1);
      const TransformedSupport b(polytopeB, poseB);
      const bool warm = intersects(a, b, 0.0, &booleanCache);
      ASSERT_EQ(warm, intersects(a, b)) << "step " << step;
      hits += warm ? 1 : 0;
      const DistanceResult warmDistance = distance(a, b, &distanceCache);
      const DistanceResult coldDistance = distance(a, b);
      ASSERT_NEAR(warmDistance.distance, coldDistance.distance, 1e-8) << "step " << step;
      if (!coldDistance.intersecting) {
        warmIterations += warmDistance.iterations;
        coldIterations += coldDistance.iterations;
      }
    }
    EXPECT_GT(hits, 0);
    EXPECT_LT(hits, 401);
    EXPECT_LT(warmIterations, coldIterations) << "N=" << n;
  }
}

// The convex hull of one polytope at two poses, given only by its support function (a swept
// piece, thesis Eq. 4.22): GJK needs nothing else.
class TwoPoseHull {
 public:
  struct Hint {
    ConvexPolytope::Hint first{};
    ConvexPolytope::Hint second{};
  };
  TwoPoseHull(const ConvexPolytope& polytope, const Eigen::Isometry3d& from,
              const Eigen::Isometry3d& to)
      : from_(polytope, from), to_(polytope, to) {}
  Vec3 support(const Vec3& direction, Hint& hint) const {
    const Vec3 p = from_.support(direction, hint.first);
    const Vec3 q = to_.support(direction, hint.second);
    return direction.dot(p) >= direction.dot(q) ? p : q;
  }
  Vec3 center() const { return 0.5 * (from_.center() + to_.center()); }

 private:
  TransformedSupport from_;
  TransformedSupport to_;
};

TEST(Gjk, AnySupportMappingWorksSuchAsASweptPiece) {
  Tally tally;
  for (const PolytopePair& pair : randomPolytopePairs(300, 16, 5)) {
    const ConvexPolytope polytopeA(pair.localA);
    const ConvexPolytope polytopeB(pair.localB);
    Eigen::Isometry3d later = pair.poseB;
    later.translation() += Vec3(0.4, -0.3, 0.2);
    later.linear() = later.linear() * Eigen::AngleAxisd(0.5, Vec3::UnitZ()).toRotationMatrix();
    std::vector<Vec3> sweptB = pair.worldB();
    for (const Vec3& p : pair.localB) sweptB.push_back(later * p);
    checkPair(TransformedSupport(polytopeA, pair.poseA), TwoPoseHull(polytopeB, pair.poseB, later),
              pair.worldA(), sweptB, tally, "swept");
  }
  tally.expectClean();
}

TEST(Gjk, HullsOfRealRobotLinksAgreeWithTheReference) {
  std::vector<std::vector<Vec3>> hulls;
  for (const char* name : {"kr5-wrist.stl", "kr5-base-link.stl", "wam2.stl"}) {
    const TriangleMesh mesh = readMesh(kaboum::testing::dataFile(std::string("meshes/") + name));
    const ConvexHull hull = convexHull(mesh.vertices, name);
    // Centered and scaled to unit size so the reference's tolerances apply.
    const Eigen::AlignedBox3d box(hull.mesh.vertices.front(), hull.mesh.vertices.front());
    Eigen::AlignedBox3d bounds = box;
    for (const Vec3& v : hull.mesh.vertices) bounds.extend(v);
    std::vector<Vec3> points;
    for (const Vec3& v : hull.mesh.vertices) {
      points.push_back((v - bounds.center()) / bounds.diagonal().norm());
    }
    hulls.push_back(points);
  }
  Tally tally;
  std::size_t k = 0;
  for (PolytopePair pair : randomPolytopePairs(120, 4, 77)) {
    pair.localA = hulls[k % hulls.size()];
    pair.localB = hulls[(k / hulls.size()) % hulls.size()];
    pair.poseB.translation() =
        pair.poseA.translation() + 0.4 * (pair.poseB.translation() - pair.poseA.translation());
    ++k;
    checkPolytopePair(pair, tally, "robot links");
  }
  EXPECT_GT(tally.overlapping, 10);
  EXPECT_LT(tally.overlapping, tally.pairs - 10);
  tally.expectClean();
}

}  // namespace
}  // namespace kaboum::collision
