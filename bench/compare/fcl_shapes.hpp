// Kaboum geometry handed to FCL for the side-by-side benchmarks (FCL is a reference, never used
// by the library itself).
#pragma once

#include <fcl/geometry/shape/convex.h>

#include <memory>
#include <span>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;

// The convex hull of `points` as an fcl::Convexd (same vertices and facets kaboum uses).
std::shared_ptr<fcl::Convexd> fclConvex(std::span<const Vec3> points);

}  // namespace kaboum::cli
