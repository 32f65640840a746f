// The fan test, a conservative pre-test of a polytope pair (thesis §4.1: the convex–convex query):
// sixteen support directions of a − b at once, in one pass over both polytopes' vertices, certify
// a separation or an intersection for most pairs the sphere tests leave (docs/collision.md,
// "Pre-tests and the portal test"). Written with GCC vector extensions of eight doubles, one
// AVX-512 register: only the AVX-512 build of placed_pair.cpp runs it (split into AVX2 or SSE2
// registers, GCC spills them: measured slower than the portal test it replaces).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/gjk.hpp"

// Every function here is inlined into its caller (always_inline), so passing eight-double
// vectors by value crosses no ABI boundary; GCC still warns that doing so without AVX-512 changes
// the ABI (-Wpsabi, reported at the end of the file that includes this one), so that file turns
// the warning off.

namespace kaboum::collision::detail {

// Eight doubles, or eight 64-bit integers, side by side (one AVX-512 register). Comparisons give
// integer lanes of all ones (true) or zero.
using Lanes = double __attribute__((vector_size(64)));
using LaneIntegers = std::int64_t __attribute__((vector_size(64)));

// A point per lane.
struct LanePoints {
  Lanes x, y, z;
};

// The fan's sixteen directions, two registers of eight, as coefficients on an orthonormal frame
// (u, e1, e2) where u points from the interior point centre(a) − centre(b) to the origin: lane 0
// is u itself, lanes 1–7 a ring of seven at 25° from it, lanes 8–15 a ring of eight at 60°
// (turned by half a step). Chosen on the random pair workload (it decides 91% of the pairs the
// sphere tests leave at N = 8, 87% at N = 16; docs/benchmarks.md).
struct FanFrame {
  std::array<Lanes, 2> alongU, alongE1, alongE2;
};
FanFrame fanFrame();

// Where the origin is when the fan test certifies an intersection: the tetrahedron of the
// interior point and three support points holding it, by vertex indices of a and b (slot 0 is
// the interior point, no vertex), and the origin's barycentric weights in it.
struct FanTetrahedron {
  std::array<std::uint32_t, 4> vertexA{}, vertexB{};
  std::array<double, 4> weight{};
};

namespace fan {

[[gnu::always_inline]] inline Lanes splat(double value) {
  return Lanes{} + value;
}
[[gnu::always_inline]] inline LanePoints splat(const Vec3& p) {
  return {splat(p.x()), splat(p.y()), splat(p.z())};
}
[[gnu::always_inline]] inline LanePoints minus(const LanePoints& p, const LanePoints& q) {
  return {p.x - q.x, p.y - q.y, p.z - q.z};
}
[[gnu::always_inline]] inline LanePoints cross(const LanePoints& p, const LanePoints& q) {
  return {p.y * q.z - p.z * q.y, p.z * q.x - p.x * q.z, p.x * q.y - p.y * q.x};
}
[[gnu::always_inline]] inline Lanes dot(const LanePoints& p, const LanePoints& q) {
  return p.x * q.x + p.y * q.y + p.z * q.z;
}
// Lane i takes lane order[i] of p.
template <int... kOrder>
[[gnu::always_inline]] inline LanePoints permuted(const LanePoints& p) {
  return {__builtin_shufflevector(p.x, p.x, kOrder...),
          __builtin_shufflevector(p.y, p.y, kOrder...),
          __builtin_shufflevector(p.z, p.z, kOrder...)};
}
template <int... kOrder>
[[gnu::always_inline]] inline Lanes permuted(const Lanes& p) {
  return __builtin_shufflevector(p, p, kOrder...);
}

}  // namespace fan

// Per lane of the directions `first` and `second`, a vertex of `chunks` maximising
// (kLowest: minimising) d·x, and that extreme. One pass over the vertices for both registers,
// even and odd vertices in separate chains (half the dependent compares), merged at the end.
template <bool kLowest>
[[gnu::always_inline]] inline void fanScan(const VertexChunk* chunks, std::size_t chunkCount,
                                           const LanePoints& first, const LanePoints& second,
                                           Lanes& firstExtreme, LaneIntegers& firstVertex,
                                           Lanes& secondExtreme, LaneIntegers& secondVertex) {
  const auto along = [&](const LanePoints& d, const VertexChunk& chunk, std::size_t lane) {
    return d.x * chunk.x[lane] + d.y * chunk.y[lane] + d.z * chunk.z[lane];
  };
  const auto better = [](const Lanes& candidate, const Lanes& best) {
    return kLowest ? candidate < best : candidate > best;
  };
  std::array<Lanes, 2> extreme0 = {along(first, chunks[0], 0), along(first, chunks[0], 1)};
  std::array<Lanes, 2> extreme1 = {along(second, chunks[0], 0), along(second, chunks[0], 1)};
  std::array<LaneIntegers, 2> vertex0 = {LaneIntegers{}, LaneIntegers{} + 1};
  std::array<LaneIntegers, 2> vertex1 = vertex0;
  for (std::size_t c = 0; c < chunkCount; ++c) {
    for (std::size_t lane = c == 0 ? 2 : 0; lane < kLaneWidth; ++lane) {
      const std::size_t parity = lane % 2;
      const auto index = static_cast<std::int64_t>(c * kLaneWidth + lane);
      const Lanes d0 = along(first, chunks[c], lane);
      const Lanes d1 = along(second, chunks[c], lane);
      const LaneIntegers better0 = better(d0, extreme0[parity]);
      const LaneIntegers better1 = better(d1, extreme1[parity]);
      extreme0[parity] = better0 ? d0 : extreme0[parity];
      extreme1[parity] = better1 ? d1 : extreme1[parity];
      vertex0[parity] = better0 ? index : vertex0[parity];
      vertex1[parity] = better1 ? index : vertex1[parity];
    }
  }
  const LaneIntegers odd0 = better(extreme0[1], extreme0[0]);
  const LaneIntegers odd1 = better(extreme1[1], extreme1[0]);
  firstExtreme = odd0 ? extreme0[1] : extreme0[0];
  firstVertex = odd0 ? vertex0[1] : vertex0[0];
  secondExtreme = odd1 ? extreme1[1] : extreme1[0];
  secondVertex = odd1 ? vertex1[1] : vertex1[0];
}

namespace fan {

[[gnu::always_inline]] inline Lanes larger(const Lanes& a, const Lanes& b) {
  return a > b ? a : b;
}
[[gnu::always_inline]] inline Lanes smaller(const Lanes& a, const Lanes& b) {
  return a < b ? a : b;
}
// Per lane, positive exactly when the four signed volumes of a tetrahedron share the strict sign
// of their sum, i.e. the origin is strictly inside it (originInsideTetrahedron()); zero or
// negative otherwise (a product that underflows reads as outside), NaN when a volume is (the sum,
// hence every product, is then NaN).
[[gnu::always_inline]] inline Lanes insideScore(const std::array<Lanes, 4>& volume) {
  const Lanes total = volume[0] + volume[1] + volume[2] + volume[3];
  return smaller(smaller(volume[0] * total, volume[1] * total),
                 smaller(volume[2] * total, volume[3] * total));
}

}  // namespace fan

// GJK's first support points for a and b (ScannedChunks of placed_pair.cpp: vertex chunks in one
// frame, their centres interior points), along −v0 and v0 for v0 = centre(a) − centre(b): the
// point of a − b farthest towards the origin from v0 (the portal test's first support too). True
// when it certifies a separation beyond `separation` (GJK's early exit).
template <class Chunks>
[[gnu::always_inline]] inline bool firstSupportSeparates(const Chunks& a, const Chunks& b,
                                                         double separation,
                                                         GjkFirstSupport<Chunks, Chunks>& first) {
  const Vec3 v0 = a.center() - b.center();
  first.pointA = a.support(-v0, first.hintA);
  first.pointB = b.support(v0, first.hintB);
  const double wv = (first.pointA - first.pointB).dot(v0);
  return wv > 0.0 && wv * wv > separation * separation * v0.squaredNorm();
}

// The fan test on a and b (as above; run after firstSupportSeparates() said no): `separated`
// when one of its sixteen support points p along d certifies p·d < −(margin + absolute)·|d| (the
// portal test's certificate), `intersecting` when the origin lies strictly inside one of 23
// tetrahedra of the interior point and three support points (each a point of a − b; the
// tetrahedron goes to `tetrahedron` when not null), else `unknown`. Kernels provides
// `gather(chunks, count, vertex, points)` (the lanes' vertices), `anyPositive(lanes)` (a lane >
// 0, NaN lanes not) and `inverseSquareRoot(x)` (approximate).
template <class Kernels, class Chunks>
[[gnu::always_inline]] inline PairVerdict fanVerdict(const FanFrame& frame, const Chunks& a,
                                                     const Chunks& b, double margin,
                                                     const GjkTolerance& tolerance,
                                                     FanTetrahedron* tetrahedron) {
  using namespace fan;
  const Vec3 v0 = a.center() - b.center();
  const double lengthSquared = v0.squaredNorm();
  if (!(lengthSquared > kShortestSquared)) return PairVerdict::unknown;
  const double separation = margin + tolerance.absolute;
  // u need not be exactly of unit length: only the fan's spread depends on it, every certificate
  // uses the directions as computed.
  const Vec3 u = -v0 * Kernels::inverseSquareRoot(lengthSquared);
  // An orthonormal frame around u (Duff et al., "Building an orthonormal basis, revisited", 2017).
  const double sign = std::copysign(1.0, u.z());
  const double scale = -1.0 / (sign + u.z());
  const double mixed = u.x() * u.y() * scale;
  const Vec3 e1(1.0 + sign * u.x() * u.x() * scale, sign * mixed, -sign * u.x());
  const Vec3 e2(mixed, sign + u.y() * u.y() * scale, -u.y());
  const auto directions = [&](std::size_t r) -> LanePoints {
    const auto along = [&](int axis) {
      return frame.alongU[r] * u[axis] + frame.alongE1[r] * e1[axis] + frame.alongE2[r] * e2[axis];
    };
    return {along(0), along(1), along(2)};
  };
  // Register 0: u and the inner ring (lanes 1–7); register 1: the outer ring.
  const LanePoints inner = directions(0);
  const LanePoints outer = directions(1);
  Lanes highA0, highA1, lowB0, lowB1;
  LaneIntegers vertexA0, vertexA1, vertexB0, vertexB1;
  fanScan<false>(a.chunks, a.count, inner, outer, highA0, vertexA0, highA1, vertexA1);
  fanScan<true>(b.chunks, b.count, inner, outer, lowB0, vertexB0, lowB1, vertexB1);

  // The largest p·d over a − b is highA − lowB; -pd·|pd| − separation²·|d|² is positive exactly
  // when pd < 0 and pd² > separation²·|d|² (the certificate).
  const auto separating = [separation](const Lanes& pd, const LanePoints& d) {
    const Lanes magnitude = pd < Lanes{} ? -pd : pd;
    return -pd * magnitude - separation * separation * dot(d, d);
  };
  if (Kernels::anyPositive(
          larger(separating(highA0 - lowB0, inner), separating(highA1 - lowB1, outer)))) {
    return PairVerdict::separated;
  }

  LanePoints onA, onB;
  Kernels::gather(a.chunks, a.count, vertexA0, onA);
  Kernels::gather(b.chunks, b.count, vertexB0, onB);
  const LanePoints first = minus(onA, onB);
  Kernels::gather(a.chunks, a.count, vertexA1, onA);
  Kernels::gather(b.chunks, b.count, vertexB1, onB);
  const LanePoints second = minus(onA, onB);
  const LanePoints w0 = splat(v0);
  const LanePoints p0 = {splat(first.x[0]), splat(first.y[0]), splat(first.z[0])};
  // The next point of each ring (lane 0 of the first register maps to itself: a flat
  // tetrahedron, which never holds the origin strictly).
  const LanePoints firstNext = permuted<0, 2, 3, 4, 5, 6, 7, 1>(first);
  const LanePoints secondNext = permuted<1, 2, 3, 4, 5, 6, 7, 0>(second);
  // Three families of tetrahedra, one per register of lanes: fans (w0, p0, ring_k, ring_k+1)
  // around each ring, and (w0, inner_k, outer_k, outer_k+1). Their signed volumes (those of
  // originInsideTetrahedron(), with the origin in place of each vertex) share cross products.
  const LanePoints m = cross(w0, p0);
  const LanePoints firstEdge = cross(first, firstNext);
  const LanePoints secondEdge = cross(second, secondNext);
  const Lanes firstSide = dot(m, first);
  const Lanes secondSide = dot(m, second);
  const Lanes secondBase = -dot(w0, secondEdge);
  const LanePoints toFirst = cross(w0, first);
  const std::array<std::array<Lanes, 4>, 3> volumes = {{
      {dot(p0, firstEdge), -dot(w0, firstEdge), permuted<0, 2, 3, 4, 5, 6, 7, 1>(firstSide),
       -firstSide},
      {dot(p0, secondEdge), secondBase, permuted<1, 2, 3, 4, 5, 6, 7, 0>(secondSide), -secondSide},
      {dot(first, secondEdge), secondBase, dot(secondNext, toFirst), -dot(second, toFirst)},
  }};
  const std::array<Lanes, 3> score = {insideScore(volumes[0]), insideScore(volumes[1]),
                                      insideScore(volumes[2])};
  if (!Kernels::anyPositive(larger(larger(score[0], score[1]), score[2]))) {
    return PairVerdict::unknown;
  }
  if (tetrahedron == nullptr) return PairVerdict::intersecting;
  // The first family and lane holding the origin, for the weights and the vertices.
  const std::array<const LaneIntegers*, 2> vertexA = {&vertexA0, &vertexA1};
  const std::array<const LaneIntegers*, 2> vertexB = {&vertexB0, &vertexB1};
  for (std::size_t family = 0; family < 3; ++family) {
    for (std::size_t lane = 0; lane < kLaneWidth; ++lane) {
      if (!(score[family][lane] > 0.0)) continue;
      // (register, lane) of vertices 1..3 of the tetrahedron (vertex 0 is w0).
      const std::size_t next = family == 0 ? lane % 7 + 1 : (lane + 1) % kLaneWidth;
      using Slot = std::array<std::size_t, 2>;
      const std::array<Slot, 3> slot =
          family == 2 ? std::array<Slot, 3>{{{0, lane}, {1, lane}, {1, next}}}
                      : std::array<Slot, 3>{{{0, 0}, {family, lane}, {family, next}}};
      const std::array<Lanes, 4>& c = volumes[family];
      const double total = c[0][lane] + c[1][lane] + c[2][lane] + c[3][lane];
      for (std::size_t k = 0; k < 4; ++k) tetrahedron->weight[k] = c[k][lane] / total;
      for (std::size_t k = 0; k < 3; ++k) {
        tetrahedron->vertexA[k + 1] =
            static_cast<std::uint32_t>((*vertexA[slot[k][0]])[slot[k][1]]);
        tetrahedron->vertexB[k + 1] =
            static_cast<std::uint32_t>((*vertexB[slot[k][0]])[slot[k][1]]);
      }
      return PairVerdict::intersecting;
    }
  }
  return PairVerdict::intersecting;  // not reached: some lane is positive
}

}  // namespace kaboum::collision::detail
