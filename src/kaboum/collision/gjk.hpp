// GJK (Gilbert–Johnson–Keerthi) on any two support mappings: the convex–convex query every
// collision predicate of thesis §4.1 (Definition 1) and §4.5 reduces to. Boolean "distance <=
// margin" with a separating-axis early exit, and separation distance with witness points.
// Sub-algorithm: signed volumes (Montanari, Petrinic & Barbieri 2017). No heap allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "kaboum/collision/support_mapping.hpp"

namespace kaboum::collision {

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

// Points of the Minkowski difference a − b with the support points they came from, and the
// barycentric weights of the current closest point.
struct Simplex {
  std::array<Vec3, 4> w;
  std::array<Vec3, 4> a;
  std::array<Vec3, 4> b;
  std::array<double, 4> lambda{};
  int size = 0;

  void add(const Vec3& pointW, const Vec3& pointA, const Vec3& pointB) {
    w[size] = pointW;
    a[size] = pointA;
    b[size] = pointB;
    ++size;
  }
  [[nodiscard]] bool contains(const Vec3& point) const {
    for (int i = 0; i < size; ++i) {
      if (w[i] == point) return true;
    }
    return false;
  }
  [[nodiscard]] Vec3 pointA() const {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < size; ++i) p += lambda[i] * a[i];
    return p;
  }
  [[nodiscard]] Vec3 pointB() const {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < size; ++i) p += lambda[i] * b[i];
    return p;
  }
};

// Signed-volume distance sub-algorithm: keeps the smallest face of the simplex whose hull holds
// the point closest to the origin, sets its weights and returns that point in `closest`. Returns
// true when the origin lies inside the tetrahedron (the simplex then keeps its 4 points).
bool reduceSimplex(Simplex& simplex, Vec3& closest);

enum class GjkExit { separated, intersecting, converged, stalled };

// The GJK loop. Boolean mode stops as soon as a support point certifies distance > margin +
// tolerance.absolute, or the simplex comes within `margin` of the origin; distance mode runs to
// convergence and tracks the best certified lower bound.
template <bool kBoolean, SupportMapping A, SupportMapping B>
GjkExit runGjk(const A& a, const B& b, double margin, GjkCache<A, B>* cache,
               const GjkTolerance& tolerance, Simplex& simplex, double& lowerBound,
               int& iterations) {
  typename A::Hint hintA{};
  typename B::Hint hintB{};
  Vec3 v = Vec3::Zero();
  if (cache != nullptr) {
    hintA = cache->hintA;
    hintB = cache->hintB;
    v = cache->direction;
  }
  if (!(v.squaredNorm() > 0.0)) v = a.center() - b.center();
  if (!(v.squaredNorm() > 0.0)) v = Vec3::UnitX();

  const double separation = margin + tolerance.absolute;
  simplex.size = 0;
  lowerBound = 0.0;
  GjkExit exit = GjkExit::stalled;
  for (iterations = 1; iterations <= tolerance.maxIterations; ++iterations) {
    // w minimises x.v over a − b, so x.v >= w.v for every x: the plane through w normal to v
    // bounds the distance from below by w.v / |v|.
    const Vec3 pointA = a.support(-v, hintA);
    const Vec3 pointB = b.support(v, hintB);
    const Vec3 w = pointA - pointB;
    const double vv = v.squaredNorm();
    const double wv = w.dot(v);
    if constexpr (kBoolean) {
      if (wv > 0.0 && wv * wv > separation * separation * vv) {
        exit = GjkExit::separated;
        break;
      }
    } else if (wv > 0.0) {
      lowerBound = std::max(lowerBound, wv / std::sqrt(vv));
    }
    // Once v is a point of the simplex (hence of a − b), |v| bounds the distance from above.
    if (simplex.size > 0) {
      const double norm = std::sqrt(vv);
      if (vv - wv <= (tolerance.absolute + tolerance.relative * norm) * norm) {
        exit = GjkExit::converged;
        break;
      }
      if (simplex.contains(w)) break;
    }
    simplex.add(w, pointA, pointB);
    const bool hadUpperBound = simplex.size > 1;
    if (reduceSimplex(simplex, v)) {
      exit = GjkExit::intersecting;
      break;
    }
    const double closestSquared = v.squaredNorm();
    const double touching = kBoolean ? margin : tolerance.absolute;
    if (closestSquared <= touching * touching) {
      exit = GjkExit::intersecting;
      break;
    }
    if (hadUpperBound && closestSquared >= vv) break;  // no progress: rounding dominates
  }
  if (cache != nullptr) {
    cache->direction = v;
    cache->hintA = hintA;
    cache->hintB = hintB;
  }
  return exit;
}

}  // namespace detail

// True when distance(a, b) <= margin (margin >= 0). Single-sided: never false when the true
// distance is <= margin; may be true for distances up to margin + 2 * tolerance.absolute +
// tolerance.relative * distance, and is true when the iteration cannot certify a separation.
template <SupportMapping A, SupportMapping B>
bool intersects(const A& a, const B& b, double margin = 0.0, GjkCache<A, B>* cache = nullptr,
                const GjkTolerance& tolerance = {}) {
  detail::Simplex simplex;
  double lowerBound = 0.0;
  int iterations = 0;
  return detail::runGjk<true>(a, b, margin, cache, tolerance, simplex, lowerBound, iterations) !=
         detail::GjkExit::separated;
}

// Separation distance and witness points. The distance never exceeds the true distance (beyond
// floating-point rounding of the coordinates); on convergence it is within tolerance.absolute +
// tolerance.relative * distance below it.
template <SupportMapping A, SupportMapping B>
DistanceResult distance(const A& a, const B& b, GjkCache<A, B>* cache = nullptr,
                        const GjkTolerance& tolerance = {}) {
  detail::Simplex simplex;
  DistanceResult result;
  const detail::GjkExit exit = detail::runGjk<false>(a, b, 0.0, cache, tolerance, simplex,
                                                     result.distance, result.iterations);
  result.intersecting = exit == detail::GjkExit::intersecting;
  if (result.intersecting) result.distance = 0.0;
  result.pointA = simplex.pointA();
  result.pointB = simplex.pointB();
  return result;
}

}  // namespace kaboum::collision
