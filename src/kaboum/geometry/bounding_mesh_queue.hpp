// Internal phase of the bounding mesh (thesis Algorithm 2's edge queue, each edge solved by
// Algorithm 1; docs/bounding-mesh.md, "Greedy loop"): the lazy queue that keys every candidate edge
// by a lower bound of its exact cost, tightens and solves it when it reaches the top, and parks
// the edges that cannot be contracted.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "kaboum/geometry/bounding_mesh_costs.hpp"
#include "kaboum/geometry/bounding_mesh_guard.hpp"
#include "kaboum/geometry/bounding_mesh_topology.hpp"
#include "kaboum/geometry/indexed_heap.hpp"

namespace kaboum::geometry {

// Where an edge stands in the greedy loop. A queued edge's key is its exact cost when Solved, and
// otherwise a lower bound of its cost.
enum class EdgeState : std::uint8_t {
  Off,         // not a candidate: an endpoint is locked, or the edge was contracted away
  Lower,       // queued by a cheap lower bound; tightened (Bounded) when it reaches the top
  Bounded,     // queued by a tighter lower bound; solved when it reaches the top
  Solved,      // queued by its exact cost; `points` holds its contraction point
  Infeasible,  // queued last (key +∞): no point satisfies the current planes
  Parked,      // rejected; retried when the queue runs empty if its neighbourhood changed
};

// The candidate edges by key, what each key rests on, and the parked edges.
struct ContractionQueue {
  // Solve an edge only when it reaches the top (false: solve every queued edge at once, the
  // reference the lazy order is tested on).
  bool lazy = true;
  IndexedMinHeap heap;  // queued edges by key, ties by edge id
  std::vector<EdgeState> state;
  std::vector<double> lowerBounds;
  std::vector<Vec3> points;                   // contraction point of a Solved edge
  std::vector<std::uint32_t> parkedVersions;  // versionSum(e) when it was parked
  std::vector<std::uint8_t> listed;           // in `parked`
  std::vector<std::uint8_t> raised;           // listed in the `raised` list of its hub ends
  // The last solve of each edge: its cost, when (contractionCount) and its active triangles
  // (activeKnown: with the edge's current quadric; the triangles are kept as hints afterwards).
  std::vector<double> solvedCosts;
  std::vector<std::uint32_t> solvedAt;
  std::vector<std::array<std::uint32_t, 3>> activeTriangles;
  std::vector<std::uint8_t> activeKnown;
  std::vector<std::uint32_t> triangleChangedAt;  // contractionCount when its plane last changed
  std::uint32_t contractionCount = 0;
  std::vector<std::uint32_t> parked;  // parked edges (and some no longer parked)
  // Edges parked because the error limit stopped them, queued again when the limit rises.
  std::vector<std::uint32_t> overLimit;
  // Scratch of solveEdge and tightenKey.
  std::vector<std::uint32_t> fanA, fanB;
  EdgeHalfSpaces halfSpaces;
};

// An empty queue for `edgeCount` edges, every one Off, over `triangleCount` triangles.
void allocateQueue(ContractionQueue& queue, std::size_t edgeCount, std::size_t triangleCount,
                   bool lazy);

// Queues edge e by the lower bound of its cost (lazy), or by its exact cost (eager reference).
void queueEdge(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
               Hubs& hubs, std::uint32_t e);
// Solves edge e's constrained problem (Algorithm 1) with the current planes and re-keys it by its
// exact cost.
void solveEdge(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
               Hubs& hubs, std::uint32_t e);
// Tightens the key of edge e, at the top of the queue, towards its exact cost: a Lower edge gets a
// tighter lower bound (Bounded) or, without one, its exact cost; a Bounded edge gets its exact
// cost. False, changing nothing, when the key is exact already (Solved or Infeasible).
bool tightenKey(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                Hubs& hubs, std::uint32_t e);
// Edge e's planes changed: its exact cost is no longer known, only a lower bound.
void invalidateEdge(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                    Hubs& hubs, std::uint32_t e);
// Invalidates the raised edges of hub v (all its edges but the Lower ones, whose key, their
// plane-independent lower bound, invalidateEdge leaves as it is) and forgets those no longer raised
// or no longer at the hub.
void invalidateRaised(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                      Hubs& hubs, std::uint32_t v);

// Takes edge e out of the queue until its neighbourhood changes.
void park(ContractionQueue& queue, const ContractionMesh& mesh, std::uint32_t e);
// Re-queues the parked edges whose neighbourhood changed since they were parked; false if none.
bool revisitParked(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                   Hubs& hubs);

}  // namespace kaboum::geometry
