#include "kaboum/geometry/star_directions.hpp"

#include <algorithm>
#include <cmath>

namespace kaboum::geometry {

std::optional<std::array<Vec3, 3>> directionsFrom(const Vec3& apex, std::span<const Vec3> corners) {
  const std::size_t count = std::min<std::size_t>(corners.size(), 3);
  if (count < 2) return std::nullopt;
  std::array<Vec3, 3> directions;
  Vec3 sum = Vec3::Zero();
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3 offset = corners[k] - apex;
    const double length = offset.norm();
    const double scale = std::max(corners[k].cwiseAbs().maxCoeff(), apex.cwiseAbs().maxCoeff());
    if (!(length > 1e-12 * scale)) return std::nullopt;
    directions[k] = offset / length;
    sum += directions[k];
  }
  if (count == 2) directions[2] = directions[1];
  const double sumLength = sum.norm();
  for (std::size_t k = 0; k < count; ++k) {
    if (!(directions[k].dot(sum) >= 0.5 * sumLength)) return std::nullopt;
  }
  return directions;
}

Box3 sphericalBox(const std::array<Vec3, 3>& directions, int count, double margin) {
  Vec3 lo = directions[0].cwiseMin(directions[1]), hi = directions[0].cwiseMax(directions[1]);
  double chord = (directions[0] - directions[1]).squaredNorm();
  if (count == 3) {
    lo = lo.cwiseMin(directions[2]);
    hi = hi.cwiseMax(directions[2]);
    chord = std::max({chord, (directions[1] - directions[2]).squaredNorm(),
                      (directions[2] - directions[0]).squaredNorm()});
  }
  const double grow = chord / 3.0 + margin + 1e-12;
  lo.array() -= grow;
  hi.array() += grow;
  return triangleBox(lo, hi, hi);
}

double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double lengthSquared = ab.squaredNorm();
  const double s =
      lengthSquared > 0.0 ? std::clamp((p - a).dot(ab) / lengthSquared, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

}  // namespace kaboum::geometry
