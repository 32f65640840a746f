// Repairs that make a read mesh usable by the bounding mesh algorithm, which assumes welded,
// consistently counter-clockwise oriented 2-manifolds (§3.1, §4.3 "Limitations").
#pragma once

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// Merges vertices at most `tolerance` apart (0 = exact duplicates only; -0 equals +0) and drops
// unreferenced vertices. Each vertex joins the first earlier kept vertex within tolerance; kept
// vertices stay in their original order. Hash-grid based, O(n) expected.
void weldVertices(TriangleMesh& mesh, double tolerance = 0.0);

// Drops vertices no triangle uses, keeping the order of the others.
void removeUnreferencedVertices(TriangleMesh& mesh);

// Makes triangle orientation consistent within each edge-manifold component (BFS flipping) and
// outward (positive signed volume) for closed components; an open component keeps the orientation
// most of its triangles had. Returns false when a component cannot be oriented consistently
// (non-orientable / touches a non-manifold edge), leaving that component unchanged.
bool repairOrientation(TriangleMesh& mesh);

// Prepares a mesh for single-sided approximation: consistent orientation where it is not (via
// repairOrientation), closed components outward, and an open mesh flipped as a whole when its
// signed volume (measured as if its holes were capped) is negative. Returns false when the mesh
// cannot be oriented consistently; sets `changed` when triangles were flipped.
bool orientOutward(TriangleMesh& mesh, bool& changed);

}  // namespace kaboum::geometry
