#include "kaboum/testing/polytope_pairs.hpp"

#include <algorithm>
#include <random>

namespace kaboum::testing {

using namespace kaboum::geometry;

namespace {

double uniform(std::mt19937_64& rng, double low, double high) {
  return low + (high - low) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}

Vec3 unitVector(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  for (;;) {
    const Vec3 v(normal(rng), normal(rng), normal(rng));
    if (v.squaredNorm() > 1e-12) return v.normalized();
  }
}

Eigen::Quaterniond randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  return q;
}

std::vector<Vec3> ellipsoidPoints(std::mt19937_64& rng, int count) {
  const Vec3 axes(uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5), uniform(rng, 0.5, 1.5));
  std::vector<Vec3> points;
  Vec3 centroid = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    points.push_back(unitVector(rng).cwiseProduct(axes));
    centroid += points.back();
  }
  centroid /= count;
  for (Vec3& p : points) p -= centroid;
  return points;
}

// Mean over random directions of the largest extent from the centroid (half the mean width).
double meanHalfWidth(std::mt19937_64& rng, const std::vector<Vec3>& points) {
  constexpr int kDirections = 64;
  double sum = 0.0;
  for (int i = 0; i < kDirections; ++i) {
    const Vec3 d = unitVector(rng);
    double extent = d.dot(points.front());
    for (const Vec3& p : points) extent = std::max(extent, d.dot(p));
    sum += extent;
  }
  return sum / kDirections;
}

std::vector<Vec3> transformed(const std::vector<Vec3>& points, const Eigen::Isometry3d& pose) {
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back(pose * p);
  return out;
}

}  // namespace

std::vector<Vec3> PolytopePair::worldA() const {
  return transformed(localA, poseA);
}
std::vector<Vec3> PolytopePair::worldB() const {
  return transformed(localB, poseB);
}

std::vector<PolytopePair> randomPolytopePairs(std::size_t count, int vertexCount,
                                              std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<PolytopePair> pairs(count);
  for (PolytopePair& pair : pairs) {
    pair.localA = ellipsoidPoints(rng, vertexCount);
    pair.localB = ellipsoidPoints(rng, vertexCount);
    const Vec3 centerA(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    pair.poseA.linear() = randomRotation(rng).toRotationMatrix();
    pair.poseA.translation() = centerA;
    pair.poseB.linear() = randomRotation(rng).toRotationMatrix();
    // Contact happens at a center distance of about the sum of the half widths.
    const double reach = meanHalfWidth(rng, pair.localA) + meanHalfWidth(rng, pair.localB);
    pair.poseB.translation() = centerA + uniform(rng, 0.0, reach / 0.45) * unitVector(rng);
  }
  return pairs;
}

}  // namespace kaboum::testing
