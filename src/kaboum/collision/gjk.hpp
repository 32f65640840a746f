// GJK (Gilbert–Johnson–Keerthi) on any two support mappings: the convex–convex query every
// collision predicate of thesis §4.1 (Definition 1) and §4.5 reduces to. Boolean "distance <=
// margin" with a separating-axis early exit, and separation distance with witness points.
// Sub-algorithm: signed volumes (Montanari, Petrinic & Barbieri 2017). No heap allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "kaboum/collision/simplex.hpp"
#include "kaboum/collision/support_mapping.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

// Termination tolerances (lengths in the shapes' units; see docs/collision.md). `absolute`
// must exceed the rounding error of the coordinates (1e-10 suits |x| up to ~1e4).
struct GjkTolerance {
  double absolute = 1e-10;
  double relative = 1e-9;
  int maxIterations = 128;
};

// Per-pair warm start: the last query's search direction and both shapes' support hints. Reuse
// one cache for the same (a, b) pair from query to query; a zero direction means cold start.
template <SupportMapping A, SupportMapping B>
struct GjkCache {
  Vec3 direction = Vec3::Zero();
  typename A::Hint hintA{};
  typename B::Hint hintB{};
};

struct DistanceResult {
  // Never above the true distance (a certified lower bound); 0 when the shapes intersect.
  double distance = 0.0;
  // Witness points on a and b; |pointA - pointB| is within the tolerance above `distance`.
  // When intersecting, both are (up to rounding) one common point.
  Vec3 pointA = Vec3::Zero();
  Vec3 pointB = Vec3::Zero();
  bool intersecting = false;
  int iterations = 0;
};

namespace detail {

// Directions shorter than this (squared) are not used: squaring them would underflow.
constexpr double kShortestSquared = 1e-200;

// A support mapping whose support points are vertices it can give again by index (the index is
// in its hint after each support call): distance queries keep the indices of the simplex's points
// and form the witness points once at the end.
template <class Shape>
concept VertexSupport = SupportMapping<Shape> &&
    requires(const Shape& shape, const typename Shape::Hint& hint) {
  { shape.vertex(hint.vertex) } -> std::same_as<Vec3>;
};

// Where a simplex point of a − b came from, for the witness points: the support points of a and
// b themselves, or their vertex indices when both shapes are VertexSupport.
template <class A, class B>
struct SupportOrigin {
  Vec3 a, b;
  static SupportOrigin of(const Vec3& pointA, const Vec3& pointB, const typename A::Hint&,
                          const typename B::Hint&) {
    return {pointA, pointB};
  }
  [[nodiscard]] Vec3 onA(const A&) const { return a; }
  [[nodiscard]] Vec3 onB(const B&) const { return b; }
};
template <VertexSupport A, VertexSupport B>
struct SupportOrigin<A, B> {
  std::uint32_t a = 0, b = 0;
  static SupportOrigin of(const Vec3&, const Vec3&, const typename A::Hint& hintA,
                          const typename B::Hint& hintB) {
    return {hintA.vertex, hintB.vertex};
  }
  [[nodiscard]] Vec3 onA(const A& shape) const { return shape.vertex(a); }
  [[nodiscard]] Vec3 onB(const B& shape) const { return shape.vertex(b); }
};

enum class GjkExit { separated, intersecting, converged, stalled };

// What the GJK loop ends with: the simplex (its points' origins for distance queries), the best
// certified lower bound (distance mode), the iterations run and why it stopped.
template <class Origin>
struct GjkRun {
  Simplex<Origin> simplex;
  double lowerBound = 0.0;
  int iterations = 0;
  GjkExit exit = GjkExit::stalled;
};

// The support points of a cold query's first iteration (a's along −v, b's along v, for v =
// center(a) − center(b)) and the hints they leave, when a pre-test computed them already.
template <SupportMapping A, SupportMapping B>
struct GjkFirstSupport {
  Vec3 pointA, pointB;
  typename A::Hint hintA{};
  typename B::Hint hintB{};
};

// The GJK loop. Boolean mode stops as soon as a support point certifies distance > margin +
// tolerance.absolute, or the simplex comes within margin + tolerance.absolute of the origin;
// distance mode runs to convergence, tracks the best certified lower bound and records where each
// simplex point came from. `first` (cold queries only) replaces the first support calls.
template <bool kBoolean, SupportMapping A, SupportMapping B>
auto runGjk(const A& a, const B& b, double margin, GjkCache<A, B>* cache,
            const GjkTolerance& tolerance, const GjkFirstSupport<A, B>* first = nullptr) {
  using Origin = std::conditional_t<kBoolean, NoOrigin, SupportOrigin<A, B>>;
  GjkRun<Origin> run;
  Simplex<Origin>& simplex = run.simplex;
  typename A::Hint hintA{};
  typename B::Hint hintB{};
  Vec3 v = Vec3::Zero();
  if (cache != nullptr) {
    hintA = cache->hintA;
    hintB = cache->hintB;
    v = cache->direction;
  }
  if (!(v.squaredNorm() > kShortestSquared)) v = a.center() - b.center();
  if (!(v.squaredNorm() > kShortestSquared)) v = Vec3::UnitX();

  const double separation = margin + tolerance.absolute;
  for (run.iterations = 1; run.iterations <= tolerance.maxIterations; ++run.iterations) {
    // w minimises x.v over a − b, so x.v >= w.v for every x: the plane through w normal to v
    // bounds the distance from below by w.v / |v|.
    Vec3 pointA, pointB;
    if (first != nullptr && run.iterations == 1) {
      pointA = first->pointA;
      pointB = first->pointB;
      hintA = first->hintA;
      hintB = first->hintB;
    } else {
      pointA = a.support(-v, hintA);
      pointB = b.support(v, hintB);
    }
    const Vec3 w = pointA - pointB;
    const double vv = v.squaredNorm();
    const double wv = w.dot(v);
    if constexpr (kBoolean) {
      if (wv > 0.0 && wv * wv > separation * separation * vv) {
        run.exit = GjkExit::separated;
        break;
      }
    } else {
      // (A negative w.v bounds nothing, and loses to the initial 0.)
      run.lowerBound = std::max(run.lowerBound, wv / std::sqrt(vv));
    }
    // Once v is a point of the simplex (hence of a − b), |v| bounds the distance from above.
    if (simplex.size > 0) {
      const double norm = std::sqrt(vv);
      if (vv - wv <= (tolerance.absolute + tolerance.relative * norm) * norm) {
        run.exit = GjkExit::converged;
        break;
      }
      if (simplex.contains(w)) break;
    }
    if constexpr (!kBoolean) {
      simplex.origin[simplex.size] = Origin::of(pointA, pointB, hintA, hintB);
    }
    simplex.w[simplex.size++] = w;
    const bool hadUpperBound = simplex.size > 1;
    if (reduceSimplex(simplex, v)) {
      run.exit = GjkExit::intersecting;
      break;
    }
    const double closestSquared = v.squaredNorm();
    // |v| bounds the distance from above: within the band, answer "intersects" (this also keeps
    // |v| >= tolerance.absolute, far from underflow in the certificate above).
    const double touching = kBoolean ? separation : tolerance.absolute;
    if (closestSquared <= touching * touching) {
      run.exit = GjkExit::intersecting;
      break;
    }
    if (hadUpperBound && closestSquared >= vv) break;  // no progress: rounding dominates
  }
  if (cache != nullptr) {
    cache->direction = v;
    cache->hintA = hintA;
    cache->hintB = hintB;
  }
  return run;
}

// A distance query's answer from its GJK run: the witness points from the simplex's origins.
template <SupportMapping A, SupportMapping B, class Run>
DistanceResult distanceResult(const Run& run, const A& a, const B& b) {
  DistanceResult result;
  result.iterations = run.iterations;
  result.intersecting = run.exit == GjkExit::intersecting;
  result.distance = result.intersecting ? 0.0 : run.lowerBound;
  for (int i = 0; i < run.simplex.size; ++i) {
    result.pointA += run.simplex.lambda[i] * run.simplex.origin[i].onA(a);
    result.pointB += run.simplex.lambda[i] * run.simplex.origin[i].onB(b);
  }
  return result;
}

}  // namespace detail

// A conservative answer to "distance(a, b) <= margin": `unknown` when the test at hand cannot
// decide, otherwise backed by a certificate (a separating plane, or the origin strictly inside a
// tetrahedron of points of a − b).
enum class PairVerdict { separated, intersecting, unknown };

// Minkowski Portal Refinement (Snethen's XenoCollide, the boolean test of libccd) on a − b, from
// its interior point center(a) − center(b). `separated` only when a support point certifies
// distance > margin + tolerance.absolute (as GJK's early exit), `intersecting` only when the
// origin lies strictly inside the final portal's tetrahedron; degenerate portals, stalls and the
// band near contact give `unknown` (GJK decides those). Allocates nothing.
template <SupportMapping A, SupportMapping B>
PairVerdict portalIntersects(const A& a, const B& b, double margin = 0.0,
                             const GjkTolerance& tolerance = {}) {
  typename A::Hint hintA{};
  typename B::Hint hintB{};
  // The point of a − b maximising d.x.
  const auto support = [&](const Vec3& d) -> Vec3 {
    return a.support(d, hintA) - b.support(-d, hintB);
  };
  const double separation = margin + tolerance.absolute;
  // p maximises d.x over a − b: when p.d < -separation |d|, the plane through p normal to d keeps
  // a − b farther than `separation` from the origin.
  const auto separates = [separation](const Vec3& p, const Vec3& d) {
    const double pd = p.dot(d);
    return pd < 0.0 && pd * pd > separation * separation * d.squaredNorm();
  };
  // A direction too short (relative to the points it came from) to orient anything.
  const auto degenerate = [](const Vec3& d, double scaleSquared) {
    return !(d.squaredNorm() > 1e-24 * scaleSquared) ||
           !(d.squaredNorm() > detail::kShortestSquared);
  };

  // Portal discovery: v0 inside, v1 towards the origin, then v2 and v3 until the origin ray
  // passes through the triangle (v1, v2, v3).
  const Vec3 v0 = a.center() - b.center();
  if (!(v0.squaredNorm() > detail::kShortestSquared)) return PairVerdict::unknown;
  Vec3 d = -v0;
  Vec3 v1 = support(d);
  if (separates(v1, d)) return PairVerdict::separated;
  if (!(v1.dot(d) > 0.0)) return PairVerdict::unknown;
  d = v0.cross(v1);
  if (degenerate(d, v0.squaredNorm() * v1.squaredNorm())) return PairVerdict::unknown;
  Vec3 v2 = support(d);
  if (separates(v2, d)) return PairVerdict::separated;
  if (!(v2.dot(d) > 0.0)) return PairVerdict::unknown;
  d = (v1 - v0).cross(v2 - v0);
  if (d.dot(v0) > 0.0) {
    std::swap(v1, v2);
    d = -d;
  }
  Vec3 v3;
  for (int iteration = 0;; ++iteration) {
    if (iteration == tolerance.maxIterations) return PairVerdict::unknown;
    v3 = support(d);
    if (separates(v3, d)) return PairVerdict::separated;
    if (!(v3.dot(d) > 0.0)) return PairVerdict::unknown;
    if (v1.cross(v3).dot(v0) < 0.0) {
      v2 = v3;  // the origin is outside (v1, v0, v3)
    } else if (v3.cross(v2).dot(v0) < 0.0) {
      v1 = v3;  // the origin is outside (v3, v0, v2)
    } else {
      break;
    }
    d = (v1 - v0).cross(v2 - v0);
    if (degenerate(d, (v1 - v0).squaredNorm() * (v2 - v0).squaredNorm())) {
      return PairVerdict::unknown;
    }
  }

  // Portal refinement: push the portal (v1, v2, v3) outwards until the origin is behind it or a
  // support point certifies a separation.
  for (int iteration = 0; iteration < tolerance.maxIterations; ++iteration) {
    d = (v2 - v1).cross(v3 - v1);
    if (degenerate(d, (v2 - v1).squaredNorm() * (v3 - v1).squaredNorm())) break;
    if (d.dot(v1) >= 0.0) {
      return detail::originInsideTetrahedron(v0, v1, v2, v3) ? PairVerdict::intersecting
                                                             : PairVerdict::unknown;
    }
    const Vec3 v4 = support(d);
    if (separates(v4, d)) return PairVerdict::separated;
    const double v4d = v4.dot(d);
    // The portal cannot move past the origin, or no longer moves beyond the tolerance.
    const double progress = v4d - v1.dot(d);
    if (!(v4d > 0.0) ||
        !(progress > 0.0 &&
          progress * progress > tolerance.absolute * tolerance.absolute * d.squaredNorm())) {
      break;
    }
    // Keep the triangle of (v1, v2, v3, v4) that the origin ray passes through.
    const Vec3 c = v4.cross(v0);
    if (v1.dot(c) > 0.0) {
      (v2.dot(c) > 0.0 ? v1 : v3) = v4;
    } else {
      (v3.dot(c) > 0.0 ? v2 : v1) = v4;
    }
  }
  return PairVerdict::unknown;
}

// True when distance(a, b) <= margin (margin >= 0). Single-sided: never false when the true
// distance is <= margin; may be true for distances up to margin + 2 * tolerance.absolute +
// tolerance.relative * distance, and is true when the iteration cannot certify a separation.
// Without a cache, portalIntersects() answers first and GJK only runs when it is inconclusive;
// with a cache, GJK runs warm-started.
template <SupportMapping A, SupportMapping B>
bool intersects(const A& a, const B& b, double margin = 0.0, GjkCache<A, B>* cache = nullptr,
                const GjkTolerance& tolerance = {}) {
  if (cache == nullptr) {
    const PairVerdict verdict = portalIntersects(a, b, margin, tolerance);
    if (verdict != PairVerdict::unknown) return verdict == PairVerdict::intersecting;
  }
  return detail::runGjk<true>(a, b, margin, cache, tolerance).exit != detail::GjkExit::separated;
}

// Separation distance and witness points. The distance never exceeds the true distance (beyond
// floating-point rounding of the coordinates); on convergence it is within tolerance.absolute +
// tolerance.relative * distance below it.
template <SupportMapping A, SupportMapping B>
DistanceResult distance(const A& a, const B& b, GjkCache<A, B>* cache = nullptr,
                        const GjkTolerance& tolerance = {}) {
  return detail::distanceResult(detail::runGjk<false>(a, b, 0.0, cache, tolerance), a, b);
}

}  // namespace kaboum::collision
