// Exact (slow) reference for convex–convex queries: the qhull hull of the Minkowski difference
// A ⊕ (−B), against which the narrow phase and the reference libraries are verified.
#pragma once

#include <span>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;

struct MinkowskiReference {
  // The separation distance when positive; minus the penetration depth (distance from the origin
  // to the boundary of A ⊕ (−B)) when overlapping.
  double signedDistance = 0.0;
  // When separated, the point of A ⊕ (−B) closest to the origin (pA − pB for closest points).
  Vec3 closestPoint = Vec3::Zero();
};

// The reference for the convex hulls of `a` and `b` (world coordinates). Computes a hull of
// |a|·|b| points: milliseconds, for tests and correctness counts only. Throws InputError when the
// difference set has no volume.
MinkowskiReference minkowskiReference(std::span<const Vec3> a, std::span<const Vec3> b);

}  // namespace kaboum::testing
