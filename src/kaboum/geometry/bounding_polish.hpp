// A finishing pass for bounding meshes: moves vertices and flips edges to lower both one-sided
// Hausdorff distances to the original while keeping the mesh on its side of it (§4.2's guarantee).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "kaboum/geometry/bound_side.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

struct PolishOptions {
  BoundSide side = BoundSide::Outer;
  // Sweeps over all vertices and edges. The first `maxSweeps` accept a change only when it lowers
  // the largest distance around it; the next `sumSweeps` accept one that lowers the sum of fourth
  // powers of the distances around it without raising the largest. A sweep that changes nothing
  // ends its phase.
  int maxSweeps = 6, sumSweeps = 2;
  // Random original samples (besides its vertices and edge midpoints) that score the
  // original→result distance; the result→original side uses 7 points per result triangle.
  std::size_t samples = 20000;
  // After the sweeps, up to this many relocations: split the result triangle at the worst point
  // of either distance, sweep around the new vertex, collapse the interior edge whose collapse
  // leaves the smallest largest distance around it, and sweep around that; kept only when
  // neither largest distance rises and one drops (result→original judged on 45 grid points per
  // triangle). The vertex count stays the same.
  int relocations = 0;
  std::uint64_t seed = 7;
  std::function<void(double)> progress;  // fraction of the sweeps done (0..1)
};

struct PolishStats {
  std::size_t moves = 0, flips = 0;  // accepted vertex moves and edge flips
  std::size_t relocations = 0;       // kept relocations
  double seconds = 0.0;
};

// Polishes `result`, a bounding mesh of `original` on side `options.side` (as simplifyBounding
// returns it). A vertex moves from p to p' only when no original triangle meets the tetrahedra
// (a, b, p, p') over the edges (a, b) of its link, and an edge (a, b) flips to (c, d) only when no
// original triangle meets the tetrahedron (a, b, c, d): the surface changes only inside those
// tetrahedra, so every original point keeps its winding number with respect to the result and an
// outer result still contains the original (an inner one stays inside it). Changes also keep
// triangles unflipped and non-degenerate, the mesh edge-manifold, and add no self-intersection.
// Border and non-manifold vertices of the result stay where they are. Deterministic.
PolishStats polishBoundingMesh(const TriangleMesh& original, TriangleMesh& result,
                               const PolishOptions& options);

}  // namespace kaboum::geometry
