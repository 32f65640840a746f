// Convex hulls of point sets, computed with qhull: the polytope every convex piece, swept segment
// and exact collision reference in kaboum is built from.
#pragma once

#include <span>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// A facet plane: unit outward normal n and offset d, the hull being { x : n.x <= d }.
struct HullPlane {
  Vec3 normal;
  double offset = 0.0;
};

// The hull as a closed, outward-oriented triangle mesh over the hull's own vertices (a subset of
// the input points), and one plane per facet (coplanar triangles are merged into one facet).
struct ConvexHull {
  TriangleMesh mesh;
  std::vector<HullPlane> planes;
  // Index into the input points of every vertex of `mesh`.
  std::vector<std::uint32_t> inputIndex;
};

// Throws InputError when fewer than four points are given, a point is not finite, or all points
// are coplanar (the hull has no volume). `what` names the points in that message.
ConvexHull convexHull(std::span<const Vec3> points, const std::string& what = "points");

}  // namespace kaboum::geometry
