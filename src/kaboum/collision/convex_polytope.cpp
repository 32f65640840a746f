#include "kaboum/collision/convex_polytope.hpp"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace kaboum::collision {

namespace detail {

std::uint32_t scanVertexChunksScalar(const VertexChunk* chunks, std::size_t chunkCount,
                                     const Vec3& direction) {
  const double dx = direction.x();
  const double dy = direction.y();
  const double dz = direction.z();
  std::uint32_t best = 0;
  double bestDot = dx * chunks[0].x[0] + dy * chunks[0].y[0] + dz * chunks[0].z[0];
  // Padding lanes repeat vertex 0 and never beat it (strict comparison).
  for (std::size_t c = 0; c < chunkCount; ++c) {
    const VertexChunk& chunk = chunks[c];
    for (std::size_t lane = 0; lane < kLaneWidth; ++lane) {
      const double d = dx * chunk.x[lane] + dy * chunk.y[lane] + dz * chunk.z[lane];
      best = d > bestDot ? static_cast<std::uint32_t>(c * kLaneWidth + lane) : best;
      bestDot = d > bestDot ? d : bestDot;
    }
  }
  return best;
}

// The eight dot products of a chunk with the direction (dx, dy, dz) broadcast.
[[gnu::target("avx512f"), gnu::always_inline]] inline __m512d chunkDots(const VertexChunk& chunk,
                                                                        __m512d dx, __m512d dy,
                                                                        __m512d dz) {
  return _mm512_fmadd_pd(dz, _mm512_load_pd(chunk.z.data()),
                         _mm512_fmadd_pd(dy, _mm512_load_pd(chunk.y.data()),
                                         _mm512_mul_pd(dx, _mm512_load_pd(chunk.x.data()))));
}

// The largest (or smallest) of the eight lanes, in every lane: halves, then quarters, then pairs
// swapped and compared. Vector-extension shuffles rather than GCC 12's AVX-512 reduction
// intrinsics, which warn (-Wmaybe-uninitialized, GCC bug 105593).
[[gnu::target("avx512f"), gnu::always_inline]] inline __m512d laneMaximum(__m512d v) {
  __m512d swapped = __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  v = swapped > v ? swapped : v;
  swapped = __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5);
  v = swapped > v ? swapped : v;
  swapped = __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6);
  return swapped > v ? swapped : v;
}
[[gnu::target("avx512f"), gnu::always_inline]] inline __v8di laneMinimum(__v8di v) {
  __v8di swapped = __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  v = swapped < v ? swapped : v;
  swapped = __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5);
  v = swapped < v ? swapped : v;
  swapped = __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6);
  return swapped < v ? swapped : v;
}

// Per lane the best dot and its vertex, then the largest dot across lanes and the smallest vertex
// index reaching it (the first one, as the scalar scan). One chunk (up to 8 vertices, the common
// case) skips the index lanes: the first lane holding the maximum is the vertex.
[[gnu::target("avx512f")]] std::uint32_t scanVertexChunksAvx512(const VertexChunk* chunks,
                                                                std::size_t chunkCount,
                                                                const Vec3& direction) {
  const __m512d dx = _mm512_set1_pd(direction.x());
  const __m512d dy = _mm512_set1_pd(direction.y());
  const __m512d dz = _mm512_set1_pd(direction.z());
  __m512d best = chunkDots(chunks[0], dx, dy, dz);
  if (chunkCount == 1) {
    const __mmask8 atTop = _mm512_cmp_pd_mask(best, laneMaximum(best), _CMP_EQ_OQ);
    // No lane equals the maximum only for a NaN direction: any vertex will do.
    return atTop == 0 ? 0 : static_cast<std::uint32_t>(__builtin_ctz(atTop));
  }
  const __m512i laneIndex = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
  __m512i bestIndex = laneIndex;
  for (std::size_t c = 1; c < chunkCount; ++c) {
    const __m512d d = chunkDots(chunks[c], dx, dy, dz);
    const __mmask8 better = _mm512_cmp_pd_mask(d, best, _CMP_GT_OQ);
    best = _mm512_mask_mov_pd(best, better, d);
    bestIndex = _mm512_mask_add_epi64(bestIndex, better, laneIndex,
                                      _mm512_set1_epi64(static_cast<long long>(kLaneWidth * c)));
  }
  const __mmask8 atTop = _mm512_cmp_pd_mask(best, laneMaximum(best), _CMP_EQ_OQ);
  if (atTop == 0) return 0;
  const __v8di first = laneMinimum(reinterpret_cast<__v8di>(
      _mm512_mask_blend_epi64(atTop, _mm512_set1_epi64(UINT32_MAX), bestIndex)));
  return static_cast<std::uint32_t>(first[0]);
}

[[gnu::target("default")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                          std::size_t chunkCount,
                                                          const Vec3& direction) {
  return scanVertexChunksScalar(chunks, chunkCount, direction);
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
