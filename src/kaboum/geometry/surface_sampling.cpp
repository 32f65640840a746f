#include "kaboum/geometry/surface_sampling.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace kaboum::geometry {

namespace {

// Uniform double in [0, 1) from the top 53 bits: the same sequence on every platform.
double unitInterval(std::mt19937_64& engine) {
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

}  // namespace

SurfaceSampler::SurfaceSampler(const TriangleMesh& mesh, std::size_t randomCount,
                               std::uint64_t seed)
    : mesh_(&mesh), randomCount_(randomCount), seed_(seed), used_(mesh.vertices.size(), 0) {
  for (const Triangle& tri : mesh.triangles) {
    for (const std::uint32_t index : tri) used_[index] = 1;
  }
}

void SurfaceSampler::beginEdges() {
  edges_.reserve(3 * mesh_->triangles.size());
  for (const Triangle& tri : mesh_->triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      if (a != b) edges_.push_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b));
    }
  }
  std::sort(edges_.begin(), edges_.end());
  edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
  stage_ = Stage::edges;
  position_ = 0;
}

void SurfaceSampler::beginRandom() {
  cumulativeArea_.resize(mesh_->triangles.size());
  double total = 0.0;
  for (std::size_t t = 0; t < mesh_->triangles.size(); ++t) {
    const Triangle& tri = mesh_->triangles[t];
    const Vec3& a = mesh_->vertices[tri[0]];
    const double area =
        0.5 * (mesh_->vertices[tri[1]] - a).cross(mesh_->vertices[tri[2]] - a).norm();
    if (area > 0.0) lastWithArea_ = t;
    total += area;
    cumulativeArea_[t] = total;
  }
  stage_ = total > 0.0 ? Stage::random : Stage::done;
  position_ = 0;
  engine_.emplace(seed_);
}

bool SurfaceSampler::next(Vec3& sample) {
  const std::vector<Vec3>& vertices = mesh_->vertices;
  if (stage_ == Stage::vertices) {
    while (position_ < used_.size() && !used_[position_]) ++position_;
    if (position_ < used_.size()) {
      sample = vertices[position_++];
      ++produced_;
      return true;
    }
    beginEdges();
  }
  if (stage_ == Stage::edges) {
    if (position_ < edges_.size()) {
      const std::uint64_t edge = edges_[position_++];
      sample = 0.5 * (vertices[edge >> 32] + vertices[edge & 0xffffffffu]);
      ++produced_;
      return true;
    }
    beginRandom();
  }
  if (stage_ == Stage::random) {
    if (position_ == randomCount_) {
      stage_ = Stage::done;
      return false;
    }
    ++position_;
    // A zero-area triangle spans an empty interval of the cumulative areas: never selected.
    const double target = unitInterval(*engine_) * cumulativeArea_.back();
    const auto t = std::min<std::size_t>(
        std::upper_bound(cumulativeArea_.begin(), cumulativeArea_.end(), target) -
            cumulativeArea_.begin(),
        lastWithArea_);
    const double root = std::sqrt(unitInterval(*engine_)), v = unitInterval(*engine_);
    const Triangle& tri = mesh_->triangles[t];
    sample = (1.0 - root) * vertices[tri[0]] + root * (1.0 - v) * vertices[tri[1]] +
             root * v * vertices[tri[2]];
    ++produced_;
    return true;
  }
  return false;
}

std::vector<Vec3> sampleSurface(const TriangleMesh& mesh, std::size_t randomCount,
                                std::uint64_t seed) {
  std::vector<Vec3> samples;
  samples.reserve(mesh.vertices.size() + 3 * mesh.triangles.size() / 2 + randomCount);
  SurfaceSampler sampler(mesh, randomCount, seed);
  for (Vec3 sample; sampler.next(sample);) samples.push_back(sample);
  return samples;
}

}  // namespace kaboum::geometry
