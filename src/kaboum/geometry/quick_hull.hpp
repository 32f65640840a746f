// A quickhull for the many candidate pieces a decomposition ranks and samples but does not keep,
// several times faster than qhull on such point sets. Its result is not a bound: a point within
// `tolerance` of the hull may lie just outside it, so pieces that must contain their points are
// built with convexHull (qhull).
#pragma once

#include <optional>
#include <span>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// The convex hull of `points` as a closed, outward-oriented triangle mesh over some of them
// (coplanar triangles are not merged): a point at most `tolerance` above the hull's triangles
// counts as inside, and every hull vertex is checked to be at most 1000 tolerances above the
// plane of every triangle. Nothing when the points span no volume beyond the tolerance, or when
// nearly coplanar points defeat the tolerance (the surface would not be one closed convex sheet);
// the caller then falls back to convexHull. The points must be finite (convexHull checks them).
std::optional<TriangleMesh> quickHull(std::span<const Vec3> points, double tolerance);

}  // namespace kaboum::geometry
