// Random convex polytope pairs, deterministic for a seed: the shared workload of the narrow-phase
// tests, `kaboum-compare collision` and bench_collision_pairs.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;

// Two polytopes in their local frames (every listed point is a hull vertex) and their poses.
struct PolytopePair {
  std::vector<Vec3> localA;
  std::vector<Vec3> localB;
  Eigen::Isometry3d poseA = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d poseB = Eigen::Isometry3d::Identity();

  [[nodiscard]] std::vector<Vec3> worldA() const;
  [[nodiscard]] std::vector<Vec3> worldB() const;
};

// `count` pairs of `vertexCount`-vertex polytopes (points on random ellipsoids with semi-axes in
// [0.5, 1.5], centroid at the local origin), randomly rotated, B's center at a uniformly random
// distance from A's in [0, the sum of their mean half widths / 0.45]: about 40% overlap.
std::vector<PolytopePair> randomPolytopePairs(std::size_t count, int vertexCount,
                                              std::uint64_t seed);

}  // namespace kaboum::testing
