#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <string>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace kaboum::geometry {

using namespace kaboum::testing;

namespace {

const Vec3& corner(const TriangleMesh& mesh, std::size_t triangle, std::size_t k) {
  return mesh.vertices[mesh.triangles[triangle][k]];
}

double bruteForceDistance(const TriangleMesh& mesh, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 q =
        closestPointOnTriangle(p, corner(mesh, t, 0), corner(mesh, t, 1), corner(mesh, t, 2));
    best = std::min(best, (q - p).norm());
  }
  return best;
}

// Generalized winding number: the solid angles of all triangles seen from p over 4 pi (Van
// Oosterom and Strackee). An integer for closed meshes, +1 inside an outward component.
double windingNumber(const TriangleMesh& mesh, const Vec3& p) {
  double total = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 a = corner(mesh, t, 0) - p, b = corner(mesh, t, 1) - p, c = corner(mesh, t, 2) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    total += 2.0 * std::atan2(a.dot(b.cross(c)),
                              la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return total / (4.0 * std::numbers::pi);
}

struct NamedMesh {
  std::string name;
  TriangleMesh mesh;
};

std::vector<NamedMesh> closedShapes() {
  const TriangleMesh sphere = makeIcosphere(3);
  return {{"icosphere", sphere},
          {"torus", makeTorus(1.0, 0.35, 40, 20)},
          {"lprism", makeLPrism(0.7)},
          {"box", makeBox(Vec3(-1, -0.5, 0), Vec3(1, 0.5, 2), 3)},
          {"overlapping spheres", mergeMeshes(sphere, makeIcosphere(2, 0.8, Vec3(0.9, 0.1, 0)))},
          {"inside-out sphere", flipMesh(makeIcosphere(2))}};
}

Vec3 boxMin(const TriangleMesh& mesh) {
  Vec3 lo = mesh.vertices[0];
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v);
  return lo;
}
Vec3 boxMax(const TriangleMesh& mesh) {
  Vec3 hi = mesh.vertices[0];
  for (const Vec3& v : mesh.vertices) hi = hi.cwiseMax(v);
  return hi;
}

// Uniform points in the bounding box grown by 20%, and points at several tiny distances off the
// surface near face interiors, edges and vertices.
std::vector<Vec3> queryPoints(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Vec3 lo = boxMin(mesh), hi = boxMax(mesh);
  const Vec3 grown = 0.2 * (hi - lo);
  const double diagonal = (hi - lo).norm();
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 u(unit(engine), unit(engine), unit(engine));
    points.push_back(lo - grown + u.cwiseProduct(hi - lo + 2 * grown));
  }
  std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t t = pick(engine);
    const Vec3 &a = corner(mesh, t, 0), &b = corner(mesh, t, 1), &c = corner(mesh, t, 2);
    const Vec3 normal = (b - a).cross(c - a).normalized();
    const double r = unit(engine);
    const Vec3 onSurface = i % 3 == 0   ? a + r * (b - a)                         // on an edge
                           : i % 3 == 1 ? a                                       // a vertex
                                        : (a + b + c) / 3.0 + r * 0.1 * (b - a);  // inside
    const double offset = diagonal * std::pow(10.0, -3.0 - 3.0 * static_cast<double>(i / 3 % 3));
    const Vec3 jitter = Vec3(unit(engine), unit(engine), unit(engine)) - Vec3::Constant(0.5);
    points.push_back(onSurface + offset * (i % 2 == 0 ? 1.0 : -1.0) * (normal + 0.3 * jitter));
  }
  return points;
}

TEST(ClosestPointOnTriangle, PicksTheRightRegion) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(closestPointOnTriangle(Vec3(0.2, 0.3, 5), a, b, c).isApprox(Vec3(0.2, 0.3, 0)));
  EXPECT_EQ(closestPointOnTriangle(Vec3(-1, -1, 1), a, b, c), a);
  EXPECT_TRUE(closestPointOnTriangle(Vec3(0.5, -2, 0), a, b, c).isApprox(Vec3(0.5, 0, 0)));
  EXPECT_TRUE(closestPointOnTriangle(Vec3(1, 1, -3), a, b, c).isApprox(Vec3(0.5, 0.5, 0)));
  EXPECT_EQ(closestPointOnTriangle(Vec3(3, -1, 0), a, b, c), b);
}

TEST(ClosestPointOnTriangle, HandlesZeroAreaTriangles) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  EXPECT_TRUE(closestPointOnTriangle(Vec3(1.5, 1, 0), a, b, c).isApprox(Vec3(1.5, 0, 0)));
  EXPECT_EQ(closestPointOnTriangle(Vec3(5, 1, 0), a, b, c), c);
  EXPECT_EQ(closestPointOnTriangle(Vec3(5, 1, 0), a, a, a), a);
}

TEST(ClosestPointOnTriangle, IsNoFartherThanAnyPointOfTheTriangle) {
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto randomVec = [&] { return Vec3(normal(engine), normal(engine), normal(engine)); };
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a = randomVec(), b = randomVec(), c = randomVec(), p = 1.5 * randomVec();
    const Vec3 q = closestPointOnTriangle(p, a, b, c);
    // q lies on the triangle: its barycentric coordinates are in [0, 1].
    Eigen::Matrix<double, 3, 2> edges;
    edges << b - a, c - a;
    const Eigen::Vector2d uv = edges.colPivHouseholderQr().solve(q - a);
    EXPECT_LT((a + edges * uv - q).norm(), 1e-9);
    EXPECT_GE(uv.minCoeff(), -1e-9);
    EXPECT_LE(uv.sum(), 1.0 + 1e-9);
    const double distance = (q - p).norm();
    constexpr int kGrid = 40;
    for (int i = 0; i <= kGrid; ++i) {
      for (int j = 0; i + j <= kGrid; ++j) {
        const Vec3 s = a + (b - a) * i / double{kGrid} + (c - a) * j / double{kGrid};
        ASSERT_LE(distance, (s - p).norm() + 1e-12);
      }
    }
  }
}

TEST(TriangleBvh, ClosestMatchesBruteForce) {
  for (const auto& [name, mesh] : closedShapes()) {
    SCOPED_TRACE(name);
    const TriangleBvh bvh(mesh);
    for (const Vec3& p : queryPoints(mesh, 600, 11)) {
      const TriangleBvh::Closest found = bvh.closest(p);
      ASSERT_NEAR(found.distance, bruteForceDistance(mesh, p), 1e-12);
      ASSERT_NEAR((found.point - p).norm(), found.distance, 1e-12);
      ASSERT_LT(found.triangle, mesh.triangles.size());
      const Vec3 onTriangle =
          closestPointOnTriangle(p, corner(mesh, found.triangle, 0),
                                 corner(mesh, found.triangle, 1), corner(mesh, found.triangle, 2));
      ASSERT_NEAR((onTriangle - p).norm(), found.distance, 1e-12);
    }
  }
}

// hasTriangleWithin(p, r) must agree with closest(p).distance <= r bit for bit, including at
// r equal to that distance and one rounding step either side of it.
TEST(TriangleBvh, HasTriangleWithinAgreesWithClosest) {
  for (const auto& [name, mesh] : closedShapes()) {
    SCOPED_TRACE(name);
    const TriangleBvh bvh(mesh);
    for (const Vec3& p : queryPoints(mesh, 300, 5)) {
      const double d = bvh.closest(p).distance;
      for (const double r : {0.0, 0.5 * d, std::nextafter(d, 0.0), d,
                             std::nextafter(d, std::numeric_limits<double>::infinity()), 2.0 * d}) {
        ASSERT_EQ(bvh.hasTriangleWithin(p, r), d <= r) << "r = " << r << ", distance " << d;
      }
    }
  }
}

TEST(TriangleBvh, ClosestOfASurfacePointIsItself) {
  const TriangleMesh mesh = makeTorus(1.0, 0.3, 24, 12);
  const TriangleBvh bvh(mesh);
  for (const Vec3& v : mesh.vertices) EXPECT_EQ(bvh.closest(v).distance, 0.0);
}

TEST(TriangleBvh, ContainsMatchesWindingNumber) {
  for (const auto& [name, mesh] : closedShapes()) {
    SCOPED_TRACE(name);
    const TriangleBvh bvh(mesh);
    std::size_t inside = 0, outside = 0;
    for (const Vec3& p : queryPoints(mesh, 1500, 5)) {
      const double winding = windingNumber(mesh, p);
      ASSERT_NEAR(winding, std::round(winding), 1e-6) << p.transpose();
      const bool expected = std::lround(winding) != 0;
      ASSERT_EQ(bvh.contains(p), expected) << p.transpose() << " winding " << winding;
      ASSERT_EQ(bvh.containsInClosedMesh(p), expected) << p.transpose() << " winding " << winding;
      ++(expected ? inside : outside);
    }
    EXPECT_GT(inside, 300u);
    EXPECT_GT(outside, 300u);
  }
}

TEST(TriangleBvh, ContainsRetriesRaysThroughEdgesAndVertices) {
  // Points from which one of the first rays passes exactly through a lattice point of a box:
  // a vertex, an edge point or a face point where triangles meet.
  const TriangleMesh box = makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1), 2);
  const TriangleBvh bvh(box);
  const auto directions = TriangleBvh::insideTestDirections();
  std::size_t checked = 0, inside = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    for (const Vec3& target : box.vertices) {
      for (const double distance : {0.3, 0.9, 1.7, 2.5}) {
        const Vec3 p = target - distance * directions[k];
        const double winding = windingNumber(box, p);
        if (std::abs(winding - std::round(winding)) > 1e-9) continue;  // on the surface
        EXPECT_EQ(bvh.contains(p), std::lround(winding) != 0) << p.transpose();
        EXPECT_EQ(bvh.containsInClosedMesh(p), std::lround(winding) != 0) << p.transpose();
        ++checked;
        inside += std::lround(winding) != 0 ? 1 : 0;
      }
    }
  }
  EXPECT_GT(checked, 200u);
  EXPECT_GT(inside, 50u);
}

TEST(TriangleBvh, SurfacePointsCountAsInside) {
  const TriangleMesh box = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1), 2);
  const TriangleBvh bvh(box);
  for (const Vec3& v : box.vertices) {
    EXPECT_TRUE(bvh.contains(v)) << v.transpose();
    EXPECT_TRUE(bvh.containsInClosedMesh(v)) << v.transpose();
  }
  for (const auto& test : {&TriangleBvh::contains, &TriangleBvh::containsInClosedMesh}) {
    EXPECT_TRUE((bvh.*test)(Vec3(0.3, 0.7, 1.0)));
    EXPECT_FALSE((bvh.*test)(Vec3(0.3, 0.7, 1.0 + 1e-9)));
    EXPECT_TRUE((bvh.*test)(Vec3(0.3, 0.7, 1.0 - 1e-9)));
  }
}

TEST(TriangleBvh, InsideTestDirectionsAreUnitAndIrregular) {
  const auto directions = TriangleBvh::insideTestDirections();
  ASSERT_GE(directions.size(), 3u);
  for (const Vec3& d : directions) {
    EXPECT_NEAR(d.norm(), 1.0, 1e-15);
    EXPECT_GT(d.cwiseAbs().minCoeff(), 0.1);  // no ray runs along a coordinate plane
  }
}

TEST(TriangleBvh, RejectsUnusableMeshes) {
  const auto message = [](const TriangleMesh& mesh) {
    try {
      const TriangleBvh bvh(mesh);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(TriangleMesh{}), "mesh has no triangles");
  TriangleMesh badIndex = makeBox(Vec3::Zero(), Vec3::Ones());
  badIndex.triangles[5][1] = 8;
  EXPECT_EQ(message(badIndex), "triangle 5 uses vertex 8 but the mesh has 8 vertices");
  TriangleMesh notFinite = makeBox(Vec3::Zero(), Vec3::Ones());
  notFinite.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(notFinite), "vertex 3 has a non-finite coordinate");
}

TEST(SegmentIntersectsTriangle, ClosedTest) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_TRUE(segmentIntersectsTriangle(Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vec3(1.5, 1.5, -1), Vec3(1.5, 1.5, 1), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vec3(0.5, 0.5, 0.1), Vec3(0.5, 0.5, 1), a, b, c));
  EXPECT_TRUE(segmentIntersectsTriangle(Vec3(0.5, 0.5, 0), Vec3(0.5, 0.5, 1), a, b, c));
  EXPECT_TRUE(segmentIntersectsTriangle(Vec3(1, 1, -1), Vec3(1, 1, 1), a, b, c));  // on an edge
  EXPECT_TRUE(segmentIntersectsTriangle(Vec3(-1, 1, 0), Vec3(3, 1, 0), a, b, c));  // coplanar
  EXPECT_FALSE(segmentIntersectsTriangle(Vec3(-1, 3, 0), Vec3(3, 3, 0), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), a, b, 2 * b));
}

TEST(TrianglesIntersect, KnownConfigurations) {
  const Vec3 a0(0, 0, 0), a1(2, 0, 0), a2(0, 2, 0);
  const auto both = [&](const Vec3& b0, const Vec3& b1, const Vec3& b2) {
    const bool forward = trianglesIntersect(a0, a1, a2, b0, b1, b2);
    EXPECT_EQ(forward, trianglesIntersect(b0, b1, b2, a0, a1, a2));
    return forward;
  };
  EXPECT_TRUE(both(Vec3(0.5, 0.5, -1), Vec3(0.6, 0.5, 1), Vec3(0.5, 0.6, 1)));  // pierces
  EXPECT_FALSE(both(Vec3(0.5, 0.5, 1), Vec3(0.6, 0.5, 2), Vec3(0.5, 0.6, 2)));  // above
  EXPECT_TRUE(both(Vec3(0.5, 0.5, 0), Vec3(0.6, 0.5, 2), Vec3(0.5, 0.6, 2)));   // touches
  EXPECT_FALSE(both(Vec3(0.5, 0.5, 1e-6), Vec3(0.6, 0.5, 2), Vec3(0.5, 0.6, 2)));
  EXPECT_TRUE(both(Vec3(1, -1, -1), Vec3(1, -1, 1), Vec3(1, 1, 0)));       // crosses an edge region
  EXPECT_TRUE(both(Vec3(0.5, 0.5, 0), Vec3(3, 0.5, 0), Vec3(0.5, 3, 0)));  // coplanar overlap
  EXPECT_TRUE(both(Vec3(0.2, 0.2, 0), Vec3(0.4, 0.2, 0), Vec3(0.2, 0.4, 0)));    // coplanar inside
  EXPECT_TRUE(both(Vec3(-1, -1, 0), Vec3(5, -1, 0), Vec3(-1, 5, 0)));            // coplanar around
  EXPECT_FALSE(both(Vec3(3, 3, 0), Vec3(4, 3, 0), Vec3(3, 4, 0)));               // coplanar apart
  EXPECT_FALSE(both(Vec3(0.5, 0.5, -1), Vec3(0.6, 0.5, 1), Vec3(0.7, 0.5, 3)));  // zero area
}

TEST(TrianglesMeetBesideSharedVertex, FindsFoldsThroughTheVertex) {
  const Vec3 s(0, 0, 0), p1(1, 0, 0), q1(0, 1, 0);
  EXPECT_TRUE(trianglesMeetBesideSharedVertex(s, p1, q1, Vec3(0.5, 0.2, 1), Vec3(0.2, 0.5, -1)));
  EXPECT_FALSE(trianglesMeetBesideSharedVertex(s, p1, q1, Vec3(0.5, 0.2, 1), Vec3(0.2, 0.5, 2)));
  EXPECT_TRUE(trianglesMeetBesideSharedVertex(s, p1, q1, Vec3(0.5, 0.1, 0), Vec3(0.1, 0.5, 0)));
  EXPECT_FALSE(trianglesMeetBesideSharedVertex(s, p1, q1, Vec3(-1, 1, 0), Vec3(-1, 0, 0)));
  EXPECT_FALSE(trianglesMeetBesideSharedVertex(s, p1, q1, Vec3(0, -1, 0), Vec3(-1, -1, 0)));
}

TEST(TrianglesIntersect, ContactToleranceIsRelativeToTheLongestEdge) {
  for (const double scale : {1e-3, 1.0, 1e3}) {
    const Vec3 a0(0, 0, 0), a1(2 * scale, 0, 0), a2(0, 2 * scale, 0);
    const double tolerance = 1e-12 * (a2 - a1).norm();  // of the longest edge
    const auto apexAt = [&](double height) {
      return trianglesIntersect(a0, a1, a2, Vec3(0.5, 0.5, height) * scale,
                                Vec3(0.6 * scale, 0.5 * scale, scale),
                                Vec3(0.5 * scale, 0.6 * scale, scale));
    };
    EXPECT_TRUE(apexAt(0.0)) << scale;
    EXPECT_TRUE(apexAt(0.3 * tolerance / scale)) << scale;
    EXPECT_FALSE(apexAt(3 * tolerance / scale)) << scale;
    EXPECT_TRUE(apexAt(-3 * tolerance / scale)) << scale;  // pierces a little
  }
}

// Two nearly coplanar triangles 0.2 apart, from a CAD mesh: a0 lies on the line through b0 and b2,
// a2 is 3e-15 off b's plane. Ambiguous orientation signs once made the edge a2a0 count as meeting.
TEST(TrianglesIntersect, NearlyCoplanarTrianglesFarApartAreDisjoint) {
  const Vec3 a0(3.0801599999999998, 15.3644, -1.4746600000000001),
      a1(3.0256799999997308, 15.356299999999958, -1.5568300000004052),
      a2(2.9807757827301162, 15.364399999999993, -1.4746600000000427),
      b0(2.7820800000000001, 15.3644, -1.4746600000000001),
      b1(2.7386300000000001, 15.3558, -1.56138),
      b2(2.6827200000000002, 15.3644, -1.4746600000000001);
  EXPECT_FALSE(trianglesIntersect(a0, a1, a2, b0, b1, b2));
  EXPECT_FALSE(trianglesIntersect(b0, b1, b2, a0, a1, a2));
  EXPECT_FALSE(trianglesIntersect(a2, a0, a1, b2, b0, b1));
  // Slid along the line b0b2 until a0 lies on the edge b0b2, they touch.
  const Vec3 slide(-0.3, 0, 0);
  ASSERT_EQ((a0 + slide).tail<2>(), b0.tail<2>());
  EXPECT_TRUE(trianglesIntersect(a0 + slide, a1 + slide, a2 + slide, b0, b1, b2));
  EXPECT_TRUE(trianglesIntersect(b0, b1, b2, a0 + slide, a1 + slide, a2 + slide));
}

// Distance from segment pq to triangle abc by golden-section search along the segment (distance
// to a convex set is convex along a line): independent of the predicates' closed forms.
double segmentTriangleDistance(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                               const Vec3& c) {
  const auto distanceAt = [&](double s) {
    const Vec3 x = p + s * (q - p);
    return (closestPointOnTriangle(x, a, b, c) - x).norm();
  };
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = 0.0, hi = 1.0;
  double s1 = hi - ratio * (hi - lo), s2 = lo + ratio * (hi - lo);
  double d1 = distanceAt(s1), d2 = distanceAt(s2);
  for (int iteration = 0; iteration < 100; ++iteration) {
    if (d1 <= d2) {
      hi = s2;
      s2 = s1;
      d2 = d1;
      s1 = hi - ratio * (hi - lo);
      d1 = distanceAt(s1);
    } else {
      lo = s1;
      s1 = s2;
      d1 = d2;
      s2 = lo + ratio * (hi - lo);
      d2 = distanceAt(s2);
    }
  }
  return std::min({d1, d2, distanceAt(0.0), distanceAt(1.0)});
}

using Corners = std::array<Vec3, 3>;

// The distance between two triangles is that of an edge of one to the other.
double triangleDistance(const Corners& a, const Corners& b) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    best = std::min({best, segmentTriangleDistance(a[k], a[(k + 1) % 3], b[0], b[1], b[2]),
                     segmentTriangleDistance(b[k], b[(k + 1) % 3], a[0], a[1], a[2])});
  }
  return best;
}

double longestEdge(const Corners& t) {
  return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
}

std::string describe(std::initializer_list<Vec3> points) {
  std::string text;
  for (const Vec3& p : points) {
    text += fmt::format("({:.17g}, {:.17g}, {:.17g}) ", p.x(), p.y(), p.z());
  }
  return text;
}

// Random nearly coplanar shapes, where tolerant predicates go wrong: points of a plane far from
// the origin, each lifted off it by 0 or by +-10^[-15, -4]. Half the planes contain the x axis
// and snap the in-plane coordinates to a 1/8 grid, so that corners share coordinates and lie
// exactly on lines through other corners, as in CAD meshes; the other half are rotated at random.
class NearlyCoplanar {
 public:
  explicit NearlyCoplanar(std::uint64_t seed) : engine_(seed) {}

  void newPlane() {
    origin_ = Vec3(3.0, 15.36, -1.47) + 10.0 * Vec3(unit(), unit(), unit());
    grid_ = unit() < 0.5;
    const double angle = grid_ && unit() < 0.3 ? 0.0 : std::numbers::pi * unit();
    const Eigen::Matrix3d rotation =
        grid_ ? Eigen::AngleAxisd(angle, Vec3::UnitX()).toRotationMatrix()
              : Eigen::AngleAxisd(angle, Vec3(unit(), unit(), unit()).normalized())
                    .toRotationMatrix();
    u_ = rotation.col(0);
    v_ = rotation.col(1);
    normal_ = rotation.col(2);
  }

  // A point at in-plane coordinates (x, y), snapped to the grid for grid planes, then lifted.
  Vec3 point(double x, double y) {
    if (grid_) {
      x = std::round(8.0 * x) / 8.0;
      y = std::round(8.0 * y) / 8.0;
    }
    const double lift =
        unit() < 0.3 ? 0.0 : (unit() < 0.5 ? -1.0 : 1.0) * std::pow(10.0, -15.0 + 11.0 * unit());
    return origin_ + x * u_ + y * v_ + lift * normal_;
  }

  // A triangle of size 0.25 to 1.4 around in-plane (x, y), not thin: |normal| >= 0.01 * longest
  // edge^2.
  Corners triangle(double x, double y) {
    while (true) {
      const Corners t{point(x + unit() - 0.5, y + unit() - 0.5),
                      point(x + unit() - 0.5, y + unit() - 0.5),
                      point(x + unit() - 0.5, y + unit() - 0.5)};
      const double longest = longestEdge(t);
      if (longest >= 0.25 && (t[1] - t[0]).cross(t[2] - t[0]).norm() >= 0.01 * longest * longest) {
        return t;
      }
    }
  }

  double unit() { return unitDistribution_(engine_); }

 private:
  std::mt19937_64 engine_;
  std::uniform_real_distribution<double> unitDistribution_{0.0, 1.0};
  Vec3 origin_, u_, v_, normal_;
  bool grid_ = false;
};

// Answers of a contact predicate, for two orders of the same corners, checked against the
// reference distance: coming within 1e-12 of the size (the longest edge involved) counts as
// meeting, checked below 0.5e-12 clear of rounding, and a pair reported as meeting is never
// farther apart than 1.5e-12 of the size. In between, rounding may tip either answer.
struct AgreementTally {
  std::size_t contacts = 0, nearMisses = 0;  // answers "meet", and "apart" within 1e-4 * size

  ::testing::AssertionResult record(bool meet, bool meetReordered, double distance, double size) {
    contacts += meet ? 1 : 0;
    nearMisses += !meet && distance < 1e-4 * size ? 1 : 0;
    for (const bool answer : {meet, meetReordered}) {
      if (answer && distance > 1.5e-12 * size) {
        return ::testing::AssertionFailure() << "meet at distance " << distance / size << " * size";
      }
      if (!answer && distance <= 0.5e-12 * size) {
        return ::testing::AssertionFailure()
               << "apart at distance " << distance / size << " * size";
      }
    }
    return ::testing::AssertionSuccess();
  }
};

TEST(TrianglesIntersect, NearlyCoplanarAnswersAgreeWithTheDistance) {
  NearlyCoplanar shapes(21);
  AgreementTally tally;
  for (int trial = 0; trial < 5000; ++trial) {
    shapes.newPlane();
    const Corners a = shapes.triangle(0.0, 0.0);
    const Corners b = shapes.triangle(2.0 * shapes.unit() - 1.0, 2.0 * shapes.unit() - 1.0);
    const double size = std::max(longestEdge(a), longestEdge(b));
    const double distance = triangleDistance(a, b);
    ASSERT_TRUE(tally.record(trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2]),
                             trianglesIntersect(b[2], b[0], b[1], a[1], a[2], a[0]), distance,
                             size))
        << describe({a[0], a[1], a[2], b[0], b[1], b[2]});
  }
  EXPECT_GT(tally.contacts, 200u);
  EXPECT_GT(tally.nearMisses, 200u);
}

TEST(SegmentIntersectsTriangle, NearlyCoplanarAnswersAgreeWithTheDistance) {
  NearlyCoplanar shapes(22);
  AgreementTally tally;
  for (int trial = 0; trial < 10000; ++trial) {
    shapes.newPlane();
    const Corners t = shapes.triangle(0.0, 0.0);
    const Vec3 p = shapes.point(3.0 * shapes.unit() - 1.5, 3.0 * shapes.unit() - 1.5);
    const Vec3 q = shapes.point(3.0 * shapes.unit() - 1.5, 3.0 * shapes.unit() - 1.5);
    const double size = std::max(longestEdge(t), (q - p).norm());
    const double distance = segmentTriangleDistance(p, q, t[0], t[1], t[2]);
    ASSERT_TRUE(tally.record(segmentIntersectsTriangle(p, q, t[0], t[1], t[2]),
                             segmentIntersectsTriangle(q, p, t[1], t[2], t[0]), distance, size))
        << describe({p, q, t[0], t[1], t[2]});
  }
  EXPECT_GT(tally.contacts, 300u);
  EXPECT_GT(tally.nearMisses, 300u);
}

TEST(TrianglesMeetBesideSharedVertex, NearlyCoplanarAnswersAgreeWithTheDistance) {
  NearlyCoplanar shapes(23);
  AgreementTally tally;
  for (int trial = 0; trial < 10000; ++trial) {
    shapes.newPlane();
    const Corners first = shapes.triangle(0.0, 0.0);
    const Vec3& s = first[0];
    Corners second = shapes.triangle(0.0, 0.0);
    second[0] = s;
    const double size = std::max(longestEdge(first), longestEdge(second));
    if ((second[1] - s).cross(second[2] - s).norm() < 0.01 * size * size) continue;
    // Beside s the triangles can only meet along the edges opposite it.
    const double distance =
        std::min(segmentTriangleDistance(first[1], first[2], s, second[1], second[2]),
                 segmentTriangleDistance(second[1], second[2], s, first[1], first[2]));
    ASSERT_TRUE(
        tally.record(trianglesMeetBesideSharedVertex(s, first[1], first[2], second[1], second[2]),
                     trianglesMeetBesideSharedVertex(s, second[2], second[1], first[1], first[2]),
                     distance, size))
        << describe({s, first[1], first[2], second[1], second[2]});
  }
  EXPECT_GT(tally.contacts, 300u);
  EXPECT_GT(tally.nearMisses, 300u);
}

// General position exercises the fast separation certificate (an edge clearly on one side of the
// other triangle's plane) as well as clear crossings: every answer must agree with the distance.
TEST(TrianglesMeetBesideSharedVertex, GeneralPositionAnswersAgreeWithTheDistance) {
  std::mt19937_64 engine(24);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto point = [&](const Vec3& around, double scale) {
    return Vec3(around + scale * Vec3(unit(engine), unit(engine), unit(engine)));
  };
  AgreementTally tally;
  std::size_t apart = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 s = point(Vec3(3.0, -7.0, 11.0), 10.0);
    const double scale = std::pow(10.0, 2.0 * unit(engine));
    const Vec3 p1 = point(s, scale), q1 = point(s, scale), p2 = point(s, scale),
               q2 = point(s, scale);
    const double size = std::max(longestEdge({s, p1, q1}), longestEdge({s, p2, q2}));
    if ((p1 - s).cross(q1 - s).norm() < 0.01 * size * size ||
        (p2 - s).cross(q2 - s).norm() < 0.01 * size * size) {
      continue;
    }
    const double distance = std::min(segmentTriangleDistance(p1, q1, s, p2, q2),
                                     segmentTriangleDistance(p2, q2, s, p1, q1));
    const bool meet = trianglesMeetBesideSharedVertex(s, p1, q1, p2, q2);
    ASSERT_TRUE(
        tally.record(meet, trianglesMeetBesideSharedVertex(s, q2, p2, q1, p1), distance, size))
        << describe({s, p1, q1, p2, q2});
    apart += meet ? 0 : 1;
  }
  EXPECT_GT(tally.contacts, 2000u);
  EXPECT_GT(apart, 2000u);
}

TEST(TriangleBvh, IntersectsTriangleMatchesBruteForce) {
  const TriangleMesh mesh = makeTorus(1.0, 0.35, 32, 16);
  const TriangleBvh bvh(mesh);
  std::mt19937_64 engine(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t hits = 0, misses = 0, ignoredHits = 0;
  for (int trial = 0; trial < 800; ++trial) {
    const Vec3 center(1.6 * unit(engine), 1.6 * unit(engine), 0.5 * unit(engine));
    const double size = 0.05 + 0.5 * (unit(engine) + 1.0);
    const Vec3 a = center + size * Vec3(unit(engine), unit(engine), unit(engine));
    const Vec3 b = center + size * Vec3(unit(engine), unit(engine), unit(engine));
    const Vec3 c = center + size * Vec3(unit(engine), unit(engine), unit(engine));
    bool expected = false;
    for (std::size_t t = 0; t < mesh.triangles.size() && !expected; ++t) {
      expected =
          trianglesIntersect(a, b, c, corner(mesh, t, 0), corner(mesh, t, 1), corner(mesh, t, 2));
    }
    ASSERT_EQ(bvh.intersectsTriangle(a, b, c), expected);
    ++(expected ? hits : misses);
  }
  // A copy of a mesh triangle pushed slightly outward touches only its own neighbourhood.
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 7) {
    const Triangle& tri = mesh.triangles[t];
    const Vec3 lift = 1e-3 * (corner(mesh, t, 1) - corner(mesh, t, 0))
                                 .cross(corner(mesh, t, 2) - corner(mesh, t, 0))
                                 .normalized();
    const Vec3 a = 1.01 * corner(mesh, t, 0) + lift, b = 1.01 * corner(mesh, t, 1) + lift,
               c = 1.01 * corner(mesh, t, 2) + lift;
    const std::array<std::uint32_t, 3> ignore = tri;
    bool expected = false;
    for (std::size_t u = 0; u < mesh.triangles.size() && !expected; ++u) {
      const Triangle& other = mesh.triangles[u];
      if (std::ranges::any_of(
              other, [&](std::uint32_t id) { return std::ranges::count(ignore, id) > 0; })) {
        continue;
      }
      expected =
          trianglesIntersect(a, b, c, corner(mesh, u, 0), corner(mesh, u, 1), corner(mesh, u, 2));
    }
    ASSERT_EQ(bvh.intersectsTriangle(a, b, c, ignore), expected);
    ignoredHits += bvh.intersectsTriangle(a, b, c) ? 1 : 0;
  }
  EXPECT_GT(hits, 100u);
  EXPECT_GT(misses, 100u);
  EXPECT_GT(ignoredHits, 10u);  // without the ignore list the neighbourhood is found
}

TEST(TriangleBvh, OverlapQueryVisitsEveryOverlappingTriangle) {
  const TriangleMesh mesh = makeIcosphere(3);
  const TriangleBvh bvh(mesh);
  std::mt19937_64 engine(9);
  std::uniform_real_distribution<double> unit(-1.2, 1.2);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 p(unit(engine), unit(engine), unit(engine));
    const Vec3 lo = p - Vec3::Constant(0.2), hi = p + Vec3::Constant(0.2);
    std::set<std::uint32_t> visited;
    bvh.forEachTriangleOverlapping(lo, hi, [&](std::uint32_t t) {
      EXPECT_TRUE(visited.insert(t).second);
      return true;
    });
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Vec3 tLo = corner(mesh, t, 0).cwiseMin(corner(mesh, t, 1)).cwiseMin(corner(mesh, t, 2));
      const Vec3 tHi = corner(mesh, t, 0).cwiseMax(corner(mesh, t, 1)).cwiseMax(corner(mesh, t, 2));
      if ((tLo.array() <= hi.array()).all() && (lo.array() <= tHi.array()).all()) {
        ASSERT_TRUE(visited.contains(static_cast<std::uint32_t>(t)));
      }
    }
  }
}

}  // namespace
}  // namespace kaboum::geometry
