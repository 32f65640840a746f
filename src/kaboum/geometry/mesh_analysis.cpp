#include "kaboum/geometry/mesh_analysis.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>
#include <span>

namespace kaboum::geometry {

namespace {

bool hasRepeatedIndex(const Triangle& t) {
  return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
}

// Union-find over 0..n-1; the smaller index becomes the root, so results do not depend on the
// order of unions.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  // True when x and y were in different sets.
  bool unite(std::uint32_t x, std::uint32_t y) {
    x = find(x);
    y = find(y);
    if (x == y) return false;
    if (y < x) std::swap(x, y);
    parent_[y] = x;
    return true;
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// Calls `visit(ids)` once per undirected edge with the ids 3t+k of all half-edges on it, in
// increasing order. Half-edges are bucketed by their smaller vertex (counting sort), then each
// bucket is sorted by the larger vertex: O(T log valence), no per-edge allocation.
template <typename Visit>
void forEachEdge(const TriangleMesh& mesh, Visit&& visit) {
  const std::size_t vertexCount = mesh.vertices.size();
  std::vector<std::uint32_t> bucketStart(vertexCount + 1, 0);
  for (const Triangle& t : mesh.triangles) {
    if (hasRepeatedIndex(t)) continue;
    for (int k = 0; k < 3; ++k) ++bucketStart[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  std::partial_sum(bucketStart.begin(), bucketStart.end(), bucketStart.begin());

  struct Entry {
    std::uint32_t other;  // larger vertex of the edge
    std::uint32_t id;     // 3t+k
    bool operator<(const Entry& e) const { return other != e.other ? other < e.other : id < e.id; }
  };
  std::vector<Entry> entries(bucketStart.back());
  std::vector<std::uint32_t> fill(bucketStart.begin(), bucketStart.end() - 1);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    if (hasRepeatedIndex(tri)) continue;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      entries[fill[std::min(a, b)]++] = {std::max(a, b), 3 * t + k};
    }
  }

  std::vector<std::uint32_t> run;  // ids of one edge; grows only to the largest edge multiplicity
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const auto first = entries.begin() + bucketStart[v],
               last = entries.begin() + bucketStart[v + 1];
    std::sort(first, last);
    for (auto it = first; it != last;) {
      run.clear();
      const std::uint32_t other = it->other;
      for (; it != last && it->other == other; ++it) run.push_back(it->id);
      visit(std::span<const std::uint32_t>(run));
    }
  }
}

std::uint32_t cornerVertex(const TriangleMesh& mesh, std::uint32_t corner) {
  return mesh.triangles[corner / 3][corner % 3];
}

// The corner of half-edge h's head (its second vertex).
std::uint32_t headCorner(std::uint32_t h) {
  return 3 * (h / 3) + (h % 3 + 1) % 3;
}

}  // namespace

bool isDegenerateTriangle(const TriangleMesh& mesh, const Triangle& triangle) {
  if (hasRepeatedIndex(triangle)) return true;
  const Vec3& a = mesh.vertices[triangle[0]];
  const Vec3& b = mesh.vertices[triangle[1]];
  const Vec3& c = mesh.vertices[triangle[2]];
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).norm() <= 1e-12 * longest;
}

EdgeNeighbors findEdgeNeighbors(const TriangleMesh& mesh) {
  EdgeNeighbors result;
  result.across.assign(3 * mesh.triangles.size(), EdgeNeighbors::kNoEdge);
  forEachEdge(mesh, [&](std::span<const std::uint32_t> ids) {
    if (ids.size() == 1) {
      result.across[ids[0]] = EdgeNeighbors::kBorder;
      ++result.borderEdges;
    } else if (ids.size() == 2) {
      result.across[ids[0]] = ids[1] / 3;
      result.across[ids[1]] = ids[0] / 3;
      if (cornerVertex(mesh, ids[0]) == cornerVertex(mesh, ids[1])) ++result.inconsistentEdges;
    } else {
      for (const std::uint32_t id : ids) result.across[id] = EdgeNeighbors::kNonManifold;
      ++result.nonManifoldEdges;
    }
  });
  return result;
}

MeshAnalysis analyzeMesh(const TriangleMesh& mesh) {
  MeshAnalysis result;
  result.vertices = mesh.vertices.size();
  result.triangles = mesh.triangles.size();
  if (mesh.triangles.empty()) return result;

  result.boxMin = result.boxMax = mesh.vertices[mesh.triangles[0][0]];
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t v : t) {
      result.boxMin = result.boxMin.cwiseMin(mesh.vertices[v]);
      result.boxMax = result.boxMax.cwiseMax(mesh.vertices[v]);
    }
    if (isDegenerateTriangle(mesh, t)) ++result.degenerateTriangles;
  }
  result.diagonal = (result.boxMax - result.boxMin).norm();

  const std::size_t triangleCount = mesh.triangles.size();
  DisjointSets components(triangleCount);
  DisjointSets corners(3 * triangleCount);
  DisjointSets borderGraph(mesh.vertices.size());
  std::vector<std::uint32_t> fans(mesh.vertices.size(), 0);  // corners minus merges per vertex
  std::vector<char> onBorder(mesh.vertices.size(), 0), onNonManifoldEdge(mesh.vertices.size(), 0);
  std::vector<char> triangleOpen(triangleCount, 0);  // has a border or non-manifold edge
  for (const Triangle& t : mesh.triangles) {
    if (hasRepeatedIndex(t)) continue;
    for (const std::uint32_t v : t) ++fans[v];
  }

  std::size_t inconsistentEdges = 0;
  forEachEdge(mesh, [&](std::span<const std::uint32_t> ids) {
    const std::uint32_t a = cornerVertex(mesh, ids[0]), b = cornerVertex(mesh, headCorner(ids[0]));
    if (ids.size() == 1) {
      ++result.borderEdges;
      borderGraph.unite(a, b);
      onBorder[a] = onBorder[b] = 1;
      triangleOpen[ids[0] / 3] = 1;
      return;
    }
    for (const std::uint32_t id : ids) components.unite(ids[0] / 3, id / 3);
    if (ids.size() > 2) {
      ++result.nonManifoldEdges;
      onNonManifoldEdge[a] = onNonManifoldEdge[b] = 1;
      for (const std::uint32_t id : ids) triangleOpen[id / 3] = 1;
      return;
    }
    const std::uint32_t tail0 = ids[0], head0 = headCorner(ids[0]);
    const std::uint32_t tail1 = ids[1], head1 = headCorner(ids[1]);
    const bool sameDirection = cornerVertex(mesh, tail0) == cornerVertex(mesh, tail1);
    if (sameDirection) ++inconsistentEdges;
    // Corners at the same vertex on both sides of a two-triangle edge belong to one fan.
    if (corners.unite(tail0, sameDirection ? tail1 : head1)) --fans[a];
    if (corners.unite(head0, sameDirection ? head1 : tail1)) --fans[b];
  });

  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (fans[v] > 1 || onNonManifoldEdge[v]) ++result.nonManifoldVertices;
    if (onBorder[v] && borderGraph.find(static_cast<std::uint32_t>(v)) == v) ++result.borderLoops;
  }

  // Per component: signed volume about the box centre (exact for closed components, where the
  // reference point cancels) and whether every edge has exactly two triangles.
  const Vec3 centre = 0.5 * (result.boxMin + result.boxMax);
  std::vector<double> componentVolume(triangleCount, 0.0);  // six times the volume until the end
  std::vector<char> componentOpen(triangleCount, 0);
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    const Triangle& tri = mesh.triangles[t];
    if (hasRepeatedIndex(tri)) continue;
    const std::uint32_t root = components.find(t);
    const Vec3 p = mesh.vertices[tri[0]] - centre, q = mesh.vertices[tri[1]] - centre,
               r = mesh.vertices[tri[2]] - centre;
    componentVolume[root] += p.dot(q.cross(r));
    componentOpen[root] |= triangleOpen[t];
  }
  std::size_t closedComponents = 0;
  bool closedAllPositive = true;
  for (std::uint32_t t = 0; t < triangleCount; ++t) {
    if (hasRepeatedIndex(mesh.triangles[t]) || components.find(t) != t) continue;
    ++result.components;
    const double volume = componentVolume[t] / 6.0;
    result.volume += volume;
    if (!componentOpen[t]) {
      ++closedComponents;
      closedAllPositive = closedAllPositive && volume > 0.0;
    }
  }

  result.closed = result.borderEdges == 0;
  result.edgeManifold = result.nonManifoldEdges == 0;
  result.consistentlyOriented = inconsistentEdges == 0;
  result.outwardOriented = result.consistentlyOriented && closedComponents > 0 && closedAllPositive;
  return result;
}

double boundingBoxDiagonal(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0.0;
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

}  // namespace kaboum::geometry
