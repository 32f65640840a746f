// Pair queries with b's vertices placed in a's frame once per query (thesis §4.1: the convex–
// convex query; docs/collision.md, "Pre-tests and the portal test"): the portal test and GJK of
// gjk.hpp on two plain vertex scans, built whole once per instruction set.
#include <array>

#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/gjk.hpp"
#include "kaboum/collision/vertex_scan.hpp"

namespace kaboum::collision::detail {
namespace {

constexpr std::size_t kMaxChunks = ConvexPolytope::kBruteForceMaxVertices / kLaneWidth;

struct ScalarKernels {
  static std::uint32_t scan(const VertexChunk* chunks, std::size_t count, const Vec3& d) {
    return scanChunksScalar(chunks, count, d);
  }
  static void place(const VertexChunk* chunks, std::size_t count, const Eigen::Matrix3d& r,
                    const Vec3& t, VertexChunk* placed) {
    placeChunksScalar(chunks, count, r, t, placed);
  }
};

struct Avx2Kernels {
  [[gnu::target("avx2")]] static std::uint32_t scan(const VertexChunk* chunks, std::size_t count,
                                                    const Vec3& d) {
    return scanChunksAvx2(chunks, count, d);
  }
  [[gnu::target("avx2")]] static void place(const VertexChunk* chunks, std::size_t count,
                                            const Eigen::Matrix3d& r, const Vec3& t,
                                            VertexChunk* placed) {
    placeChunksAvx2(chunks, count, r, t, placed);
  }
};

struct Avx512Kernels {
  [[gnu::target("avx512f")]] static std::uint32_t scan(const VertexChunk* chunks, std::size_t count,
                                                       const Vec3& d) {
    return scanChunksAvx512(chunks, count, d);
  }
  [[gnu::target("avx512f")]] static void place(const VertexChunk* chunks, std::size_t count,
                                               const Eigen::Matrix3d& r, const Vec3& t,
                                               VertexChunk* placed) {
    placeChunksAvx512(chunks, count, r, t, placed);
  }
};

// Vertex chunks already in the query frame: the support is a scan and a read. Hints are a
// ConvexPolytope's (the vertex index), so caches carry over. Satisfies SupportMapping.
template <class Kernels>
struct ScannedChunks {
  using Hint = ConvexPolytope::Hint;

  Vec3 support(const Vec3& direction, Hint& hint) const {
    const std::uint32_t index = Kernels::scan(chunks, count, direction);
    hint.vertex = index;
    const VertexChunk& chunk = chunks[index / kLaneWidth];
    const std::uint32_t lane = index % kLaneWidth;
    return {chunk.x[lane], chunk.y[lane], chunk.z[lane]};
  }
  [[nodiscard]] Vec3 center() const { return centre; }

  const VertexChunk* chunks;
  std::size_t count;
  Vec3 centre;
};

// a as it is and b placed into `placed` (left uninitialised: only b's chunk count is written).
template <class Kernels>
struct PlacedPair {
  PlacedPair(const ConvexPolytope& a, const TransformedSupport& bInA)
      : first{a.chunks().data(), a.chunks().size(), a.center()},
        second{placed.data(), bInA.polytope().chunks().size(), bInA.center()} {
    const std::span<const VertexChunk> chunks = bInA.polytope().chunks();
    Kernels::place(chunks.data(), chunks.size(), bInA.rotation(), bInA.translation(),
                   placed.data());
  }
  PlacedPair(const PlacedPair&) = delete;
  PlacedPair& operator=(const PlacedPair&) = delete;

  std::array<VertexChunk, kMaxChunks> placed;
  ScannedChunks<Kernels> first;
  ScannedChunks<Kernels> second;
};

template <class Kernels>
bool intersectsPlacedWith(const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
                          const GjkTolerance& tolerance) {
  const PlacedPair<Kernels> pair(a, bInA);
  const PairVerdict verdict = portalIntersects(pair.first, pair.second, margin, tolerance);
  if (verdict != PairVerdict::unknown) return verdict == PairVerdict::intersecting;
  Simplex simplex;
  double lowerBound = 0.0;
  int iterations = 0;
  using Chunks = ScannedChunks<Kernels>;
  return runGjk<true, Chunks, Chunks>(pair.first, pair.second, margin, nullptr, tolerance, simplex,
                                      nullptr, lowerBound, iterations) != GjkExit::separated;
}

template <class Kernels>
DistanceResult distancePlacedWith(const ConvexPolytope& a, const TransformedSupport& bInA,
                                  LocalPairCache* cache, const GjkTolerance& tolerance) {
  const PlacedPair<Kernels> pair(a, bInA);
  using Chunks = ScannedChunks<Kernels>;
  if (cache == nullptr)
    return distance<Chunks, Chunks>(pair.first, pair.second, nullptr, tolerance);
  GjkCache<Chunks, Chunks> local{cache->direction, cache->hintA, cache->hintB};
  const DistanceResult result = distance(pair.first, pair.second, &local, tolerance);
  *cache = {local.direction, local.hintA, local.hintB};
  return result;
}

}  // namespace

// flatten: the portal and GJK loops, and the scans in them, are compiled into each build.
[[gnu::flatten]] bool intersectsPlacedScalar(const ConvexPolytope& a,
                                             const TransformedSupport& bInA, double margin,
                                             const GjkTolerance& tolerance) {
  return intersectsPlacedWith<ScalarKernels>(a, bInA, margin, tolerance);
}
[[gnu::target("avx2"), gnu::flatten]] bool intersectsPlacedAvx2(const ConvexPolytope& a,
                                                                const TransformedSupport& bInA,
                                                                double margin,
                                                                const GjkTolerance& tolerance) {
  return intersectsPlacedWith<Avx2Kernels>(a, bInA, margin, tolerance);
}
[[gnu::target("avx512f"), gnu::flatten]] bool intersectsPlacedAvx512(
    const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
    const GjkTolerance& tolerance) {
  return intersectsPlacedWith<Avx512Kernels>(a, bInA, margin, tolerance);
}
[[gnu::target("default")]] bool intersectsPlaced(const ConvexPolytope& a,
                                                 const TransformedSupport& bInA, double margin,
                                                 const GjkTolerance& tolerance) {
  return intersectsPlacedScalar(a, bInA, margin, tolerance);
}
[[gnu::target("avx2")]] bool intersectsPlaced(const ConvexPolytope& a,
                                              const TransformedSupport& bInA, double margin,
                                              const GjkTolerance& tolerance) {
  return intersectsPlacedAvx2(a, bInA, margin, tolerance);
}
[[gnu::target("avx512f")]] bool intersectsPlaced(const ConvexPolytope& a,
                                                 const TransformedSupport& bInA, double margin,
                                                 const GjkTolerance& tolerance) {
  return intersectsPlacedAvx512(a, bInA, margin, tolerance);
}

[[gnu::flatten]] DistanceResult distancePlacedScalar(const ConvexPolytope& a,
                                                     const TransformedSupport& bInA,
                                                     LocalPairCache* cache,
                                                     const GjkTolerance& tolerance) {
  return distancePlacedWith<ScalarKernels>(a, bInA, cache, tolerance);
}
[[gnu::target("avx2"), gnu::flatten]] DistanceResult distancePlacedAvx2(
    const ConvexPolytope& a, const TransformedSupport& bInA, LocalPairCache* cache,
    const GjkTolerance& tolerance) {
  return distancePlacedWith<Avx2Kernels>(a, bInA, cache, tolerance);
}
[[gnu::target("avx512f"), gnu::flatten]] DistanceResult distancePlacedAvx512(
    const ConvexPolytope& a, const TransformedSupport& bInA, LocalPairCache* cache,
    const GjkTolerance& tolerance) {
  return distancePlacedWith<Avx512Kernels>(a, bInA, cache, tolerance);
}
[[gnu::target("default")]] DistanceResult distancePlaced(const ConvexPolytope& a,
                                                         const TransformedSupport& bInA,
                                                         LocalPairCache* cache,
                                                         const GjkTolerance& tolerance) {
  return distancePlacedScalar(a, bInA, cache, tolerance);
}
[[gnu::target("avx2")]] DistanceResult distancePlaced(const ConvexPolytope& a,
                                                      const TransformedSupport& bInA,
                                                      LocalPairCache* cache,
                                                      const GjkTolerance& tolerance) {
  return distancePlacedAvx2(a, bInA, cache, tolerance);
}
[[gnu::target("avx512f")]] DistanceResult distancePlaced(const ConvexPolytope& a,
                                                         const TransformedSupport& bInA,
                                                         LocalPairCache* cache,
                                                         const GjkTolerance& tolerance) {
  return distancePlacedAvx512(a, bInA, cache, tolerance);
}

}  // namespace kaboum::collision::detail
