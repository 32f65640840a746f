#include "kaboum/geometry/bounding_mesh.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kaboum/geometry/bounding_mesh_run.hpp"
#include "kaboum/geometry/bounding_polish.hpp"

namespace kaboum::geometry {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// The phases in order: adjacency, edge numbering and locks (topology), planes and quadrics (costs),
// the spatial hash and hub indexes (guard), then the queue of every edge whose ends may move.
BoundingRun startRun(const TriangleMesh& input, const BoundingMeshOptions& options) {
  const auto startTime = std::chrono::steady_clock::now();
  BoundingRun run;
  run.options = options;
  ContractionMesh& mesh = run.mesh;
  buildAdjacency(mesh, input);
  const std::vector<std::uint32_t> interiorEdges = classifyEdges(mesh);
  lockNonManifoldVertices(mesh);
  retireUnusedVertices(mesh);
  const double diagonal = liveDiagonal(mesh);
  fillCosts(run.costs, mesh, options, diagonal);
  buildGuard(run.guard, mesh, diagonal);
  allocateQueue(run.queue, mesh.edgeEnds.size(), mesh.triangles.size(), options.lazyQueue);
  for (const std::uint32_t e : interiorEdges) {
    if (!mesh.vertexLocked[mesh.edgeEnds[e][0]] && !mesh.vertexLocked[mesh.edgeEnds[e][1]]) {
      queueEdge(run.queue, mesh, run.costs, run.guard.hubs, e);
    }
  }
  run.stats.inputVertices = mesh.aliveVertices;
  run.stats.lockedVertices = lockedVertexCount(mesh);
  run.seconds += secondsSince(startTime);
  return run;
}

void advanceRun(BoundingRun& run, double maxError) {
  const auto startTime = std::chrono::steady_clock::now();
  ContractionMesh& mesh = run.mesh;
  ContractionQueue& queue = run.queue;
  Hubs& hubs = run.guard.hubs;
  BoundingMeshStats& stats = run.stats;
  for (const std::uint32_t e : queue.overLimit) {
    if (queue.state[e] == EdgeState::Parked) queueEdge(queue, mesh, run.costs, hubs, e);
  }
  queue.overLimit.clear();
  // Algorithm 2 with a lazy queue. Every queued edge's key is at most its exact cost (a minimum
  // over fewer planes is at most the minimum over all), and a popped edge is first given a tighter
  // bound, then solved if it is not yet: it is contracted only once it is the least by exact cost.
  // So edges are taken in exactly the order of a queue holding every exact cost
  // (options.lazyQueue = false), ties broken by edge id.
  run.options.maxError = maxError;
  const std::size_t target = run.options.targetVertices;
  const double maxCost = maxError * maxError;
  const std::size_t toRemove = mesh.aliveVertices > target ? mesh.aliveVertices - target : 0;
  const std::size_t contractionsBefore = stats.contractions;
  while (mesh.aliveVertices > target) {
    if (queue.heap.empty()) {
      if (!revisitParked(queue, mesh, run.costs, hubs)) break;
      continue;
    }
    const std::uint32_t e = queue.heap.top();
    const double cost = queue.heap.topKey();
    if (cost > maxCost) {  // every queued exact cost is at least this: none may be contracted
      park(queue, mesh, e);
      queue.overLimit.push_back(e);
      continue;
    }
    if (tightenKey(queue, mesh, run.costs, hubs, e)) continue;
    if (queue.state[e] == EdgeState::Infeasible) {
      ++stats.rejectedInfeasible;
      park(queue, mesh, e);
      continue;
    }
    coarsenGridIfSparse(run.guard, mesh);
    switch (contractEdge(mesh, run.costs, run.guard, queue, run.fans, e)) {
      case ContractionOutcome::Done: {
        ++stats.contractions;
        run.worstCost = std::max(run.worstCost, cost);
        const std::size_t made = stats.contractions - contractionsBefore;
        if (run.options.progress && made % 8192 == 0 && toRemove > 0) {
          run.options.progress(static_cast<double>(made) / static_cast<double>(toRemove));
        }
        break;
      }
      case ContractionOutcome::Topology:
        ++stats.rejectedTopology;
        park(queue, mesh, e);
        break;
      case ContractionOutcome::Geometry:
        ++stats.rejectedGeometry;
        park(queue, mesh, e);
        break;
      case ContractionOutcome::Crossing:
        ++stats.rejectedCrossing;
        park(queue, mesh, e);
        break;
    }
  }

  run.seconds += secondsSince(startTime);
  if (run.options.progress) run.options.progress(1.0);
}

BoundingMeshResult runResult(const BoundingRun& run) {
  BoundingMeshResult result;
  result.mesh = compactMesh(run.mesh);
  result.stats = run.stats;
  result.stats.outputVertices = result.mesh.vertices.size();
  result.stats.quadricError = std::sqrt(run.worstCost);
  if (run.mesh.aliveVertices <= run.options.targetVertices) {
    result.stats.stopReason = "vertex target reached";
  } else if (std::isfinite(run.options.maxError)) {
    result.stats.stopReason = "no contraction left within the error limit";
  } else {
    result.stats.stopReason = "no contraction left that keeps the mesh valid and bounding";
  }
  result.stats.seconds = run.seconds;
  return result;
}

// Applies the polish pass of options.polish to `result` and records it in its stats.
void polishResult(const TriangleMesh& input, const BoundingMeshOptions& options,
                  BoundingMeshResult& result) {
  PolishOptions polish;
  polish.side = options.side;
  polish.progress = options.polishProgress;
  polish.relocations = options.polishRelocations;
  const PolishStats stats = polishBoundingMesh(input, result.mesh, polish);
  result.stats.polishMoves = stats.moves;
  result.stats.polishFlips = stats.flips;
  result.stats.polishRelocations = stats.relocations;
  result.stats.polishSeconds = stats.seconds;
}

BoundingMeshResult simplifyBounding(const TriangleMesh& input, const BoundingMeshOptions& options) {
  BoundingRun run = startRun(input, options);
  advanceRun(run, options.maxError);
  BoundingMeshResult result = runResult(run);
  if (options.polish) polishResult(input, options, result);
  return result;
}

}  // namespace kaboum::geometry
