// The vertex-chunk kernels of the support mapping (thesis §4.1: every query is convex–convex, its
// inner loop a support scan), inline so that whole pair queries compile around them per CPU:
// support scans and rigid placement of chunks, scalar (any x86-64), AVX2 and AVX-512.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cstdint>

#include "kaboum/collision/convex_polytope.hpp"

namespace kaboum::collision::detail {

// The first vertex of `chunkCount` chunks maximising direction.x, one vertex at a time with
// conditional moves. Padding lanes repeat vertex 0 and never beat it (strict comparison).
inline std::uint32_t scanChunksScalar(const VertexChunk* chunks, std::size_t chunkCount,
                                      const Vec3& direction) {
  const double dx = direction.x();
  const double dy = direction.y();
  const double dz = direction.z();
  std::uint32_t best = 0;
  double bestDot = dx * chunks[0].x[0] + dy * chunks[0].y[0] + dz * chunks[0].z[0];
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

// `chunkCount` chunks placed by x -> rotation x + translation into `placed` (padding lanes stay
// copies of vertex 0).
inline void placeChunksScalar(const VertexChunk* chunks, std::size_t chunkCount,
                              const Eigen::Matrix3d& r, const Vec3& t, VertexChunk* placed) {
  for (std::size_t c = 0; c < chunkCount; ++c) {
    const VertexChunk& in = chunks[c];
    VertexChunk& out = placed[c];
    for (std::size_t lane = 0; lane < kLaneWidth; ++lane) {
      const double x = in.x[lane];
      const double y = in.y[lane];
      const double z = in.z[lane];
      out.x[lane] = r(0, 0) * x + r(0, 1) * y + r(0, 2) * z + t.x();
      out.y[lane] = r(1, 0) * x + r(1, 1) * y + r(1, 2) * z + t.y();
      out.z[lane] = r(2, 0) * x + r(2, 1) * y + r(2, 2) * z + t.z();
    }
  }
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
[[gnu::target("avx512f")]] inline std::uint32_t scanChunksAvx512(const VertexChunk* chunks,
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

// placeChunksScalar() with one chunk per three fused multiply-add chains.
[[gnu::target("avx512f")]] inline void placeChunksAvx512(const VertexChunk* chunks,
                                                         std::size_t chunkCount,
                                                         const Eigen::Matrix3d& r, const Vec3& t,
                                                         VertexChunk* placed) {
  for (std::size_t c = 0; c < chunkCount; ++c) {
    const __m512d x = _mm512_load_pd(chunks[c].x.data());
    const __m512d y = _mm512_load_pd(chunks[c].y.data());
    const __m512d z = _mm512_load_pd(chunks[c].z.data());
    double* const out[3] = {placed[c].x.data(), placed[c].y.data(), placed[c].z.data()};
    for (int row = 0; row < 3; ++row) {
      const __m512d p = _mm512_fmadd_pd(
          _mm512_set1_pd(r(row, 2)), z,
          _mm512_fmadd_pd(_mm512_set1_pd(r(row, 1)), y,
                          _mm512_fmadd_pd(_mm512_set1_pd(r(row, 0)), x, _mm512_set1_pd(t[row]))));
      _mm512_store_pd(out[row], p);
    }
  }
}

// AVX2 (4-wide, for CPUs without AVX-512): a chunk is two halves of four lanes. No fused
// multiply-adds (the dispatch is on AVX2 alone, not every AVX2 CPU has FMA).
struct ChunkHalves {
  __m256d low, high;
};

// The four dot products of the lanes from `first` on with the direction (dx, dy, dz) broadcast.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256d halfDotsAvx2(const VertexChunk& chunk,
                                                                        std::size_t first,
                                                                        __m256d dx, __m256d dy,
                                                                        __m256d dz) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, _mm256_load_pd(chunk.x.data() + first)),
                                     _mm256_mul_pd(dy, _mm256_load_pd(chunk.y.data() + first))),
                       _mm256_mul_pd(dz, _mm256_load_pd(chunk.z.data() + first)));
}
[[gnu::target("avx2"), gnu::always_inline]] inline ChunkHalves chunkDotsAvx2(
    const VertexChunk& chunk, __m256d dx, __m256d dy, __m256d dz) {
  return {halfDotsAvx2(chunk, 0, dx, dy, dz), halfDotsAvx2(chunk, 4, dx, dy, dz)};
}

// The largest of the four lanes, in every lane.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256d laneMaximumAvx2(__m256d v) {
  v = _mm256_max_pd(v, _mm256_permute2f128_pd(v, v, 0x01));
  return _mm256_max_pd(v, _mm256_permute_pd(v, 0x5));
}

// scanChunksScalar() four lanes at a time: per lane the best dot and its vertex, then the first
// vertex at the largest dot.
[[gnu::target("avx2")]] inline std::uint32_t scanChunksAvx2(const VertexChunk* chunks,
                                                            std::size_t chunkCount,
                                                            const Vec3& direction) {
  const __m256d dx = _mm256_set1_pd(direction.x());
  const __m256d dy = _mm256_set1_pd(direction.y());
  const __m256d dz = _mm256_set1_pd(direction.z());
  ChunkHalves best = chunkDotsAvx2(chunks[0], dx, dy, dz);
  // Lane indices as doubles (exact up to 2^53), blended along with the dots.
  __m256d indexLow = _mm256_set_pd(3, 2, 1, 0);
  __m256d indexHigh = _mm256_set_pd(7, 6, 5, 4);
  for (std::size_t c = 1; c < chunkCount; ++c) {
    const ChunkHalves d = chunkDotsAvx2(chunks[c], dx, dy, dz);
    const __m256d offset = _mm256_set1_pd(static_cast<double>(kLaneWidth * c));
    const __m256d betterLow = _mm256_cmp_pd(d.low, best.low, _CMP_GT_OQ);
    const __m256d betterHigh = _mm256_cmp_pd(d.high, best.high, _CMP_GT_OQ);
    best.low = _mm256_blendv_pd(best.low, d.low, betterLow);
    best.high = _mm256_blendv_pd(best.high, d.high, betterHigh);
    indexLow =
        _mm256_blendv_pd(indexLow, _mm256_add_pd(_mm256_set_pd(3, 2, 1, 0), offset), betterLow);
    indexHigh =
        _mm256_blendv_pd(indexHigh, _mm256_add_pd(_mm256_set_pd(7, 6, 5, 4), offset), betterHigh);
  }
  const __m256d top = laneMaximumAvx2(_mm256_max_pd(best.low, best.high));
  const unsigned atTop =
      static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(best.low, top, _CMP_EQ_OQ))) |
      static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(best.high, top, _CMP_EQ_OQ))) << 4;
  // No lane equals the maximum only for a NaN direction: any vertex will do.
  if (atTop == 0) return 0;
  if (chunkCount == 1) return static_cast<std::uint32_t>(__builtin_ctz(atTop));
  alignas(32) std::array<double, kLaneWidth> index;
  _mm256_store_pd(index.data(), indexLow);
  _mm256_store_pd(index.data() + 4, indexHigh);
  double first = index[static_cast<std::size_t>(__builtin_ctz(atTop))];
  for (unsigned rest = atTop; rest != 0; rest &= rest - 1) {
    first = std::min(first, index[static_cast<std::size_t>(__builtin_ctz(rest))]);
  }
  return static_cast<std::uint32_t>(first);
}

// placeChunksScalar() four lanes at a time.
[[gnu::target("avx2")]] inline void placeChunksAvx2(const VertexChunk* chunks,
                                                    std::size_t chunkCount,
                                                    const Eigen::Matrix3d& r, const Vec3& t,
                                                    VertexChunk* placed) {
  for (std::size_t c = 0; c < chunkCount; ++c) {
    double* const out[3] = {placed[c].x.data(), placed[c].y.data(), placed[c].z.data()};
    for (std::size_t first = 0; first < kLaneWidth; first += 4) {
      const __m256d x = _mm256_load_pd(chunks[c].x.data() + first);
      const __m256d y = _mm256_load_pd(chunks[c].y.data() + first);
      const __m256d z = _mm256_load_pd(chunks[c].z.data() + first);
      for (int row = 0; row < 3; ++row) {
        const __m256d p = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(r(row, 0)), x),
                          _mm256_mul_pd(_mm256_set1_pd(r(row, 1)), y)),
            _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(r(row, 2)), z), _mm256_set1_pd(t[row])));
        _mm256_store_pd(out[row] + first, p);
      }
    }
  }
}

}  // namespace kaboum::collision::detail
