#include "kaboum/geometry/bounding_mesh_queue.hpp"

#include <algorithm>
#include <limits>

#include "kaboum/geometry/bounded_contraction.hpp"

namespace kaboum::geometry {
namespace {

// The edge's cost at x, computed as minimum + (x - x₀)ᵀA(x - x₀) for the unconstrained minimizer
// x₀: never below the lower bound, even in floating point.
double costAt(const EdgeProblem& p, const Vec3& x) {
  if (!p.start) return std::max(p.quadric(x), 0.0);
  const Vec3 step = x - *p.start;
  return std::max(p.minimum + std::max(step.dot(p.quadric.a * step), 0.0), 0.0);
}

// Edge e is now keyed above its lower bound: lists it at its hub ends.
void noteRaised(ContractionQueue& queue, const ContractionMesh& mesh, Hubs& hubs, std::uint32_t e) {
  if (queue.raised[e]) return;
  for (const std::uint32_t v : mesh.edgeEnds[e]) {
    if (!isHub(hubs, v)) continue;
    hubs.slots[hubs.slotOf[v]].raised.push_back(e);
    queue.raised[e] = 1;
  }
}

// A lower bound of edge e's exact cost after its planes changed. If none of the planes held as
// equalities at its last optimum changed since, that optimum is still the optimum over the planes
// that did not change (the KKT conditions involve only the active ones), and adding the changed
// planes can only raise it: its cost (less a relative 10⁻⁷ for rounding) bounds the new one.
// Otherwise the unconstrained minimum does. `fromLastCost` tells which.
double boundAfterChange(const ContractionQueue& queue, const ContractionMesh& mesh,
                        const ContractionCosts& costs, std::uint32_t e, bool& fromLastCost) {
  fromLastCost = false;
  if (!queue.activeKnown[e]) return queue.lowerBounds[e];
  for (const std::uint32_t t : queue.activeTriangles[e]) {
    if (t != kNoIndex &&
        (!mesh.triangleAlive[t] || queue.triangleChangedAt[t] > queue.solvedAt[e])) {
      return queue.lowerBounds[e];
    }
  }
  fromLastCost = true;
  return std::max(queue.lowerBounds[e], queue.solvedCosts[e] * (1.0 - 1e-7) - costs.costSlack);
}

// Raises Lower edge e's key to the minimum of its quadric over the half-spaces of the triangles
// active at its last solve that still bound it (alive, at one of its ends), from the dual in closed
// form (dualMinimumBound): a subset of its current planes, so at most its exact cost, less a
// relative 10⁻⁶ and 10⁻¹⁰ of the diagonal² for rounding. False when no such triangle exists.
bool tightenBound(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                  Hubs& hubs, std::uint32_t e) {
  const auto [a, b] = mesh.edgeEnds[e];
  std::array<std::uint32_t, 3> hints{};
  std::size_t hintCount = 0;
  for (const std::uint32_t t : queue.activeTriangles[e]) {
    if (t != kNoIndex && mesh.triangleAlive[t] &&
        (triangleHas(mesh, t, a) || triangleHas(mesh, t, b))) {
      hints[hintCount++] = t;
    }
  }
  if (hintCount == 0) return false;
  const EdgeProblem p = problemOf(costs, mesh, e);
  if (!p.start) return false;
  EdgeHalfSpaces& constraints = queue.halfSpaces;
  constraints.halfSpaces.clear();
  constraints.triangles.clear();
  for (std::size_t i = 0; i < hintCount; ++i) addHalfSpace(constraints, costs, hints[i], p.origin);
  const double minimum = dualMinimumBound(p.quadric, *p.start, p.minimum, constraints.halfSpaces,
                                          costs.tolerance, p.curvatureFloor);
  queue.state[e] = EdgeState::Bounded;
  if (!hubs.slots.empty()) noteRaised(queue, mesh, hubs, e);
  if (minimum > p.lowerBound) {
    const double bound = minimum * (1.0 - 1e-6) - costs.costSlack;
    if (bound > queue.heap.key(e)) queue.heap.set(e, bound);
  }
  return true;
}

}  // namespace

void allocateQueue(ContractionQueue& queue, std::size_t edgeCount, std::size_t triangleCount,
                   bool lazy) {
  queue.lazy = lazy;
  queue.heap.reset(edgeCount);
  queue.state.assign(edgeCount, EdgeState::Off);
  queue.lowerBounds.assign(edgeCount, 0.0);
  queue.points.resize(edgeCount);
  queue.parkedVersions.assign(edgeCount, 0);
  queue.listed.assign(edgeCount, 0);
  queue.raised.assign(edgeCount, 0);
  queue.solvedCosts.assign(edgeCount, 0.0);
  queue.solvedAt.assign(edgeCount, 0);
  queue.activeTriangles.assign(edgeCount, {kNoIndex, kNoIndex, kNoIndex});
  queue.activeKnown.assign(edgeCount, 0);
  queue.triangleChangedAt.assign(triangleCount, 0);
}

void queueEdge(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
               Hubs& hubs, std::uint32_t e) {
  queue.lowerBounds[e] = problemOf(costs, mesh, e).lowerBound;
  queue.state[e] = EdgeState::Lower;
  queue.raised[e] = 0;  // listed again at its (perhaps new) hub ends when raised
  queue.activeKnown[e] = 0;
  queue.heap.set(e, queue.lowerBounds[e]);
  if (!queue.lazy) solveEdge(queue, mesh, costs, hubs, e);
}

void solveEdge(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
               Hubs& hubs, std::uint32_t e) {
  const auto [a, b] = mesh.edgeEnds[e];
  gatherFan(mesh, a, queue.fanA);
  gatherFan(mesh, b, queue.fanB);
  const EdgeProblem p = problemOf(costs, mesh, e);
  EdgeHalfSpaces& constraints = queue.halfSpaces;
  constraints.halfSpaces.clear();
  constraints.triangles.clear();
  for (std::uint32_t t : queue.fanA) addHalfSpace(constraints, costs, t, p.origin);
  for (std::uint32_t t : queue.fanB) {
    if (!triangleHas(mesh, t, a)) addHalfSpace(constraints, costs, t, p.origin);
  }
  const ContractionPoint point =
      p.start ? solveContractionFrom(p.quadric, *p.start, constraints.halfSpaces, costs.tolerance)
              : solveContraction(p.quadric, constraints.halfSpaces, costs.tolerance);
  if (!hubs.slots.empty()) noteRaised(queue, mesh, hubs, e);
  if (!point.feasible) {
    queue.state[e] = EdgeState::Infeasible;
    queue.heap.set(e, std::numeric_limits<double>::infinity());
    return;
  }
  const double cost = costAt(p, point.position);
  queue.state[e] = EdgeState::Solved;
  queue.points[e] = p.origin + point.position;
  queue.heap.set(e, cost);
  queue.solvedCosts[e] = cost;
  queue.solvedAt[e] = queue.contractionCount;
  queue.activeTriangles[e] = {kNoIndex, kNoIndex, kNoIndex};
  queue.activeKnown[e] = point.activeCount >= 0;
  for (int i = 0; i < point.activeCount; ++i) {
    queue.activeTriangles[e][static_cast<std::size_t>(i)] =
        constraints.triangles[static_cast<std::size_t>(point.active[static_cast<std::size_t>(i)])];
  }
}

bool tightenKey(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                Hubs& hubs, std::uint32_t e) {
  if (queue.state[e] == EdgeState::Lower) {
    if (!tightenBound(queue, mesh, costs, hubs, e)) solveEdge(queue, mesh, costs, hubs, e);
    return true;
  }
  if (queue.state[e] == EdgeState::Bounded) {
    solveEdge(queue, mesh, costs, hubs, e);
    return true;
  }
  return false;
}

void invalidateEdge(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                    Hubs& hubs, std::uint32_t e) {
  const EdgeState state = queue.state[e];
  if (state == EdgeState::Off || state == EdgeState::Parked) return;
  if (!queue.lazy) {
    solveEdge(queue, mesh, costs, hubs, e);
    return;
  }
  if (state == EdgeState::Infeasible) {
    queue.state[e] = EdgeState::Lower;
    queue.activeKnown[e] = 0;
    queue.heap.set(e, queue.lowerBounds[e]);
    return;
  }
  bool fromLastCost = false;
  const double bound = boundAfterChange(queue, mesh, costs, e, fromLastCost);
  if (state != EdgeState::Lower || bound < queue.heap.key(e)) {  // a tightened bound may not hold
    queue.state[e] = fromLastCost ? EdgeState::Bounded : EdgeState::Lower;
    queue.heap.set(e, bound);
  }
}

void invalidateRaised(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                      Hubs& hubs, std::uint32_t v) {
  Hub& hub = hubs.slots[hubs.slotOf[v]];
  const auto isRaised = [&](std::uint32_t e) {
    const EdgeState state = queue.state[e];
    return state == EdgeState::Bounded || state == EdgeState::Solved ||
           state == EdgeState::Infeasible;
  };
  std::size_t kept = 0;
  for (const std::uint32_t e : hub.raised) {
    const bool atHub = mesh.edgeEnds[e][0] == hub.vertex || mesh.edgeEnds[e][1] == hub.vertex;
    if (atHub && isRaised(e)) invalidateEdge(queue, mesh, costs, hubs, e);
    if (atHub && isRaised(e)) {
      hub.raised[kept++] = e;
    } else {
      queue.raised[e] = 0;
    }
  }
  hub.raised.resize(kept);
}

void park(ContractionQueue& queue, const ContractionMesh& mesh, std::uint32_t e) {
  queue.heap.erase(e);
  queue.state[e] = EdgeState::Parked;
  queue.parkedVersions[e] = versionSum(mesh, e);
  if (!queue.listed[e]) {
    queue.listed[e] = 1;
    queue.parked.push_back(e);
  }
}

bool revisitParked(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                   Hubs& hubs) {
  bool any = false;
  std::size_t kept = 0;
  for (const std::uint32_t e : queue.parked) {
    if (queue.state[e] == EdgeState::Parked && versionSum(mesh, e) == queue.parkedVersions[e]) {
      queue.parked[kept++] = e;  // nothing changed around it: still rejected
      continue;
    }
    queue.listed[e] = 0;
    if (queue.state[e] == EdgeState::Parked) {
      queueEdge(queue, mesh, costs, hubs, e);
      any = true;
    }
  }
  queue.parked.resize(kept);
  return any;
}

}  // namespace kaboum::geometry
