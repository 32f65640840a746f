// Internal phase of the bounding mesh (thesis Algorithm 2): the state of one run of the greedy
// loop, as the plain structs of the other phases, and its steps; the distance search
// (bounding_mesh_search.cpp) goes on from copies of a run.
#pragma once

#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/bounding_mesh_collapse.hpp"
#include "kaboum/geometry/bounding_mesh_costs.hpp"
#include "kaboum/geometry/bounding_mesh_guard.hpp"
#include "kaboum/geometry/bounding_mesh_queue.hpp"
#include "kaboum/geometry/bounding_mesh_topology.hpp"

namespace kaboum::geometry {

struct BoundingRun {
  BoundingMeshOptions options;
  ContractionMesh mesh;
  ContractionCosts costs;
  CrossingGuard guard;
  ContractionQueue queue;
  CollapseFans fans;
  BoundingMeshStats stats;
  double worstCost = 0.0;  // largest exact cost of an executed contraction
  double seconds = 0.0;    // spent in startRun and advanceRun on the way to this state
};

// Builds the run's structures for `input` and queues every edge that may be contracted.
BoundingRun startRun(const TriangleMesh& input, const BoundingMeshOptions& options);
// Contracts edges, cheapest first, while the cheapest exact cost is within maxError (a distance)
// and the vertex target is not reached. Advancing again with a larger limit goes on from here:
// the edges the last limit stopped are queued again.
void advanceRun(BoundingRun& run, double maxError);
// The mesh as it is now, and the statistics since startRun.
BoundingMeshResult runResult(const BoundingRun& run);

// Applies the polish pass of options.polish to `result` and records it in its stats.
void polishResult(const TriangleMesh& input, const BoundingMeshOptions& options,
                  BoundingMeshResult& result);

}  // namespace kaboum::geometry
