// The bounding mesh algorithm (thesis §4.3, Algorithm 2): greedy bounded edge contraction that
// simplifies a closed mesh to an outer (enclosing) or inner (enclosed) single-sided approximation.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>

#include "kaboum/geometry/bound_side.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/geometry/quadric.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// The edge-contraction cost of §4.3.5.
enum class ContractionCost {
  Planes,     // E_planes (Eq. 4.4): squared distances to the planes around the edge
  Triangles,  // E_triangles (Appendix A.2): squared distances to triangle centroids; keeps convex
              // meshes convex
};

struct BoundingMeshOptions {
  BoundSide side = BoundSide::Outer;
  std::size_t targetVertices = 0;  // stop when this many vertices remain (0: no count target)
  // Stop contracting edges whose quadric error, as a distance, exceeds this (Algorithm 2's ε).
  double maxError = std::numeric_limits<double>::infinity();
  ContractionCost cost = ContractionCost::Planes;
  QuadricMerge merge = QuadricMerge::Constant;
  double mergeLength = 0.0;  // l of Eq. 4.7 for QuadricMerge::Full; 0 → 1% of the diagonal
  // Solve an edge's constrained problem only when it reaches the top of the queue. The result is
  // identical either way; false (solve every queued edge at once) is the reference it is tested on.
  bool lazyQueue = true;
  // Finish with polishBoundingMesh (bounding_polish.hpp): lower both Hausdorff distances by moving
  // vertices and flipping edges, keeping the side. Leave it off for convex pieces: it does not
  // keep convexity.
  bool polish = false;
  int polishRelocations = 10;  // PolishOptions::relocations of the polish pass
  // Called now and then with the fraction of the work done (0..1): `progress` for Algorithm 2,
  // `polishProgress` for the polish pass.
  std::function<void(double)> progress, polishProgress;
};

struct BoundingMeshStats {
  std::size_t inputVertices = 0, outputVertices = 0, contractions = 0;
  std::size_t lockedVertices = 0;  // on borders or non-manifold edges/vertices: never moved
  std::size_t rejectedInfeasible = 0, rejectedTopology = 0, rejectedGeometry = 0;
  std::size_t rejectedCrossing = 0;  // the new triangles would have crossed the mesh
  double quadricError = 0.0;  // largest quadric error (as a distance) of an executed contraction
  // Time in Algorithm 2 on the way to this result (for a distance search: the runs it built on).
  double seconds = 0.0;
  std::size_t polishMoves = 0, polishFlips = 0;  // changes made by the polish pass
  std::size_t polishRelocations = 0;             // relocations it kept
  double polishSeconds = 0.0;                    // its time (not part of `seconds`)
  int runs = 1;            // runs of Algorithm 2 (more than one when searching for a distance)
  std::string stopReason;  // "vertex target reached", or why no further contraction was valid
};

struct BoundingMeshResult {
  TriangleMesh mesh;
  BoundingMeshStats stats;
};

// Simplifies `input`, which must be welded and consistently oriented with outward normals (see
// repairOrientation). Border edges of open meshes and non-manifold parts are kept fixed; all
// components are kept. Every executed contraction keeps the result closed, edge-manifold, oriented,
// free of degenerate and flipped faces and of self-intersections, and on its side of the previous
// mesh. Throws InputError if
// the orientation is inconsistent.
BoundingMeshResult simplifyBounding(const TriangleMesh& input, const BoundingMeshOptions& options);

// Simplifies as far as the measured Hausdorff distance allows: the result's distance to `input`, in
// both directions on dense samples (every vertex, edge midpoint and `samples` random points), stays
// within `epsilon`. The quadric error of Algorithm 2 only estimates that distance (it overestimates
// it on smooth meshes), so the quadric-error limit is searched: ε first, then bisection on a
// multiple of ε, at most `maxRuns` runs of Algorithm 2, each going on from where the largest
// limit known to fit stopped instead of from the input. `options.targetVertices` still applies;
// `options.maxError` is ignored. `measured` receives the distances of the returned result.
BoundingMeshResult simplifyBoundingWithin(const TriangleMesh& input, BoundingMeshOptions options,
                                          double epsilon, std::size_t samples,
                                          HausdorffReport& measured, int maxRuns = 7);

}  // namespace kaboum::geometry
