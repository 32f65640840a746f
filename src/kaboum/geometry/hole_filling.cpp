#include "kaboum/geometry/hole_filling.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace kaboum::geometry {
namespace {

using EdgeKey = std::uint64_t;

EdgeKey edgeKey(std::uint32_t from, std::uint32_t to) {
  return (static_cast<EdgeKey>(from) << 32) | to;
}
std::uint32_t edgeFrom(EdgeKey key) {
  return static_cast<std::uint32_t>(key >> 32);
}
std::uint32_t edgeTo(EdgeKey key) {
  return static_cast<std::uint32_t>(key & 0xffffffffu);
}

// Directed edges (a, b) used more often than (b, a), each repeated by its surplus, sorted.
std::vector<EdgeKey> unmatchedEdges(const TriangleMesh& mesh) {
  std::vector<EdgeKey> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) edges.push_back(edgeKey(t[k], t[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  std::vector<EdgeKey> unmatched;
  for (auto run = edges.begin(); run != edges.end();) {
    const auto runEnd = std::upper_bound(run, edges.end(), *run);
    const auto [reverseBegin, reverseEnd] =
        std::equal_range(edges.begin(), edges.end(), edgeKey(edgeTo(*run), edgeFrom(*run)));
    const auto surplus = (runEnd - run) - (reverseEnd - reverseBegin);
    for (auto i = surplus; i > 0; --i) unmatched.push_back(*run);
    run = runEnd;
  }
  return unmatched;
}

}  // namespace

HoleFillingReport fillHoles(TriangleMesh& mesh) {
  HoleFillingReport report;
  const std::vector<EdgeKey> unmatched = unmatchedEdges(mesh);
  std::vector<bool> used(unmatched.size(), false);
  // The first unused unmatched edge leaving `vertex` (edges are sorted by their source).
  auto nextEdge = [&](std::uint32_t vertex) {
    auto it = std::lower_bound(unmatched.begin(), unmatched.end(), edgeKey(vertex, 0));
    for (; it != unmatched.end() && edgeFrom(*it) == vertex; ++it) {
      const auto index = static_cast<std::size_t>(it - unmatched.begin());
      if (!used[index]) return index;
    }
    return unmatched.size();
  };

  std::vector<std::uint32_t> loop;
  for (std::size_t start = 0; start < unmatched.size(); ++start) {
    if (used[start]) continue;
    loop.clear();
    const std::uint32_t first = edgeFrom(unmatched[start]);
    std::size_t edge = start;
    // Every vertex has as many unmatched edges in as out, so the walk returns to `first`.
    while (edge < unmatched.size()) {
      used[edge] = true;
      loop.push_back(edgeFrom(unmatched[edge]));
      const std::uint32_t to = edgeTo(unmatched[edge]);
      if (to == first) break;
      edge = nextEdge(to);
    }
    ++report.loops;
    if (loop.size() == 3) {
      mesh.triangles.push_back({loop[0], loop[2], loop[1]});
      ++report.addedTriangles;
      continue;
    }
    Vec3 centroid = Vec3::Zero();
    for (const std::uint32_t v : loop) centroid += mesh.vertices[v];
    centroid /= static_cast<double>(loop.size());
    const auto center = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(centroid);
    ++report.addedVertices;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      mesh.triangles.push_back({loop[(i + 1) % loop.size()], loop[i], center});
      ++report.addedTriangles;
    }
  }
  return report;
}

}  // namespace kaboum::geometry
