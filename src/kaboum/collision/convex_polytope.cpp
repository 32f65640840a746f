#include "kaboum/collision/convex_polytope.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "kaboum/collision/vertex_scan.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

namespace detail {

std::uint32_t scanVertexChunksScalar(const VertexChunk* chunks, std::size_t chunkCount,
                                     const Vec3& direction) {
  return scanChunksScalar(chunks, chunkCount, direction);
}
[[gnu::target("avx2")]] std::uint32_t scanVertexChunksAvx2(const VertexChunk* chunks,
                                                           std::size_t chunkCount,
                                                           const Vec3& direction) {
  return scanChunksAvx2(chunks, chunkCount, direction);
}
[[gnu::target("avx512f")]] std::uint32_t scanVertexChunksAvx512(const VertexChunk* chunks,
                                                                std::size_t chunkCount,
                                                                const Vec3& direction) {
  return scanChunksAvx512(chunks, chunkCount, direction);
}

[[gnu::target("default")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                          std::size_t chunkCount,
                                                          const Vec3& direction) {
  return scanVertexChunksScalar(chunks, chunkCount, direction);
}
[[gnu::target("avx2")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                       std::size_t chunkCount,
                                                       const Vec3& direction) {
  return scanVertexChunksAvx2(chunks, chunkCount, direction);
}
[[gnu::target("avx512f")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                          std::size_t chunkCount,
                                                          const Vec3& direction) {
  return scanVertexChunksAvx512(chunks, chunkCount, direction);
}

}  // namespace detail

namespace {

constexpr int kSphereSearchSteps = 200;

// Largest distance from `c` to a vertex, and that vertex.
double farthestVertex(const std::vector<Vec3>& vertices, const Vec3& c, Vec3& farthest) {
  double best = -1.0;
  for (const Vec3& v : vertices) {
    const double d = (v - c).squaredNorm();
    if (d > best) {
      best = d;
      farthest = v;
    }
  }
  return std::sqrt(best);
}

// The centre minimising the largest vertex distance, searched from `start`: steps towards the
// farthest vertex, or between the two farthest ones when that fails, halved when neither helps.
Vec3 enclosingCentre(const std::vector<Vec3>& vertices, Vec3 start) {
  Vec3 far = start;
  double radius = farthestVertex(vertices, start, far);
  double step = 0.25 * radius;
  for (int i = 0; i < kSphereSearchSteps && step > 1e-9 * radius; ++i) {
    Vec3 candidate = start + step * (far - start).normalized();
    Vec3 candidateFar = far;
    double candidateRadius = farthestVertex(vertices, candidate, candidateFar);
    if (!(candidateRadius < radius)) {
      candidate = start + step * (0.5 * (far + candidateFar) - start).normalized();
      candidateRadius = farthestVertex(vertices, candidate, candidateFar);
    }
    if (candidateRadius < radius) {
      start = candidate;
      radius = candidateRadius;
      far = candidateFar;
    } else {
      step *= 0.5;
    }
  }
  return start;
}

// Distance from `c` to the nearest facet plane (positive inside), and the normals of the three
// nearest planes, nearest first (fewer are filled when there are fewer planes).
double clearance(const std::vector<HullPlane>& planes, const Vec3& c,
                 std::array<Vec3, 3>& nearestNormals) {
  std::array<double, 3> nearest;
  nearest.fill(std::numeric_limits<double>::infinity());
  for (const HullPlane& plane : planes) {
    double d = plane.offset - plane.normal.dot(c);
    Vec3 normal = plane.normal;
    for (std::size_t k = 0; k < nearest.size(); ++k) {
      if (d < nearest[k]) {
        std::swap(d, nearest[k]);
        std::swap(normal, nearestNormals[k]);
      }
    }
  }
  return nearest[0];
}

// The centre maximising the facet clearance (the largest inner ball), searched from `start`:
// steps that move away from the nearest plane, from the two nearest at equal rates, or from the
// three nearest at equal rates (the first that increases the clearance is taken), halved when
// none does.
Vec3 inscribedCentre(const std::vector<HullPlane>& planes, Vec3 start) {
  std::array<Vec3, 3> normals;
  normals.fill(Vec3::Zero());
  double radius = clearance(planes, start, normals);
  double step = 0.5 * radius;
  for (int i = 0; i < kSphereSearchSteps && step > 1e-9 * radius; ++i) {
    std::array<Vec3, 3> directions = {-normals[0], -(normals[0] + normals[1]), Vec3::Zero()};
    Eigen::Matrix3d facing;
    facing << normals[0].transpose(), normals[1].transpose(), normals[2].transpose();
    if (std::abs(facing.determinant()) > 1e-9) directions[2] = -facing.inverse() * Vec3::Ones();
    bool improved = false;
    for (const Vec3& direction : directions) {
      if (!(direction.squaredNorm() > 1e-18)) continue;
      const Vec3 candidate = start + step * direction.normalized();
      std::array<Vec3, 3> candidateNormals = normals;
      const double candidateRadius = clearance(planes, candidate, candidateNormals);
      if (candidateRadius > radius) {
        start = candidate;
        radius = candidateRadius;
        normals = candidateNormals;
        improved = true;
        break;
      }
    }
    if (!improved) step *= 0.5;
  }
  return start;
}

}  // namespace

ConvexPolytope::ConvexPolytope(std::span<const Vec3> points, const std::string& what)
    : ConvexPolytope(convexHull(points, what)) {}

ConvexPolytope::ConvexPolytope(const ConvexHull& hull) : vertices_(hull.mesh.vertices) {
  const auto n = static_cast<std::uint32_t>(vertices_.size());
  chunks_.resize((n + kLaneWidth - 1) / kLaneWidth);
  for (std::size_t i = 0; i < chunks_.size() * kLaneWidth; ++i) {
    const Vec3& v = vertices_[i < n ? i : 0];
    chunks_[i / kLaneWidth].x[i % kLaneWidth] = v.x();
    chunks_[i / kLaneWidth].y[i % kLaneWidth] = v.y();
    chunks_[i / kLaneWidth].z[i % kLaneWidth] = v.z();
  }
  // Every hull edge, both ways, sorted by source vertex then deduplicated (each edge is shared by
  // two triangles).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(hull.mesh.triangles.size() * 6);
  for (const Triangle& t : hull.mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(t[k], t[(k + 1) % 3]);
      edges.emplace_back(t[(k + 1) % 3], t[k]);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  neighborBegin_.assign(n + 1, 0);
  neighbors_.reserve(edges.size());
  for (const auto& [from, to] : edges) {
    ++neighborBegin_[from + 1];
    neighbors_.push_back(to);
  }
  for (std::uint32_t i = 0; i < n; ++i) neighborBegin_[i + 1] += neighborBegin_[i];

  center_ = Vec3::Zero();
  box_.setEmpty();
  for (const Vec3& v : vertices_) {
    center_ += v;
    box_.extend(v);
  }
  center_ /= static_cast<double>(n);
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) seeds_.push_back(scan(sign * Vec3::Unit(axis)));
  }
  for (int corner = 0; corner < 8; ++corner) {
    seeds_.push_back(
        scan(Vec3(corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0)));
  }
  std::sort(seeds_.begin(), seeds_.end());
  seeds_.erase(std::unique(seeds_.begin(), seeds_.end()), seeds_.end());
  sphereCenter_ = enclosingCentre(vertices_, box_.center());
  for (const Vec3& v : vertices_) {
    sphereRadius_ = std::max(sphereRadius_, (v - sphereCenter_).norm());
  }
  innerCenter_ = inscribedCentre(hull.planes, center_);
  std::array<Vec3, 3> nearest;
  innerRadius_ = std::max(0.0, clearance(hull.planes, innerCenter_, nearest));
}

}  // namespace kaboum::collision
