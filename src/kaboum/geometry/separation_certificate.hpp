// A cheap, conservative "these two mesh triangles do not meet" certificate for the bounding mesh's
// self-intersection guard (thesis §4.3; docs/bounding-mesh.md, "No self-intersections, no folds"):
// plane heights from cached unit normals, checked before the exact predicate
// meshTrianglesIntersect.
#pragma once

#include <array>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// A mesh triangle with the plane data its owner keeps up to date, so no pair recomputes it.
struct PlanedTriangle {
  std::array<const Vec3*, 3> corners;
  Triangle ids;
  Vec3 unitNormal;     // direction of (c1 - c0) × (c2 - c0); anything when crossLength is tiny
  double crossLength;  // |(c1 - c0) × (c2 - c0)|, twice the area (a slightly rounded value is fine)
  double sizeSquared;  // at least the longest edge squared, e.g. the diagonal of its box squared
};

// True only when meshTrianglesIntersect(t, u) is certain to answer false. Both must be well shaped
// (crossLength ≥ 1.01e-4 size²). Triangles sharing an edge are ignored by the predicate. For
// triangles sharing one vertex the predicate tests each far edge against the other triangle; an
// edge is cleared when both its ends lie beyond m = 1.01e-6 size on one side of the other plane
// (the predicate's own certificate, with 1% slack for the different rounding of cached normals), or
// when it is steep to that plane (end heights differ by ≥ 1% of its length) and crosses it more
// than 200 m outside the other triangle's angle at the shared vertex: then it stays farther than m
// from that triangle, far beyond the predicate's contact tolerance (1e-12 size) and rounding.
// Disjoint triangles are cleared when one lies beyond 1e-4 size on one side of the other's plane,
// where its determinant signs are exact beyond ~4e-10 size³ while |det| = |normal| · height ≥ 1e-8
// size³; those farther apart than 2 size (first corners) are left to the predicate. False means
// "not certain", not "they meet".
bool certainlyApart(const PlanedTriangle& t, const PlanedTriangle& u);

}  // namespace kaboum::geometry
