#include "kaboum/geometry/surface_sampling.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace kaboum {

namespace {

// Uniform double in [0, 1) from the top 53 bits: the same sequence on every platform.
double unitInterval(std::mt19937_64& engine) {
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

void appendUsedVertices(const TriangleMesh& mesh, std::vector<Vec3>& samples) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const Triangle& tri : mesh.triangles) {
    for (const std::uint32_t index : tri) used[index] = 1;
  }
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (used[i]) samples.push_back(mesh.vertices[i]);
  }
}

void appendEdgeMidpoints(const TriangleMesh& mesh, std::vector<Vec3>& samples) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const Triangle& tri : mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      if (a != b) edges.push_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const std::uint64_t edge : edges) {
    const Vec3& a = mesh.vertices[edge >> 32];
    const Vec3& b = mesh.vertices[edge & 0xffffffffu];
    samples.push_back(0.5 * (a + b));
  }
}

void appendRandomPoints(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed,
                        std::vector<Vec3>& samples) {
  std::vector<double> cumulativeArea(mesh.triangles.size());
  double total = 0.0;
  std::size_t lastWithArea = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    const double area = 0.5 * (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).norm();
    if (area > 0.0) lastWithArea = t;
    total += area;
    cumulativeArea[t] = total;
  }
  if (!(total > 0.0)) return;
  std::mt19937_64 engine(seed);
  for (std::size_t i = 0; i < count; ++i) {
    // A zero-area triangle spans an empty interval of the cumulative areas: never selected.
    const double target = unitInterval(engine) * total;
    const auto t = std::min<std::size_t>(
        std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), target) -
            cumulativeArea.begin(),
        lastWithArea);
    const double root = std::sqrt(unitInterval(engine)), v = unitInterval(engine);
    const Triangle& tri = mesh.triangles[t];
    samples.push_back((1.0 - root) * mesh.vertices[tri[0]] +
                      root * (1.0 - v) * mesh.vertices[tri[1]] + root * v * mesh.vertices[tri[2]]);
  }
}

}  // namespace

std::vector<Vec3> sampleSurface(const TriangleMesh& mesh, std::size_t randomCount,
                                std::uint64_t seed) {
  std::vector<Vec3> samples;
  samples.reserve(mesh.vertices.size() + 3 * mesh.triangles.size() / 2 + randomCount);
  appendUsedVertices(mesh, samples);
  appendEdgeMidpoints(mesh, samples);
  appendRandomPoints(mesh, randomCount, seed, samples);
  return samples;
}

}  // namespace kaboum
