// Triangle–triangle intersection predicates that tolerate shared vertices, for keeping meshes free
// of self-intersections while they are edited.
#pragma once

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum {

// True if segment pq meets triangle abc (touching counts; a segment lying in the triangle's plane
// does not).
bool segmentMeetsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                          const Vec3& c);

// True if triangles t and u (given by corner positions and vertex ids) intersect anywhere other
// than at the vertices they share. Triangles sharing an edge are reported as not intersecting
// (folds across a shared edge are caught by orientation checks instead); coplanar overlap is not
// detected.
bool trianglesIntersect(const std::array<Vec3, 3>& t, const Triangle& tIds,
                        const std::array<Vec3, 3>& u, const Triangle& uIds);

}  // namespace kaboum
