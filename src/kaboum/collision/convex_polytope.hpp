// Convex polytopes for the narrow phase (thesis §4.1, §4.4: every convex piece of a bounding
// convex decomposition): vertices with their edge graph for hill-climbing support mapping, and
// rigid transforms applied to the query direction, never to the vertices.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/gjk.hpp"
#include "kaboum/collision/support_mapping.hpp"
#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

// Eight vertices' coordinates side by side, the unit of the vectorised support scan (one
// AVX-512 register per coordinate).
inline constexpr std::size_t kLaneWidth = 8;
struct alignas(64) VertexChunk {
  std::array<double, kLaneWidth> x, y, z;
};

namespace detail {
// The first vertex of `chunkCount` chunks (padded as ConvexPolytope's) maximising direction.x:
// a scalar loop (any x86-64), and branch-free vector lanes (only where the CPU has AVX2 /
// AVX-512F).
std::uint32_t scanVertexChunksScalar(const VertexChunk* chunks, std::size_t chunkCount,
                                     const Vec3& direction);
[[gnu::target("avx2")]] std::uint32_t scanVertexChunksAvx2(const VertexChunk* chunks,
                                                           std::size_t chunkCount,
                                                           const Vec3& direction);
[[gnu::target("avx512f")]] std::uint32_t scanVertexChunksAvx512(const VertexChunk* chunks,
                                                                std::size_t chunkCount,
                                                                const Vec3& direction);
// One of them, chosen for the CPU once (GCC function multiversioning, an ifunc).
[[gnu::target("default")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                          std::size_t chunkCount,
                                                          const Vec3& direction);
[[gnu::target("avx2")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                       std::size_t chunkCount,
                                                       const Vec3& direction);
[[gnu::target("avx512f")]] std::uint32_t scanVertexChunks(const VertexChunk* chunks,
                                                          std::size_t chunkCount,
                                                          const Vec3& direction);
}  // namespace detail

// The convex hull of a point set in its own (local) frame. Satisfies SupportMapping.
static_assert(sizeof(Vec3) == 3 * sizeof(double), "support loops read vertices as packed doubles");

class ConvexPolytope {
 public:
  static constexpr std::uint32_t kNoVertex = UINT32_MAX;
  // The vertex the last support query returned; the next query starts climbing there. A cold
  // (default) hint starts from the best of the vertices extreme along 14 fixed directions.
  struct Hint {
    std::uint32_t vertex = kNoVertex;
  };

  // Up to this many vertices, support() scans all of them (measured faster than climbing,
  // see docs/collision.md); above, it climbs the edge graph.
  static constexpr std::size_t kBruteForceMaxVertices = 64;

  // The hull of `points` (interior and duplicated points dropped). Throws InputError (naming
  // `what`) for fewer than four points, non-finite points or points without volume.
  explicit ConvexPolytope(std::span<const Vec3> points, const std::string& what = "points");
  // A hull already computed by convexHull(): its vertices, and its triangle edges as the graph.
  explicit ConvexPolytope(const ConvexHull& hull);

  // A vertex maximising direction.x; ties go to the first one found.
  [[nodiscard]] Vec3 support(const Vec3& direction, Hint& hint) const {
    const std::uint32_t index = supportIndex(direction, hint);
    const VertexChunk& chunk = chunks_[index / kLaneWidth];
    const std::uint32_t lane = index % kLaneWidth;
    return {chunk.x[lane], chunk.y[lane], chunk.z[lane]};
  }
  // Index of that vertex (also stored in `hint`).
  [[nodiscard]] std::uint32_t supportIndex(const Vec3& direction, Hint& hint) const;
  // Vertex `index` (as support() returns it; a VertexSupport).
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const { return vertices_[index]; }
  // The mean of the vertices (an interior point).
  [[nodiscard]] Vec3 center() const { return center_; }

  [[nodiscard]] const std::vector<Vec3>& vertices() const { return vertices_; }
  [[nodiscard]] std::size_t vertexCount() const { return vertices_.size(); }
  // The vertices in the support scan's layout (chunks of kLaneWidth, the last padded).
  [[nodiscard]] std::span<const VertexChunk> chunks() const { return chunks_; }
  // Vertices sharing a hull edge with vertex `index`.
  [[nodiscard]] std::span<const std::uint32_t> neighbors(std::uint32_t index) const {
    return {neighbors_.data() + neighborBegin_[index],
            neighbors_.data() + neighborBegin_[index + 1]};
  }

  // Axis-aligned box and a bounding sphere in the local frame, for cheap rejection. The sphere
  // is close to the smallest enclosing one (its radius is exact for its centre).
  [[nodiscard]] const Eigen::AlignedBox3d& localBox() const { return box_; }
  [[nodiscard]] const Vec3& boundingSphereCenter() const { return sphereCenter_; }
  [[nodiscard]] double boundingSphereRadius() const { return sphereRadius_; }
  // A ball inside the polytope (close to the largest one; its radius is the exact facet clearance
  // of its centre), for cheap acceptance: two such balls overlapping prove the polytopes do.
  [[nodiscard]] const Vec3& innerSphereCenter() const { return innerCenter_; }
  [[nodiscard]] double innerSphereRadius() const { return innerRadius_; }

 private:
  std::uint32_t climb(const Vec3& direction, std::uint32_t start) const;
  std::uint32_t bestSeed(const Vec3& direction) const;
  std::uint32_t scan(const Vec3& direction) const;

  // The vertices as given by the hull (climbing reads these as packed x y z x y z ...).
  std::vector<Vec3> vertices_;
  // The same coordinates in chunks of kLaneWidth (the last padded with copies of vertex 0, which
  // never win a tie against it): what scan() and support() read.
  std::vector<VertexChunk> chunks_;
  // Compressed adjacency: neighbors of vertex i are neighbors_[neighborBegin_[i] ..
  // neighborBegin_[i+1]).
  std::vector<std::uint32_t> neighborBegin_;
  std::vector<std::uint32_t> neighbors_;
  // Distinct vertices extreme along ±x, ±y, ±z and the 8 diagonals: cold climbing starts.
  std::vector<std::uint32_t> seeds_;
  Vec3 center_;
  Eigen::AlignedBox3d box_;
  Vec3 sphereCenter_;
  double sphereRadius_ = 0.0;
  Vec3 innerCenter_;
  double innerRadius_ = 0.0;
};

// A polytope placed by a rigid transform (local → world). The direction is rotated into the
// local frame and the support vertex back out, so no vertex is copied. Holds a reference: the
// polytope must outlive it. Satisfies SupportMapping.
inline std::uint32_t ConvexPolytope::supportIndex(const Vec3& direction, Hint& hint) const {
  if (vertices_.size() <= kBruteForceMaxVertices) {
    hint.vertex = scan(direction);
  } else {
    hint.vertex =
        climb(direction, hint.vertex < vertices_.size() ? hint.vertex : bestSeed(direction));
  }
  return hint.vertex;
}

inline std::uint32_t ConvexPolytope::bestSeed(const Vec3& direction) const {
  std::uint32_t best = seeds_.front();
  double bestDot = direction.dot(vertices_[best]);
  for (const std::uint32_t seed : seeds_) {
    const double d = direction.dot(vertices_[seed]);
    if (d > bestDot) {
      bestDot = d;
      best = seed;
    }
  }
  return best;
}

inline std::uint32_t ConvexPolytope::scan(const Vec3& direction) const {
  return detail::scanVertexChunks(chunks_.data(), chunks_.size(), direction);
}

// Steepest ascent on the edge graph: on a convex polytope a vertex no neighbor improves on is a
// global maximum.
inline std::uint32_t ConvexPolytope::climb(const Vec3& direction, std::uint32_t start) const {
  const double dx = direction.x();
  const double dy = direction.y();
  const double dz = direction.z();
  const double* p = vertices_.front().data();
  const auto dot = [&](std::uint32_t v) {
    return dx * p[3 * v] + dy * p[3 * v + 1] + dz * p[3 * v + 2];
  };
  std::uint32_t current = start;
  double currentDot = dot(current);
  for (;;) {
    const std::uint32_t from = current;
    for (std::uint32_t i = neighborBegin_[from]; i < neighborBegin_[from + 1]; ++i) {
      const double d = dot(neighbors_[i]);
      if (d > currentDot) {
        currentDot = d;
        current = neighbors_[i];
      }
    }
    if (current == from) return current;
  }
}

class TransformedSupport {
 public:
  using Hint = ConvexPolytope::Hint;

  TransformedSupport(const ConvexPolytope& polytope, const Eigen::Isometry3d& pose)
      : polytope_(&polytope), rotation_(pose.linear()), translation_(pose.translation()) {}
  TransformedSupport(const ConvexPolytope& polytope, const Eigen::Matrix3d& rotation,
                     const Vec3& translation)
      : polytope_(&polytope), rotation_(rotation), translation_(translation) {}

  [[nodiscard]] Vec3 support(const Vec3& direction, Hint& hint) const {
    // Written out: Eigen's expression templates are not always inlined at -O2 on this hot path.
    const Eigen::Matrix3d& r = rotation_;
    const Vec3& d = direction;
    const Vec3 local(r(0, 0) * d.x() + r(1, 0) * d.y() + r(2, 0) * d.z(),
                     r(0, 1) * d.x() + r(1, 1) * d.y() + r(2, 1) * d.z(),
                     r(0, 2) * d.x() + r(1, 2) * d.y() + r(2, 2) * d.z());
    return place(polytope_->support(local, hint));
  }
  [[nodiscard]] Vec3 center() const { return place(polytope_->center()); }
  // The polytope's vertex `index`, placed (a VertexSupport).
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const { return place(polytope_->vertex(index)); }
  // A point of the polytope's local frame, placed (written out, as support()).
  [[nodiscard]] Vec3 place(const Vec3& p) const {
    const Eigen::Matrix3d& r = rotation_;
    return {r(0, 0) * p.x() + r(0, 1) * p.y() + r(0, 2) * p.z() + translation_.x(),
            r(1, 0) * p.x() + r(1, 1) * p.y() + r(1, 2) * p.z() + translation_.y(),
            r(2, 0) * p.x() + r(2, 1) * p.y() + r(2, 2) * p.z() + translation_.z()};
  }

  [[nodiscard]] const ConvexPolytope& polytope() const { return *polytope_; }
  [[nodiscard]] const Eigen::Matrix3d& rotation() const { return rotation_; }
  [[nodiscard]] const Vec3& translation() const { return translation_; }

 private:
  const ConvexPolytope* polytope_;
  Eigen::Matrix3d rotation_;
  Vec3 translation_;
};

static_assert(detail::VertexSupport<ConvexPolytope>);
static_assert(detail::VertexSupport<TransformedSupport>);

namespace detail {

using LocalPairCache = GjkCache<ConvexPolytope, TransformedSupport>;

// Whether the placed pair queries below apply: both polytopes are scanned, not climbed.
inline bool scansBoth(const ConvexPolytope& a, const ConvexPolytope& b) {
  return a.vertexCount() <= ConvexPolytope::kBruteForceMaxVertices &&
         b.vertexCount() <= ConvexPolytope::kBruteForceMaxVertices;
}

// The pair queries (portal test then GJK for the boolean, GJK for the distance; gjk.hpp) with
// b's vertices placed in a's frame once per query, so that every support call is two plain
// scans: no direction or point is transformed inside the loops. Requires scansBoth(a, b).
// Scalar, AVX2 and AVX-512 builds of the whole query (each scan inlined); the unsuffixed
// overloads pick one per CPU (GCC function multiversioning). The cache may be null (cold start).
bool intersectsPlacedScalar(const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
                            const GjkTolerance& tolerance);
[[gnu::target("avx2")]] bool intersectsPlacedAvx2(const ConvexPolytope& a,
                                                  const TransformedSupport& bInA, double margin,
                                                  const GjkTolerance& tolerance);
[[gnu::target("avx512f")]] bool intersectsPlacedAvx512(const ConvexPolytope& a,
                                                       const TransformedSupport& bInA,
                                                       double margin,
                                                       const GjkTolerance& tolerance);
[[gnu::target("default")]] bool intersectsPlaced(const ConvexPolytope& a,
                                                 const TransformedSupport& bInA, double margin,
                                                 const GjkTolerance& tolerance);
[[gnu::target("avx2")]] bool intersectsPlaced(const ConvexPolytope& a,
                                              const TransformedSupport& bInA, double margin,
                                              const GjkTolerance& tolerance);
[[gnu::target("avx512f")]] bool intersectsPlaced(const ConvexPolytope& a,
                                                 const TransformedSupport& bInA, double margin,
                                                 const GjkTolerance& tolerance);
DistanceResult distancePlacedScalar(const ConvexPolytope& a, const TransformedSupport& bInA,
                                    LocalPairCache* cache, const GjkTolerance& tolerance);
[[gnu::target("avx2")]] DistanceResult distancePlacedAvx2(const ConvexPolytope& a,
                                                          const TransformedSupport& bInA,
                                                          LocalPairCache* cache,
                                                          const GjkTolerance& tolerance);
[[gnu::target("avx512f")]] DistanceResult distancePlacedAvx512(const ConvexPolytope& a,
                                                               const TransformedSupport& bInA,
                                                               LocalPairCache* cache,
                                                               const GjkTolerance& tolerance);
[[gnu::target("default")]] DistanceResult distancePlaced(const ConvexPolytope& a,
                                                         const TransformedSupport& bInA,
                                                         LocalPairCache* cache,
                                                         const GjkTolerance& tolerance);
[[gnu::target("avx2")]] DistanceResult distancePlaced(const ConvexPolytope& a,
                                                      const TransformedSupport& bInA,
                                                      LocalPairCache* cache,
                                                      const GjkTolerance& tolerance);
[[gnu::target("avx512f")]] DistanceResult distancePlaced(const ConvexPolytope& a,
                                                         const TransformedSupport& bInA,
                                                         LocalPairCache* cache,
                                                         const GjkTolerance& tolerance);

// The fan test of the AVX-512 build (fan_test.hpp: GJK's first support, then sixteen support
// directions at once) as the boolean query runs it after the sphere tests, on b placed in a's
// frame; `unknown` where it does not run (polytopes above 16 vertices, CPUs without AVX-512).
// For tests and the benchmark's decision counts.
PairVerdict fanPretest(const ConvexPolytope& a, const TransformedSupport& bInA, double margin,
                       const GjkTolerance& tolerance);

// sphereVerdict() with each polytope's sphere centres placed into a common frame by `placeA`
// and `placeB` (callables Vec3 -> Vec3); the inner balls are only placed when needed.
template <class PlaceA, class PlaceB>
PairVerdict sphereVerdict(const ConvexPolytope& a, const PlaceA& placeA, const ConvexPolytope& b,
                          const PlaceB& placeB, double margin, const GjkTolerance& tolerance) {
  const double outerReach =
      a.boundingSphereRadius() + b.boundingSphereRadius() + margin + tolerance.absolute;
  if ((placeB(b.boundingSphereCenter()) - placeA(a.boundingSphereCenter())).squaredNorm() >
      outerReach * outerReach) {
    return PairVerdict::separated;
  }
  const double innerReach = a.innerSphereRadius() + b.innerSphereRadius() + margin;
  if ((placeB(b.innerSphereCenter()) - placeA(a.innerSphereCenter())).squaredNorm() <=
      innerReach * innerReach) {
    return PairVerdict::intersecting;
  }
  return PairVerdict::unknown;
}

}  // namespace detail

// Conservative pre-test of a pair from the polytopes' spheres, with b placed in a's frame (the
// frame of a's vertices): `separated` when the bounding spheres are more than margin +
// tolerance.absolute apart (the distance is at least their gap), `intersecting` when the inner
// balls come within margin (they lie inside the polytopes), `unknown` otherwise.
inline PairVerdict sphereVerdict(const ConvexPolytope& a, const TransformedSupport& b,
                                 double margin = 0.0, const GjkTolerance& tolerance = {}) {
  return detail::sphereVerdict(
      a, [](const Vec3& p) { return p; }, b.polytope(), [&b](const Vec3& p) { return b.place(p); },
      margin, tolerance);
}

// The same with both polytopes placed (in world frame: no relative pose needed).
inline PairVerdict sphereVerdict(const TransformedSupport& a, const TransformedSupport& b,
                                 double margin = 0.0, const GjkTolerance& tolerance = {}) {
  return detail::sphereVerdict(
      a.polytope(), [&a](const Vec3& p) { return a.place(p); }, b.polytope(),
      [&b](const Vec3& p) { return b.place(p); }, margin, tolerance);
}

// The pair queries of gjk.hpp for a polytope in its own frame and one placed in that frame,
// sphereVerdict() first (chosen over the generic templates of gjk.hpp).
inline bool intersects(const ConvexPolytope& a, const TransformedSupport& b, double margin = 0.0,
                       GjkCache<ConvexPolytope, TransformedSupport>* cache = nullptr,
                       const GjkTolerance& tolerance = {}) {
  const PairVerdict verdict = sphereVerdict(a, b, margin, tolerance);
  if (verdict != PairVerdict::unknown) return verdict == PairVerdict::intersecting;
  if (cache == nullptr && detail::scansBoth(a, b.polytope())) {
    return detail::intersectsPlaced(a, b, margin, tolerance);
  }
  return intersects<ConvexPolytope, TransformedSupport>(a, b, margin, cache, tolerance);
}

// When the inner balls overlap, the pair intersects at a point of the segment between their
// centres that lies in both balls; otherwise GJK.
inline DistanceResult distance(const ConvexPolytope& a, const TransformedSupport& b,
                               GjkCache<ConvexPolytope, TransformedSupport>* cache = nullptr,
                               const GjkTolerance& tolerance = {}) {
  const Vec3 centerB = b.place(b.polytope().innerSphereCenter());
  const double radiusA = a.innerSphereRadius();
  const double reach = radiusA + b.polytope().innerSphereRadius();
  if (reach > 0.0 && (centerB - a.innerSphereCenter()).squaredNorm() <= reach * reach) {
    DistanceResult result;
    result.intersecting = true;
    result.pointA = a.innerSphereCenter() + (radiusA / reach) * (centerB - a.innerSphereCenter());
    result.pointB = result.pointA;
    return result;
  }
  if (detail::scansBoth(a, b.polytope())) return detail::distancePlaced(a, b, cache, tolerance);
  return distance<ConvexPolytope, TransformedSupport>(a, b, cache, tolerance);
}

namespace detail {

// Written out entry by entry: neither Eigen's small products nor a loop over the nine entries
// is unrolled at -O2 (120–200 instructions, and a store-forwarding stall, here).
inline TransformedSupport inFrameOf(const TransformedSupport& a, const TransformedSupport& b) {
  const Eigen::Matrix3d& ra = a.rotation();
  const Eigen::Matrix3d& rb = b.rotation();
  const auto entry = [&](int i, int j) {
    return ra(0, i) * rb(0, j) + ra(1, i) * rb(1, j) + ra(2, i) * rb(2, j);
  };
  Eigen::Matrix3d rotation;
  rotation(0, 0) = entry(0, 0);
  rotation(1, 0) = entry(1, 0);
  rotation(2, 0) = entry(2, 0);
  rotation(0, 1) = entry(0, 1);
  rotation(1, 1) = entry(1, 1);
  rotation(2, 1) = entry(2, 1);
  rotation(0, 2) = entry(0, 2);
  rotation(1, 2) = entry(1, 2);
  rotation(2, 2) = entry(2, 2);
  const Vec3 t = b.translation() - a.translation();
  const Vec3 translation(ra(0, 0) * t.x() + ra(1, 0) * t.y() + ra(2, 0) * t.z(),
                         ra(0, 1) * t.x() + ra(1, 1) * t.y() + ra(2, 1) * t.z(),
                         ra(0, 2) * t.x() + ra(1, 2) * t.y() + ra(2, 2) * t.z());
  return {b.polytope(), rotation, translation};
}

using PlacedPairCache = GjkCache<TransformedSupport, TransformedSupport>;

// Runs `query(local cache or nullptr)` with the placed cache's state moved into a's frame and
// back: a null cache stays null (a cold query).
template <class Query>
auto withLocalCache(PlacedPairCache* cache, Query&& query) {
  if (cache == nullptr) return query(nullptr);
  LocalPairCache local{cache->direction, cache->hintA, cache->hintB};
  auto result = query(&local);
  *cache = {local.direction, local.hintA, local.hintB};
  return result;
}

}  // namespace detail

// GJK between two placed polytopes runs in a's local frame: b is placed by the relative pose
// a⁻¹ b, so a's support is a plain scan and only b's direction and point are transformed. These
// overloads are chosen over the generic templates of gjk.hpp; a cache used with them keeps its
// direction in a's frame (use one cache with one overload family per pair).
//
// The sphere pre-tests run on the world-frame centres first: the relative pose is only formed
// for the pairs they leave undecided.
inline bool intersects(const TransformedSupport& a, const TransformedSupport& b,
                       double margin = 0.0, detail::PlacedPairCache* cache = nullptr,
                       const GjkTolerance& tolerance = {}) {
  const PairVerdict verdict = sphereVerdict(a, b, margin, tolerance);
  if (verdict != PairVerdict::unknown) return verdict == PairVerdict::intersecting;
  const TransformedSupport bInA = detail::inFrameOf(a, b);
  if (cache == nullptr && detail::scansBoth(a.polytope(), b.polytope())) {
    return detail::intersectsPlaced(a.polytope(), bInA, margin, tolerance);
  }
  return detail::withLocalCache(cache, [&](detail::LocalPairCache* local) {
    return intersects<ConvexPolytope, TransformedSupport>(a.polytope(), bInA, margin, local,
                                                          tolerance);
  });
}

inline DistanceResult distance(const TransformedSupport& a, const TransformedSupport& b,
                               detail::PlacedPairCache* cache = nullptr,
                               const GjkTolerance& tolerance = {}) {
  const TransformedSupport bInA = detail::inFrameOf(a, b);
  DistanceResult result = detail::withLocalCache(cache, [&](detail::LocalPairCache* local) {
    return distance(a.polytope(), bInA, local, tolerance);
  });
  result.pointA = a.place(result.pointA);
  result.pointB = a.place(result.pointB);
  return result;
}

}  // namespace kaboum::collision
