// Property tests of the direction boxes behind the bounding mesh's angular index of high-valence
// stars: every direction of a triangle seen from a vertex lies in its box and in one of its pieces.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kaboum/geometry/star_directions.hpp"
#include "kaboum/geometry/triangle_grid.hpp"

namespace kaboum::geometry {
namespace {

bool inside(const Box3& box, const Vec3& d) {
  const Eigen::Vector3f f = d.cast<float>();
  return (box.lo.array() <= f.array()).all() && (f.array() <= box.hi.array()).all();
}

// A random point of the convex hull of the first `count` corners.
Vec3 hullPoint(const std::array<Vec3, 3>& corners, int count, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double w[3] = {unit(random), unit(random), count == 3 ? unit(random) : 0.0};
  if (random() % 4 == 0) w[random() % 3] = 0.0;  // on a side
  const double sum = w[0] + w[1] + w[2];
  if (sum == 0.0) return corners[0];
  return (w[0] * corners[0] + w[1] * corners[1] + w[2] * corners[2]) / sum;
}

TEST(StarDirections, BoxesAndPiecesContainEveryDirectionOfTheHull) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), logScale(-4.0, 2.0);
  int boxed = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double scale = std::pow(10.0, logScale(random));
    const Vec3 apex(coordinate(random), coordinate(random), coordinate(random));
    const Vec3 centre = apex + Vec3(coordinate(random), coordinate(random), coordinate(random));
    std::array<Vec3, 3> corners;
    for (Vec3& c : corners) {
      c = centre + scale * Vec3(coordinate(random), coordinate(random), coordinate(random));
    }
    const int count = trial % 3 == 0 ? 2 : 3;
    const std::optional<std::array<Vec3, 3>> directions = directionsFrom(
        apex, std::span<const Vec3>(corners.data(), static_cast<std::size_t>(count)));
    if (!directions) continue;
    ++boxed;
    const Box3 box = sphericalBox(*directions, count, 0.0);
    const double extent = 0.002 + 0.1 * std::abs(coordinate(random));
    for (int sample = 0; sample < 50; ++sample) {
      const Vec3 d = (hullPoint(corners, count, random) - apex).normalized();
      ASSERT_TRUE(inside(box, d)) << "trial " << trial;
      bool covered = false;
      forEachSphericalPiece(*directions, count, 0.0, extent,
                            [&](const Box3& piece, const std::array<Vec3, 3>&) {
                              covered = covered || inside(piece, d);
                            });
      ASSERT_TRUE(covered) << "trial " << trial;
    }
  }
  EXPECT_GT(boxed, 1000);  // most random triangles are boxed: the test exercises the boxes
}

TEST(StarDirections, PiecesAreAboutTheRequestedExtent) {
  // A sliver from straight below to a short edge on the rim, as the double cone's apex sees the
  // other cone's triangles.
  const std::array<Vec3, 3> corners{Vec3(0, 0, -1), Vec3(1, 0, 0),
                                    Vec3(std::cos(0.001), std::sin(0.001), 0)};
  const std::optional<std::array<Vec3, 3>> directions = directionsFrom(Vec3(0, 0, 1), corners);
  ASSERT_TRUE(directions);
  int pieces = 0;
  forEachSphericalPiece(*directions, 3, 0.0, 0.01,
                        [&](const Box3& box, const std::array<Vec3, 3>&) {
                          ++pieces;
                          EXPECT_LE((box.hi - box.lo).maxCoeff(), 0.012f);
                        });
  // The sliver is 45° (chord 0.765) long: 77 strips of two triangles, less the first's second.
  EXPECT_EQ(pieces, 2 * 77 - 1);
}

TEST(StarDirections, RefusesCornersAtTheApexAndSetsBeyondAHemisphere) {
  const Vec3 apex(1, 2, 3);
  const std::array<Vec3, 2> atApex{apex, Vec3(2, 2, 3)};
  EXPECT_FALSE(directionsFrom(apex, atApex));
  const std::array<Vec3, 2> opposite{Vec3(2, 2, 3), Vec3(0, 2.1, 3)};
  EXPECT_FALSE(directionsFrom(apex, opposite));
  const std::array<Vec3, 3> spread{Vec3(2, 2, 3), Vec3(1, 3, 3), Vec3(0, 1.5, 3)};
  EXPECT_FALSE(directionsFrom(apex, spread));
  const std::array<Vec3, 3> narrow{Vec3(2, 2, 3), Vec3(2, 2.5, 3), Vec3(2, 2, 3.5)};
  EXPECT_TRUE(directionsFrom(apex, narrow));
}

TEST(StarDirections, PointSegmentDistance) {
  const Vec3 a(0, 0, 0), b(2, 0, 0);
  EXPECT_DOUBLE_EQ(pointSegmentDistance(Vec3(1, 3, 0), a, b), 3.0);
  EXPECT_DOUBLE_EQ(pointSegmentDistance(Vec3(-3, 4, 0), a, b), 5.0);
  EXPECT_DOUBLE_EQ(pointSegmentDistance(Vec3(5, 0, 4), a, b), 5.0);
  EXPECT_DOUBLE_EQ(pointSegmentDistance(Vec3(1, 1, 1), a, a), std::sqrt(3.0));
}

TEST(TriangleGrid, AnyNearSeesExactlyTheOccupiedCells) {
  TriangleGrid grid(1.0, 16);
  const Box3 box = triangleBox(Vec3(0.2, 0.2, 0.2), Vec3(0.4, 0.4, 0.4), Vec3(0.3, 0.2, 0.4));
  const Box3 far = triangleBox(Vec3(5.2, 0.2, 0.2), Vec3(5.4, 0.4, 0.4), Vec3(5.3, 0.2, 0.4));
  EXPECT_FALSE(grid.anyNear(box));
  grid.insert(3, box);
  EXPECT_TRUE(grid.anyNear(box));
  EXPECT_FALSE(grid.anyNear(far));
  grid.remove(3, box);
  EXPECT_FALSE(grid.anyNear(box));
}

}  // namespace
}  // namespace kaboum::geometry
