// Convex polytopes for the narrow phase (thesis §4.1, §4.4: every convex piece of a bounding
// convex decomposition): vertices with their edge graph for hill-climbing support mapping, and
// rigid transforms applied to the query direction, never to the vertices.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/gjk.hpp"
#include "kaboum/collision/support_mapping.hpp"
#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::collision {

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
    return vertices_[supportIndex(direction, hint)];
  }
  // Index of that vertex (also stored in `hint`).
  [[nodiscard]] std::uint32_t supportIndex(const Vec3& direction, Hint& hint) const;
  // The mean of the vertices (an interior point).
  [[nodiscard]] Vec3 center() const { return center_; }

  [[nodiscard]] const std::vector<Vec3>& vertices() const { return vertices_; }
  [[nodiscard]] std::size_t vertexCount() const { return vertices_.size(); }
  // Vertices sharing a hull edge with vertex `index`.
  [[nodiscard]] std::span<const std::uint32_t> neighbors(std::uint32_t index) const {
    return {neighbors_.data() + neighborBegin_[index],
            neighbors_.data() + neighborBegin_[index + 1]};
  }

  // Axis-aligned box and a bounding sphere in the local frame, for cheap rejection.
  [[nodiscard]] const Eigen::AlignedBox3d& localBox() const { return box_; }
  [[nodiscard]] const Vec3& boundingSphereCenter() const { return sphereCenter_; }
  [[nodiscard]] double boundingSphereRadius() const { return sphereRadius_; }

 private:
  std::uint32_t climb(const Vec3& direction, std::uint32_t start) const;
  std::uint32_t bestSeed(const Vec3& direction) const;
  std::uint32_t scan(const Vec3& direction) const;

  // Eigen::Vector3d is three unpadded doubles, so the support loops read these as packed
  // x y z x y z ... (one copy of the coordinates: the workload is often cache-cold).
  std::vector<Vec3> vertices_;
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
  const double dx = direction.x();
  const double dy = direction.y();
  const double dz = direction.z();
  const double* p = vertices_.front().data();
  std::uint32_t best = 0;
  double bestDot = dx * p[0] + dy * p[1] + dz * p[2];
  const auto n = static_cast<std::uint32_t>(vertices_.size());
  for (std::uint32_t i = 1; i < n; ++i) {
    const double d = dx * p[3 * i] + dy * p[3 * i + 1] + dz * p[3 * i + 2];
    if (d > bestDot) {
      bestDot = d;
      best = i;
    }
  }
  return best;
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
    const Vec3& p = polytope_->support(local, hint);
    return {r(0, 0) * p.x() + r(0, 1) * p.y() + r(0, 2) * p.z() + translation_.x(),
            r(1, 0) * p.x() + r(1, 1) * p.y() + r(1, 2) * p.z() + translation_.y(),
            r(2, 0) * p.x() + r(2, 1) * p.y() + r(2, 2) * p.z() + translation_.z()};
  }
  [[nodiscard]] Vec3 center() const { return rotation_ * polytope_->center() + translation_; }

  [[nodiscard]] const ConvexPolytope& polytope() const { return *polytope_; }
  [[nodiscard]] const Eigen::Matrix3d& rotation() const { return rotation_; }
  [[nodiscard]] const Vec3& translation() const { return translation_; }

 private:
  const ConvexPolytope* polytope_;
  Eigen::Matrix3d rotation_;
  Vec3 translation_;
};

static_assert(SupportMapping<ConvexPolytope>);
static_assert(SupportMapping<TransformedSupport>);

// GJK between two placed polytopes runs in a's local frame: b is placed by the relative pose
// a⁻¹ b, so a's support is a plain scan and only b's direction and point are transformed. These
// overloads are chosen over the generic templates of gjk.hpp; a cache used with them keeps its
// direction in a's frame (use one cache with one overload family per pair).
namespace detail {

inline TransformedSupport inFrameOf(const TransformedSupport& a, const TransformedSupport& b) {
  const Eigen::Matrix3d toA = a.rotation().transpose();
  return {b.polytope(), toA * b.rotation(), toA * (b.translation() - a.translation())};
}

using PlacedPairCache = GjkCache<TransformedSupport, TransformedSupport>;
using LocalPairCache = GjkCache<ConvexPolytope, TransformedSupport>;

inline LocalPairCache localCache(const PlacedPairCache* cache) {
  if (cache == nullptr) return {};
  return {cache->direction, cache->hintA, cache->hintB};
}

inline void storeCache(const LocalPairCache& local, PlacedPairCache* cache) {
  if (cache != nullptr) *cache = {local.direction, local.hintA, local.hintB};
}

}  // namespace detail

inline bool intersects(const TransformedSupport& a, const TransformedSupport& b,
                       double margin = 0.0, detail::PlacedPairCache* cache = nullptr,
                       const GjkTolerance& tolerance = {}) {
  detail::LocalPairCache local = detail::localCache(cache);
  const bool hit = intersects(a.polytope(), detail::inFrameOf(a, b), margin, &local, tolerance);
  detail::storeCache(local, cache);
  return hit;
}

inline DistanceResult distance(const TransformedSupport& a, const TransformedSupport& b,
                               detail::PlacedPairCache* cache = nullptr,
                               const GjkTolerance& tolerance = {}) {
  detail::LocalPairCache local = detail::localCache(cache);
  DistanceResult result = distance(a.polytope(), detail::inFrameOf(a, b), &local, tolerance);
  detail::storeCache(local, cache);
  result.pointA = a.rotation() * result.pointA + a.translation();
  result.pointB = a.rotation() * result.pointB + a.translation();
  return result;
}

}  // namespace kaboum::collision
