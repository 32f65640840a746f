// Random convex obstacles in a region, the scene of the full-robot benchmarks (issue 3, "a scene of
// about 50 convex obstacles") and of tests; deterministic for a seed.
#pragma once

#include <cstdint>
#include <random>

#include "kaboum/collision/scene.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;
using namespace kaboum::collision;

// `count` obstacles, each the hull of `vertices` random points within ±halfSize of its origin
// (the body frame), placed uniformly in `region` with a uniform random orientation.
CollisionScene randomObstacleScene(const Aabb& region, int count, int vertices, double halfSize,
                                   std::uint64_t seed);

// A uniform random rotation (Shoemake's method on three uniform numbers).
Eigen::Quaterniond uniformRotation(std::mt19937_64& rng);

}  // namespace kaboum::testing
