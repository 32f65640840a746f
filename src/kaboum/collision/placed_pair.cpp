// Pair queries with b's vertices placed in a's frame once per query (thesis §4.1: the convex–
// convex query; docs/collision.md, "Pre-tests and the portal test"): the portal test and GJK of
// gjk.hpp on two plain vertex scans, built whole once per instruction set.
#include <array>
#include <numbers>

// fan_test.hpp passes vectors of eight doubles between inlined functions (see there).
#pragma GCC diagnostic ignored "-Wpsabi"

// Each per-instruction-set query below is compiled whole (flatten: the portal test, the fan test,
// GJK and the scans inlined into one function). Not in AddressSanitizer builds (GCC defines
// __SANITIZE_ADDRESS__; the asan preset also runs UBSan): instrumented, the flattened queries
// took minutes to compile, and there only the answers matter.
#ifdef __SANITIZE_ADDRESS__
#define KABOUM_WHOLE_QUERY
#else
#define KABOUM_WHOLE_QUERY gnu::flatten
#endif

#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/fan_test.hpp"
#include "kaboum/collision/gjk.hpp"
#include "kaboum/collision/vertex_scan.hpp"

namespace kaboum::collision::detail {

FanFrame fanFrame() {
  FanFrame frame{};
  const auto ring = [&](std::size_t r, std::size_t first, std::size_t count, double degrees,
                        double turn) {
    const double tilt = degrees * std::numbers::pi / 180.0;
    for (std::size_t k = 0; k < count; ++k) {
      const double angle =
          2.0 * std::numbers::pi * (static_cast<double>(k) + turn) / static_cast<double>(count);
      frame.alongU[r][first + k] = std::cos(tilt);
      frame.alongE1[r][first + k] = std::sin(tilt) * std::cos(angle);
      frame.alongE2[r][first + k] = std::sin(tilt) * std::sin(angle);
    }
  };
  frame.alongU[0][0] = 1.0;
  ring(0, 1, 7, 25.0, 0.0);
  ring(1, 0, 8, 60.0, 0.5);
  return frame;
}

namespace {

constexpr std::size_t kMaxChunks = ConvexPolytope::kBruteForceMaxVertices / kLaneWidth;

const FanFrame kFanFrame = fanFrame();

struct ScalarKernels {
  static std::uint32_t scan(const VertexChunk* chunks, std::size_t count, const Vec3& d) {
    return scanChunksScalar(chunks, count, d);
  }
  static void place(const VertexChunk* chunks, std::size_t count, const Eigen::Matrix3d& r,
                    const Vec3& t, VertexChunk* placed) {
    placeChunksScalar(chunks, count, r, t, placed);
  }
  static constexpr bool kFan = false;
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
  static constexpr bool kFan = false;
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
  // The fan test (fan_test.hpp) and its kernels.
  static constexpr bool kFan = true;
  [[gnu::target("avx512f")]] static bool anyPositive(const Lanes& lanes) {
    return _mm512_cmp_pd_mask(reinterpret_cast<__m512d>(lanes), _mm512_setzero_pd(), _CMP_GT_OQ) !=
           0;
  }
  [[gnu::target("avx512f")]] static double inverseSquareRoot(double x) {
    const __m128d value = _mm_set_sd(x);
    return _mm_cvtsd_f64(_mm_rsqrt14_sd(value, value));
  }
  // One chunk: a lane permutation per coordinate; more: gathers (vertex i sits at double
  // 24·(i / 8) + i % 8 of the chunk array, plus 8 for y and 16 for z).
  [[gnu::target("avx512f")]] static void gather(const VertexChunk* chunks, std::size_t count,
                                                const LaneIntegers& vertex, LanePoints& p) {
    // Vector-extension shuffles and explicit gather sources rather than the intrinsics that
    // start from _mm512_undefined_pd() (-Wmaybe-uninitialized, GCC bug 105593).
    if (count == 1) {
      p.x = __builtin_shuffle(reinterpret_cast<Lanes>(_mm512_load_pd(chunks->x.data())), vertex);
      p.y = __builtin_shuffle(reinterpret_cast<Lanes>(_mm512_load_pd(chunks->y.data())), vertex);
      p.z = __builtin_shuffle(reinterpret_cast<Lanes>(_mm512_load_pd(chunks->z.data())), vertex);
      return;
    }
    // Vertex i sits at double 24·(i / 8) + i % 8 = 3·i − 2·(i % 8) of the chunks (x; y and z
    // follow 8 and 16 doubles later).
    const auto offset =
        reinterpret_cast<__m512i>(vertex + (vertex << 1) - ((vertex & (LaneIntegers{} + 7)) << 1));
    const double* base = chunks->x.data();
    const __m512d none = _mm512_setzero_pd();
    p.x = reinterpret_cast<Lanes>(_mm512_mask_i64gather_pd(none, 0xFF, offset, base, 8));
    p.y =
        reinterpret_cast<Lanes>(_mm512_mask_i64gather_pd(none, 0xFF, offset, base + kLaneWidth, 8));
    p.z = reinterpret_cast<Lanes>(
        _mm512_mask_i64gather_pd(none, 0xFF, offset, base + 2 * kLaneWidth, 8));
  }
};

// Vertex chunks already in the query frame: the support is a scan and a read. Hints are a
// ConvexPolytope's (the vertex index), so caches carry over. Satisfies VertexSupport.
template <class Kernels>
struct ScannedChunks {
  using Hint = ConvexPolytope::Hint;

  Vec3 support(const Vec3& direction, Hint& hint) const {
    hint.vertex = Kernels::scan(chunks, count, direction);
    return vertex(hint.vertex);
  }
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const {
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

// Polytopes of up to this many chunks (16 vertices) go through the fan test: it reads every
// vertex once per direction, and from 32 vertices on it cost more than the portal test it saves
// (docs/benchmarks.md).
constexpr std::size_t kFanMaxChunks = 2;

template <class Kernels>
bool fanApplies(const PlacedPair<Kernels>& pair) {
  return pair.first.count <= kFanMaxChunks && pair.second.count <= kFanMaxChunks;
}

// The boolean query's fan pre-test: GJK's first support, then the fan (`unknown` where the fan
// does not apply).
template <class Kernels>
PairVerdict fanPretest(const PlacedPair<Kernels>& pair, double margin,
                       const GjkTolerance& tolerance) {
  if constexpr (Kernels::kFan) {
    if (fanApplies(pair)) {
      using Chunks = ScannedChunks<Kernels>;
      GjkFirstSupport<Chunks, Chunks> first;
      if (firstSupportSeparates(pair.first, pair.second, margin + tolerance.absolute, first)) {
        return PairVerdict::separated;
      }
      return fanVerdict<Kernels>(kFanFrame, pair.first, pair.second, margin, tolerance, nullptr);
    }
  }
  return PairVerdict::unknown;
}

template <class Kernels>
bool intersectsPlacedWith(const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
                          const GjkTolerance& tolerance) {
  using Chunks = ScannedChunks<Kernels>;
  const PlacedPair<Kernels> pair(a, bInA);
  const PairVerdict fanned = fanPretest(pair, margin, tolerance);
  if (fanned != PairVerdict::unknown) return fanned == PairVerdict::intersecting;
  const PairVerdict verdict = portalIntersects(pair.first, pair.second, margin, tolerance);
  if (verdict != PairVerdict::unknown) return verdict == PairVerdict::intersecting;
  return runGjk<true, Chunks, Chunks>(pair.first, pair.second, margin, nullptr, tolerance).exit !=
         GjkExit::separated;
}

// Distance 0 and the common witness point of an intersection the fan test certified: the
// origin's barycentric combination of the tetrahedron's points, formed on a and on b.
template <class Kernels>
DistanceResult commonPoint(const PlacedPair<Kernels>& pair, const FanTetrahedron& tetrahedron) {
  DistanceResult result;
  result.intersecting = true;
  result.iterations = 1;
  result.pointA = tetrahedron.weight[0] * pair.first.center();
  result.pointB = tetrahedron.weight[0] * pair.second.center();
  for (std::size_t k = 1; k < 4; ++k) {
    result.pointA += tetrahedron.weight[k] * pair.first.vertex(tetrahedron.vertexA[k]);
    result.pointB += tetrahedron.weight[k] * pair.second.vertex(tetrahedron.vertexB[k]);
  }
  return result;
}

// A cold distance query through the fan test first: pairs not separated along GJK's first
// direction mostly overlap, and the fan certifies that for most, the origin's tetrahedron giving a
// common witness point; GJK (reusing that first support) answers the others.
template <class Kernels>
DistanceResult distanceAfterFan(const PlacedPair<Kernels>& pair, const GjkTolerance& tolerance) {
  using Chunks = ScannedChunks<Kernels>;
  GjkFirstSupport<Chunks, Chunks> first;
  if (!firstSupportSeparates(pair.first, pair.second, tolerance.absolute, first)) {
    FanTetrahedron tetrahedron;
    if (fanVerdict<Kernels>(kFanFrame, pair.first, pair.second, 0.0, tolerance, &tetrahedron) ==
        PairVerdict::intersecting) {
      // A nearly flat tetrahedron (the origin on its plane, as for touching pairs) has weights
      // too rounded to give one point: GJK decides those.
      const DistanceResult result = commonPoint(pair, tetrahedron);
      if ((result.pointA - result.pointB).squaredNorm() <=
          tolerance.absolute * tolerance.absolute) {
        return result;
      }
    }
  }
  return distanceResult(
      runGjk<false, Chunks, Chunks>(pair.first, pair.second, 0.0, nullptr, tolerance, &first),
      pair.first, pair.second);
}

template <class Kernels>
DistanceResult distancePlacedWith(const ConvexPolytope& a, const TransformedSupport& bInA,
                                  LocalPairCache* cache, const GjkTolerance& tolerance) {
  const PlacedPair<Kernels> pair(a, bInA);
  using Chunks = ScannedChunks<Kernels>;
  if (cache == nullptr) {
    if constexpr (Kernels::kFan) {
      if (fanApplies(pair)) return distanceAfterFan(pair, tolerance);
    }
    return distance<Chunks, Chunks>(pair.first, pair.second, nullptr, tolerance);
  }
  GjkCache<Chunks, Chunks> local{cache->direction, cache->hintA, cache->hintB};
  const DistanceResult result = distance(pair.first, pair.second, &local, tolerance);
  *cache = {local.direction, local.hintA, local.hintB};
  return result;
}

[[gnu::target("avx512f"), KABOUM_WHOLE_QUERY]] PairVerdict fanPretestAvx512(
    const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
    const GjkTolerance& tolerance) {
  return fanPretest(PlacedPair<Avx512Kernels>(a, bInA), margin, tolerance);
}

}  // namespace

PairVerdict fanPretest(const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
                       const GjkTolerance& tolerance) {
  if (!__builtin_cpu_supports("avx512f") || !scansBoth(a, bInA.polytope())) {
    return PairVerdict::unknown;
  }
  return fanPretestAvx512(a, bInA, margin, tolerance);
}

[[KABOUM_WHOLE_QUERY]] bool intersectsPlacedScalar(const ConvexPolytope& a,
                                                   const TransformedSupport& bInA, double margin,
                                                   const GjkTolerance& tolerance) {
  return intersectsPlacedWith<ScalarKernels>(a, bInA, margin, tolerance);
}
[[gnu::target("avx2"), KABOUM_WHOLE_QUERY]] bool intersectsPlacedAvx2(
    const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
    const GjkTolerance& tolerance) {
  return intersectsPlacedWith<Avx2Kernels>(a, bInA, margin, tolerance);
}
[[gnu::target("avx512f"), KABOUM_WHOLE_QUERY]] bool intersectsPlacedAvx512(
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

[[KABOUM_WHOLE_QUERY]] DistanceResult distancePlacedScalar(const ConvexPolytope& a,
                                                           const TransformedSupport& bInA,
                                                           LocalPairCache* cache,
                                                           const GjkTolerance& tolerance) {
  return distancePlacedWith<ScalarKernels>(a, bInA, cache, tolerance);
}
[[gnu::target("avx2"), KABOUM_WHOLE_QUERY]] DistanceResult distancePlacedAvx2(
    const ConvexPolytope& a, const TransformedSupport& bInA, LocalPairCache* cache,
    const GjkTolerance& tolerance) {
  return distancePlacedWith<Avx2Kernels>(a, bInA, cache, tolerance);
}
[[gnu::target("avx512f"), KABOUM_WHOLE_QUERY]] DistanceResult distancePlacedAvx512(
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
