#include "kaboum/geometry/bounding_mesh_collapse.hpp"

#include <algorithm>
#include <array>

#include "kaboum/geometry/quadric.hpp"

namespace kaboum::geometry {
namespace {

// Exactly two triangles on edge (a, b), and the link condition (the only common neighbours of a
// and b are the two vertices opposite the edge), or the mesh stops being manifold; and neither
// opposite vertex may be left with valence 2.
bool keepsManifold(ContractionMesh& mesh, const CollapseFans& fans, std::uint32_t a,
                   std::uint32_t b) {
  std::uint32_t opposite[2] = {kNoIndex, kNoIndex};
  int shared = 0;
  for (std::uint32_t t : fans.fanA) {
    if (!triangleHas(mesh, t, b)) continue;
    if (shared == 2) return false;
    for (std::uint32_t w : mesh.triangles[t]) {
      if (w != a && w != b) opposite[shared] = w;
    }
    ++shared;
  }
  if (shared != 2) return false;
  for (std::uint32_t w : opposite) {
    if (mesh.triangleCount[w] <= 3) return false;
  }
  const std::uint32_t stamp = ++mesh.stamp;
  for (std::uint32_t t : fans.fanA) {
    for (std::uint32_t w : mesh.triangles[t]) mesh.markA[w] = stamp;
  }
  int common = 0;
  for (std::uint32_t t : fans.fanB) {
    for (std::uint32_t w : mesh.triangles[t]) {
      if (w == a || w == b || mesh.markB[w] == stamp) continue;
      mesh.markB[w] = stamp;
      if (mesh.markA[w] == stamp) ++common;
    }
  }
  return common == 2;
}

// No new triangle may be degenerate or turn over relative to the one it replaces.
bool keepsShape(const ContractionMesh& mesh, const ContractionCosts& costs, const Contraction& c,
                const CollapseFans& fans) {
  const auto keeps = [&](std::uint32_t t, std::uint32_t moved) {
    std::array<Vec3, 3> p;
    for (int k = 0; k < 3; ++k) {
      p[k] = mesh.triangles[t][k] == moved ? c.position : mesh.positions[mesh.triangles[t][k]];
    }
    const Vec3 cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double longest = std::max(
        {(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm()});
    const double length = cross.norm();
    if (!(length > 1e-10 * longest)) return false;
    return costs.normals[t] == Vec3::Zero() || cross.dot(costs.normals[t]) > 1e-3 * length;
  };
  for (std::uint32_t t : fans.fanA) {
    if (!triangleHas(mesh, t, c.b) && !keeps(t, c.a)) return false;
  }
  for (std::uint32_t t : fans.fanB) {
    if (!triangleHas(mesh, t, c.a) && !keeps(t, c.b)) return false;
  }
  return true;
}

// Before b merges into a: edge (a, b) and, for each triangle (a, b, o) that collapses, edge (b, o)
// disappear; the triangle across (b, o) takes over edge (a, o).
void retireMergedEdges(ContractionQueue& queue, ContractionMesh& mesh, const CollapseFans& fans,
                       std::uint32_t a, std::uint32_t b) {
  const auto retire = [&](std::uint32_t e) {
    queue.heap.erase(e);
    queue.state[e] = EdgeState::Off;
  };
  for (std::uint32_t t : fans.fanA) {
    if (!triangleHas(mesh, t, b)) continue;
    std::uint32_t fromB = kNoIndex, fromA = kNoIndex;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t u = mesh.triangles[t][k], w = mesh.triangles[t][(k + 1) % 3];
      const std::uint32_t edge = mesh.cornerEdge[3 * t + k];
      if ((u == a && w == b) || (u == b && w == a)) {
        retire(edge);
      } else if (u == b || w == b) {
        fromB = edge;
      } else {
        fromA = edge;
      }
    }
    retire(fromB);
    for (std::uint32_t u : fans.fanB) {
      if (u == t || triangleHas(mesh, u, a)) continue;
      for (std::uint32_t k = 0; k < 3; ++k) {
        if (mesh.cornerEdge[3 * u + k] == fromB) mesh.cornerEdge[3 * u + k] = fromA;
      }
    }
  }
}

// Executes contraction c: the triangles on edge (a, b) die, b's corners pass to a, the quadrics
// merge, a moves, and the triangles at a (now listed in fans.fanA) get their new planes and boxes.
void mergeVertices(ContractionMesh& mesh, ContractionCosts& costs, CrossingGuard& guard,
                   ContractionQueue& queue, CollapseFans& fans, const Contraction& c) {
  const std::uint32_t a = c.a, b = c.b;
  // Star triangles of hubs leave the indexes while their geometry changes (placeTriangle below).
  for (std::uint32_t t : fans.fanA) {
    if (!guard.inGrid[t]) unindexAtHubs(guard, mesh, t);
  }
  for (std::uint32_t t : fans.fanB) {
    if (!guard.inGrid[t] && !triangleHas(mesh, t, a)) unindexAtHubs(guard, mesh, t);
  }
  for (std::uint32_t t : fans.fanA) {
    if (triangleHas(mesh, t, b)) {
      removeFromGrid(guard, t);
      mesh.triangleAlive[t] = 0;
      queue.triangleChangedAt[t] = queue.contractionCount;
      for (std::uint32_t w : mesh.triangles[t]) --mesh.triangleCount[w];
    }
  }
  std::uint32_t tail = kNoIndex;
  for (std::uint32_t corner = mesh.firstCorner[b]; corner != kNoIndex;
       corner = mesh.nextCorner[corner]) {
    mesh.triangles[corner / 3][corner % 3] = a;
    tail = corner;
  }
  if (tail != kNoIndex) {
    mesh.nextCorner[tail] = mesh.firstCorner[a];
    mesh.firstCorner[a] = mesh.firstCorner[b];
    mesh.firstCorner[b] = kNoIndex;
  }
  mesh.triangleCount[a] += mesh.triangleCount[b];
  mesh.triangleCount[b] = 0;
  const bool hub =
      isHub(guard.hubs, a) || isHub(guard.hubs, b) || mesh.triangleCount[a] >= kHubValence;
  releaseHub(guard.hubs, b);
  costs.quadrics[a] = mergeQuadrics(costs.quadrics[a], costs.quadrics[b], costs.merge, c.position,
                                    costs.mergeLength);
  mesh.positions[a] = c.position;
  mesh.vertexAlive[b] = 0;
  --mesh.aliveVertices;
  if (hub) acquireHub(guard.hubs, mesh, a);
  fans.fanA.clear();
  forEachTriangle(mesh, a, [&](std::uint32_t t) {
    updatePlane(costs, mesh, t);
    queue.triangleChangedAt[t] = queue.contractionCount;
    placeTriangle(guard, mesh, t, boxOf(mesh, t));
    fans.fanA.push_back(t);
  });
}

// After a contraction into a: the edges at a get a new quadric and are queued afresh; the other
// edges at a's neighbours keep their quadrics, but their planes moved, so their exact costs are
// invalidated (thesis Algorithm 2, "update the costs of the edges around the new vertex").
void requeueAround(ContractionQueue& queue, ContractionMesh& mesh, const ContractionCosts& costs,
                   Hubs& hubs, CollapseFans& fans, std::uint32_t a) {
  ++mesh.version[a];
  gatherNeighbours(mesh, a, fans.neighbours);
  for (std::uint32_t w : fans.neighbours) ++mesh.version[w];
  // Each edge (a, w) leaves a in exactly one triangle of the new fan.
  for (std::uint32_t t : fans.fanA) {
    const Triangle& tri = mesh.triangles[t];
    const std::uint32_t k = tri[0] == a ? 0 : (tri[1] == a ? 1 : 2);
    const std::uint32_t e = mesh.cornerEdge[3 * t + k], w = tri[(k + 1) % 3];
    mesh.edgeEnds[e] = {a, w};
    if (!mesh.vertexLocked[w]) queueEdge(queue, mesh, costs, hubs, e);
  }
  for (std::uint32_t w : fans.neighbours) {
    if (mesh.vertexLocked[w]) continue;
    if (isHub(hubs, w)) {  // only its raised edges can need a lower key (see invalidateEdge)
      invalidateRaised(queue, mesh, costs, hubs, w);
      continue;
    }
    forEachTriangle(mesh, w, [&](std::uint32_t t) {
      const Triangle& tri = mesh.triangles[t];
      const std::uint32_t k = tri[0] == w ? 0 : (tri[1] == w ? 1 : 2);
      if (tri[(k + 1) % 3] != a) {
        invalidateEdge(queue, mesh, costs, hubs, mesh.cornerEdge[3 * t + k]);
      }
    });
  }
}

}  // namespace

ContractionOutcome contractEdge(ContractionMesh& mesh, ContractionCosts& costs,
                                CrossingGuard& guard, ContractionQueue& queue, CollapseFans& fans,
                                std::uint32_t e) {
  const auto [a, b] = mesh.edgeEnds[e];
  const Contraction c{a, b, queue.points[e]};
  gatherFan(mesh, a, fans.fanA);
  gatherFan(mesh, b, fans.fanB);
  if (!keepsManifold(mesh, fans, a, b)) return ContractionOutcome::Topology;
  if (!keepsShape(mesh, costs, c, fans)) return ContractionOutcome::Geometry;
  if (newFanCrossesMesh(guard, mesh, costs, c, fans.fanA, fans.fanB)) {
    return ContractionOutcome::Crossing;
  }
  ++queue.contractionCount;
  retireMergedEdges(queue, mesh, fans, a, b);
  mergeVertices(mesh, costs, guard, queue, fans, c);
  requeueAround(queue, mesh, costs, guard.hubs, fans, a);
  return ContractionOutcome::Done;
}

}  // namespace kaboum::geometry
