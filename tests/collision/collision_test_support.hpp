// Shared helpers of the collision tests: random convex bodies and poses, the exact distance
// between posed bodies (minkowskiReference over all piece pairs) as the reference, and the KR5.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "kaboum/collision/body.hpp"
#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/minkowski_reference.hpp"
#include "kaboum/testing/robot_collision_models.hpp"

namespace kaboum::collision::test {

using namespace kaboum::kinematics;
using namespace kaboum::testing;

inline const std::string kKr5 = kaboum::testing::kr5Urdf();

inline Vec3 randomPoint(std::mt19937_64& rng, double halfWidth) {
  return halfWidth *
         Vec3(2 * uniformUnit(rng) - 1, 2 * uniformUnit(rng) - 1, 2 * uniformUnit(rng) - 1);
}

// Uniform rotation (Shoemake) with a translation in the cube [-halfWidth, halfWidth]^3.
inline Pose randomPose(std::mt19937_64& rng, double halfWidth) {
  const double u1 = uniformUnit(rng), u2 = uniformUnit(rng), u3 = uniformUnit(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1), tau = 2 * std::numbers::pi;
  Pose pose(Eigen::Quaterniond(b * std::cos(tau * u3), a * std::sin(tau * u2),
                               a * std::cos(tau * u2), b * std::sin(tau * u3)));
  pose.translation() = randomPoint(rng, halfWidth);
  return pose;
}

// `count` random convex sets of `points` points, each within `size` of a random centre.
inline std::vector<std::vector<Vec3>> randomConvexSets(std::mt19937_64& rng, int count, int points,
                                                       double size) {
  std::vector<std::vector<Vec3>> sets(static_cast<std::size_t>(count));
  for (auto& set : sets) {
    const Vec3 centre = randomPoint(rng, 2 * size);
    for (int i = 0; i < points; ++i) set.push_back(centre + randomPoint(rng, size));
  }
  return sets;
}

inline std::vector<Vec3> boxCorners(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> corners;
  for (int c = 0; c < 8; ++c) {
    corners.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                         (c & 4) ? hi.z() : lo.z());
  }
  return corners;
}

inline BodyPtr boxBody(const Vec3& lo, const Vec3& hi) {
  const std::vector<std::vector<Vec3>> sets{boxCorners(lo, hi)};
  return std::make_shared<const CollisionBody>(sets, "box");
}

// Exact distance between two posed bodies: the smallest over all piece pairs.
inline double exactDistance(const CollisionBody& a, const Pose& poseA, const CollisionBody& b,
                            const Pose& poseB) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.pieceCount(); ++i) {
    std::vector<Vec3> pa;
    for (const Vec3& v : a.piece(i).vertices()) pa.push_back(poseA * v);
    for (std::size_t j = 0; j < b.pieceCount(); ++j) {
      std::vector<Vec3> pb;
      for (const Vec3& v : b.piece(j).vertices()) pb.push_back(poseB * v);
      best = std::min(best, std::max(0.0, minkowskiReference(pa, pb).signedDistance));
    }
  }
  return best;
}

// The KR5 with the pair its hulls overlap in at home (forearm and palm around the wrist) allowed.
inline RobotCollisionModel kr5AllowingHomeOverlaps() {
  RobotCollisionModel robot = kaboum::testing::robotCollisionModel(kKr5);
  std::vector<Pose> poses(robot.model().links().size());
  robot.model().linkPoses(std::vector<double>(6, 0.0), poses);
  robot.allowPairsCollidingAt(poses);
  return robot;
}

}  // namespace kaboum::collision::test
