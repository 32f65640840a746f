// Closing the border loops of open meshes, so that a bounding convex decomposition of the closed
// result contains the whole original surface (§4.4.2 needs a closed input; several robot links
// in the wild are open).
#pragma once

#include <cstddef>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

struct HoleFillingReport {
  std::size_t loops = 0;           // border loops closed
  std::size_t addedVertices = 0;   // one centroid per loop of more than three edges
  std::size_t addedTriangles = 0;  // cap triangles
};

// Closes `mesh` in the directed-edge sense: afterwards every directed edge (a, b) of a triangle is
// matched by as many edges (b, a). The original vertices and triangles are kept unchanged (in the
// same order, so the original surface is part of the result); cap triangles are appended. The
// unmatched directed edges form cycles (each triangle enters and leaves each of its corners once,
// and matched pairs do too); each cycle is traced and capped by a fan around its centroid, whose
// triangles run against the cycle (b, a, centroid), or by one triangle for a three-edge cycle.
// The cap of a strongly non-planar or non-convex hole may fold over itself; the result is then
// closed but not embedded, which the containment of the original surface does not depend on.
// Non-manifold edges need no special case: their surplus orientations are capped like borders.
// Expects a consistently oriented mesh (see orientOutward); deterministic.
HoleFillingReport fillHoles(TriangleMesh& mesh);

}  // namespace kaboum::geometry
