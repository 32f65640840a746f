#include "kaboum/geometry/bounding_mesh_topology.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "kaboum/core/error.hpp"

namespace kaboum::geometry {

void gatherFan(ContractionMesh& mesh, std::uint32_t v, std::vector<std::uint32_t>& fan) {
  fan.clear();
  forEachTriangle(mesh, v, [&](std::uint32_t t) { fan.push_back(t); });
}

void gatherNeighbours(ContractionMesh& mesh, std::uint32_t v, std::vector<std::uint32_t>& out) {
  out.clear();
  const std::uint32_t stamp = ++mesh.stamp;
  forEachTriangle(mesh, v, [&](std::uint32_t t) {
    for (std::uint32_t w : mesh.triangles[t]) {
      if (w != v && mesh.markA[w] != stamp) {
        mesh.markA[w] = stamp;
        out.push_back(w);
      }
    }
  });
}

void buildAdjacency(ContractionMesh& mesh, const TriangleMesh& input) {
  mesh.positions = input.vertices;
  mesh.triangles = input.triangles;
  const std::size_t n = mesh.positions.size(), triangleCount = mesh.triangles.size();
  mesh.vertexLocked.assign(n, 0);
  mesh.vertexAlive.assign(n, 1);
  mesh.version.assign(n, 0);
  mesh.markA.assign(n, 0);
  mesh.markB.assign(n, 0);
  mesh.triangleAlive.assign(triangleCount, 1);
  mesh.triangleMark.assign(triangleCount, 0);
  mesh.firstCorner.assign(n, kNoIndex);
  mesh.nextCorner.assign(triangleCount * 3, kNoIndex);
  mesh.triangleCount.assign(n, 0);
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      mesh.nextCorner[3 * t + k] = mesh.firstCorner[v];
      mesh.firstCorner[v] = 3 * t + k;
      ++mesh.triangleCount[v];
    }
  }
}

// Numbers the edges in order of (lower, higher) vertex, filling cornerEdge and edgeEnds. Each
// vertex v numbers its edges to higher vertices from its own corners (a short sort per vertex, not
// one of all edges).
std::vector<std::uint32_t> classifyEdges(ContractionMesh& mesh) {
  struct HalfEdge {
    std::uint32_t other;  // the higher vertex (or v itself)
    std::uint32_t corner;
    bool forward;  // stored direction is lower → higher
  };
  std::vector<HalfEdge> halfEdges;
  std::vector<std::uint32_t> interiorEdges;
  mesh.cornerEdge.assign(mesh.triangles.size() * 3, kNoIndex);
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    halfEdges.clear();
    for (std::uint32_t c = mesh.firstCorner[v]; c != kNoIndex; c = mesh.nextCorner[c]) {
      const std::uint32_t t = c / 3, k = c % 3;
      const std::uint32_t next = mesh.triangles[t][(k + 1) % 3];
      const std::uint32_t previous = mesh.triangles[t][(k + 2) % 3];
      if (next >= v) halfEdges.push_back({next, c, next > v});  // (v, v) of a degenerate triangle
      if (previous > v) halfEdges.push_back({previous, 3 * t + (k + 2) % 3, false});
    }
    std::sort(halfEdges.begin(), halfEdges.end(),
              [](const HalfEdge& l, const HalfEdge& r) { return l.other < r.other; });
    for (std::size_t i = 0; i < halfEdges.size();) {
      std::size_t j = i;
      int forward = 0;
      const auto edge = static_cast<std::uint32_t>(mesh.edgeEnds.size());
      while (j < halfEdges.size() && halfEdges[j].other == halfEdges[i].other) {
        forward += halfEdges[j].forward ? 1 : 0;
        mesh.cornerEdge[halfEdges[j].corner] = edge;
        ++j;
      }
      const std::uint32_t lo = v, hi = halfEdges[i].other;
      mesh.edgeEnds.push_back({lo, hi});
      const std::size_t count = j - i;
      if (count == 2 && forward != 1) {
        throw InputError("triangles are not consistently oriented (edge between vertices " +
                         std::to_string(lo) + " and " + std::to_string(hi) +
                         " is traversed twice in the same direction)");
      }
      if (count == 2) {
        interiorEdges.push_back(edge);
      } else {  // border (1) or non-manifold (> 2): keep it exactly as it is
        mesh.vertexLocked[lo] = mesh.vertexLocked[hi] = 1;
      }
      i = j;
    }
  }
  return interiorEdges;
}

// An interior vertex is manifold when its link edges (a → b for each triangle (v, a, b)) form a
// single cycle.
void lockNonManifoldVertices(ContractionMesh& mesh) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> link;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    if (mesh.vertexLocked[v] || mesh.triangleCount[v] == 0) continue;
    link.clear();
    forEachTriangle(mesh, v, [&](std::uint32_t t) {
      const Triangle& tri = mesh.triangles[t];
      const int k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
      link.emplace_back(tri[(k + 1) % 3], tri[(k + 2) % 3]);
    });
    // Walked through the link sorted by first vertex (a binary search per step, not a scan: hubs
    // have thousands of link edges). Only a link whose edges all start at distinct vertices can be
    // one cycle, so which of several edges from one vertex is found does not change the verdict.
    const std::pair<std::uint32_t, std::uint32_t> start = link[0];
    std::sort(link.begin(), link.end());
    std::size_t steps = 0;
    std::uint32_t at = start.second;
    while (at != start.first && steps < link.size()) {
      const auto next = std::lower_bound(
          link.begin(), link.end(), at, [](const auto& e, std::uint32_t x) { return e.first < x; });
      if (next == link.end() || next->first != at) break;
      at = next->second;
      ++steps;
    }
    if (at != start.first || steps + 1 != link.size()) mesh.vertexLocked[v] = 1;
  }
}

void retireUnusedVertices(ContractionMesh& mesh) {
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    if (mesh.triangleCount[v] == 0) {
      mesh.vertexAlive[v] = 0;
    } else {
      ++mesh.aliveVertices;
    }
  }
}

double liveDiagonal(const ContractionMesh& mesh) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    if (!mesh.vertexAlive[v]) continue;
    lo = lo.cwiseMin(mesh.positions[v]);
    hi = hi.cwiseMax(mesh.positions[v]);
  }
  return mesh.aliveVertices > 0 ? (hi - lo).norm() : 0.0;
}

std::size_t lockedVertexCount(const ContractionMesh& mesh) {
  std::size_t count = 0;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    if (mesh.vertexAlive[v]) count += mesh.vertexLocked[v];
  }
  return count;
}

TriangleMesh compactMesh(const ContractionMesh& mesh) {
  TriangleMesh out;
  std::vector<std::uint32_t> remap(mesh.positions.size(), kNoIndex);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!mesh.triangleAlive[t]) continue;
    Triangle tri = mesh.triangles[t];
    for (std::uint32_t& v : tri) {
      if (remap[v] == kNoIndex) {
        remap[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(mesh.positions[v]);
      }
      v = remap[v];
    }
    out.triangles.push_back(tri);
  }
  return out;
}

}  // namespace kaboum::geometry
