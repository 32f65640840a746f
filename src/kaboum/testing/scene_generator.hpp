// Random convex obstacles in a region, the scene of the full-robot benchmarks (about 50 convex
// obstacles) and of tests; deterministic for a seed.
#pragma once

#include <cstdint>
#include <random>

#include "kaboum/collision/scene.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;
using namespace kaboum::collision;

// `count` obstacles, each the hull of `vertices` random points within ±halfSize of its origin
// (the body frame), placed uniformly in `region` with a uniform random orientation. The last
// `movable` of them are movable objects (that pose is their initial placement), the others fixed.
CollisionScene randomObstacleScene(const Aabb& region, int count, int vertices, double halfSize,
                                   std::uint64_t seed, int movable = 0);

// A uniform random rotation (Shoemake's method on three uniform numbers).
Eigen::Quaterniond uniformRotation(std::mt19937_64& rng);

}  // namespace kaboum::testing
