// Internal phase of the bounding mesh (thesis Algorithm 2, "contract the edge and update the costs
// around the new vertex", with the quadric merge of §4.3.3): the checks a contraction must pass to
// keep the mesh manifold, well shaped and free of crossings, and its execution.
#pragma once

#include <cstdint>
#include <vector>

#include "kaboum/geometry/bounding_mesh_costs.hpp"
#include "kaboum/geometry/bounding_mesh_guard.hpp"
#include "kaboum/geometry/bounding_mesh_queue.hpp"
#include "kaboum/geometry/bounding_mesh_topology.hpp"

namespace kaboum::geometry {

enum class ContractionOutcome {
  Done,
  Topology,  // refused: the mesh would stop being manifold or keep a vertex of valence 2
  Geometry,  // refused: a new triangle would be degenerate or turned over
  Crossing,  // refused: the new fan would cross the mesh
};

// The fans at the ends of the edge being contracted (fanA: at a; after the contraction, the new
// fan) and the new vertex's neighbours: scratch reused so the main loop does not allocate.
struct CollapseFans {
  std::vector<std::uint32_t> fanA, fanB, neighbours;
};

// Contracts Solved edge e (its end b merges into a, which moves to the edge's contraction point)
// unless that would break the mesh's topology or geometry or make the new fan cross the mesh; then
// updates the planes, indexes and queue keys it changed.
ContractionOutcome contractEdge(ContractionMesh& mesh, ContractionCosts& costs,
                                CrossingGuard& guard, ContractionQueue& queue, CollapseFans& fans,
                                std::uint32_t e);

}  // namespace kaboum::geometry
