// Directions seen from a vertex, for the bounding mesh's angular index of high-valence stars
// (thesis §4.3; docs/bounding-mesh.md, "No self-intersections, no folds"): two triangles sharing or
// near a vertex v can only meet where their sets of directions from v overlap.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "kaboum/geometry/triangle_grid.hpp"

namespace kaboum::geometry {

// The unit directions from `apex` to `corners` (two or three points), if each corner is clear of
// the apex beyond rounding and the directions lie well inside one hemisphere (every one at most 60°
// from their mean), so that the directions of their convex hull form the spherical arc or triangle
// they span.
std::optional<std::array<Vec3, 3>> directionsFrom(const Vec3& apex, std::span<const Vec3> corners);

// A box containing the spherical arc (count 2) or triangle (count 3) spanned by `directions` (from
// directionsFrom), grown by `margin` plus rounding on every side: the box of the directions grown
// by c²/3 for their longest chord c, since every y in their convex hull has |y|² ≥ 1 - c²/3 and so
// moves by at most 1 - |y| ≤ c²/3 onto the sphere.
Box3 sphericalBox(const std::array<Vec3, 3>& directions, int count, double margin);

// Calls f(box, piece) for pieces (spherical triangles, as three unit directions) that together
// cover the spherical arc (count 2) or triangle (count 3) spanned by `directions`, with box the
// piece's sphericalBox grown by `margin`. The pieces are strips across the corner opposite the
// shortest side, about `extent` long each (at most 4096 strips).
template <class F>
void forEachSphericalPiece(const std::array<Vec3, 3>& directions, int count, double margin,
                           double extent, F&& f) {
  int apex = 0;  // the corner opposite the shortest side
  double longest = 0.0;
  if (count == 3) {
    double shortest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double chord = (directions[(k + 1) % 3] - directions[(k + 2) % 3]).squaredNorm();
      longest = std::max(longest, chord);
      if (chord < shortest) {
        shortest = chord;
        apex = k;
      }
    }
  } else {
    longest = (directions[1] - directions[0]).squaredNorm();
  }
  const Vec3& d0 = directions[static_cast<std::size_t>(apex)];
  const Vec3& d1 = directions[static_cast<std::size_t>((apex + 1) % count)];
  const Vec3& d2 = directions[static_cast<std::size_t>((apex + 2) % count)];
  const double strips = std::clamp(std::ceil(std::sqrt(longest) / extent), 1.0, 4096.0);
  Vec3 p = d0, q = d0;  // the strip's near side, on d0d1 and d0d2
  for (int j = 1; j <= static_cast<int>(strips); ++j) {
    const double t = j / strips;
    const Vec3 pNext = ((1.0 - t) * d0 + t * d1).normalized();
    const Vec3 qNext = count == 3 ? ((1.0 - t) * d0 + t * d2).normalized() : pNext;
    if (count == 2) {
      const std::array<Vec3, 3> piece{p, pNext, pNext};
      f(sphericalBox(piece, 2, margin), piece);
    } else {
      const std::array<Vec3, 3> first{p, pNext, qNext};
      f(sphericalBox(first, 3, margin), first);
      if (j > 1) {
        const std::array<Vec3, 3> second{p, qNext, q};
        f(sphericalBox(second, 3, margin), second);
      }
    }
    p = pNext;
    q = qNext;
  }
}

// The distance from point p to segment ab.
double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace kaboum::geometry
