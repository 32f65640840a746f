#include "kaboum/geometry/subdivision.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kaboum::geometry {

TriangleMesh subdivideLoop(const TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  struct EdgeRef {
    std::uint64_t key;
    std::uint32_t triangle, corner;  // edge from corner to corner+1 of triangle
  };
  std::vector<EdgeRef> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint64_t u = mesh.triangles[t][k], w = mesh.triangles[t][(k + 1) % 3];
      edges.push_back({std::min(u, w) << 32 | std::max(u, w), t, k});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const EdgeRef& l, const EdgeRef& r) { return l.key < r.key; });

  TriangleMesh out;
  out.vertices.resize(n);
  std::vector<std::uint32_t> edgeVertex(mesh.triangles.size() * 3);
  std::vector<Vec3> neighbourSum(n, Vec3::Zero()), borderSum(n, Vec3::Zero());
  std::vector<std::uint32_t> valence(n, 0), borderCount(n, 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    const auto u = static_cast<std::uint32_t>(edges[i].key >> 32);
    const auto w = static_cast<std::uint32_t>(edges[i].key & 0xffffffffu);
    const Vec3& pu = mesh.vertices[u];
    const Vec3& pw = mesh.vertices[w];
    Vec3 point;
    if (j - i == 2) {  // interior edge: 3/8 endpoints + 1/8 opposite vertices
      Vec3 opposite = Vec3::Zero();
      for (std::size_t e = i; e < j; ++e) {
        opposite += mesh.vertices[mesh.triangles[edges[e].triangle][(edges[e].corner + 2) % 3]];
      }
      point = 0.375 * (pu + pw) + 0.125 * opposite;
    } else {  // border or non-manifold edge: midpoint
      point = 0.5 * (pu + pw);
      borderSum[u] += pw;
      borderSum[w] += pu;
      ++borderCount[u];
      ++borderCount[w];
    }
    neighbourSum[u] += pw;
    neighbourSum[w] += pu;
    ++valence[u];
    ++valence[w];
    const auto id = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.push_back(point);
    for (std::size_t e = i; e < j; ++e) edgeVertex[3 * edges[e].triangle + edges[e].corner] = id;
    i = j;
  }
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3& p = mesh.vertices[v];
    if (borderCount[v] == 2) {
      out.vertices[v] = 0.75 * p + 0.125 * borderSum[v];
    } else if (borderCount[v] > 0 || valence[v] == 0) {
      out.vertices[v] = p;  // corner of a non-manifold border: keep
    } else {
      const double k = valence[v];
      const double beta = k == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * k);
      out.vertices[v] = (1.0 - k * beta) * p + beta * neighbourSum[v];
    }
  }
  out.triangles.reserve(mesh.triangles.size() * 4);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& c = mesh.triangles[t];
    const std::uint32_t e0 = edgeVertex[3 * t], e1 = edgeVertex[3 * t + 1],
                        e2 = edgeVertex[3 * t + 2];
    out.triangles.push_back({c[0], e0, e2});
    out.triangles.push_back({c[1], e1, e0});
    out.triangles.push_back({c[2], e2, e1});
    out.triangles.push_back({e0, e1, e2});
  }
  return out;
}

}  // namespace kaboum::geometry
