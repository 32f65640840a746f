#include "kaboum/geometry/decomposition_simplify.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"

namespace kaboum::geometry {
namespace {

// Largest distance from the points to the convex piece (0 inside), exact.
double largestDistanceToConvex(const std::vector<Vec3>& points, const ConvexHull& piece) {
  double worst = 0.0;
  for (const Vec3& p : points) {
    const bool inside =
        std::all_of(piece.planes.begin(), piece.planes.end(),
                    [&](const HullPlane& h) { return h.normal.dot(p) <= h.offset; });
    if (inside) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Triangle& t : piece.mesh.triangles) {
      const Vec3 c = closestPointOnTriangle(p, piece.mesh.vertices[t[0]], piece.mesh.vertices[t[1]],
                                            piece.mesh.vertices[t[2]]);
      nearest = std::min(nearest, (c - p).norm());
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace

std::pair<ConvexHull, double> simplifyPiece(const ConvexHull& piece, double budget) {
  std::pair<ConvexHull, double> best{piece, 0.0};
  const auto attempt = [&](double limit) {
    BoundingMeshOptions options;
    options.side = BoundSide::Outer;
    options.maxError = limit;
    ConvexHull simplified;
    try {
      simplified = convexHull(simplifyBounding(piece.mesh, options).mesh.vertices, "piece");
    } catch (const InputError&) {
      return false;
    }
    const double growth = largestDistanceToConvex(simplified.mesh.vertices, piece);
    if (growth > budget) return false;
    if (simplified.mesh.vertexCount() < best.first.mesh.vertexCount()) {
      best = {std::move(simplified), growth};
    }
    return true;
  };
  double failing = 8.0 * budget;
  if (attempt(failing)) return best;
  double passing = failing;
  for (int halvings = 0; halvings < 5; ++halvings) {
    passing *= 0.5;
    if (attempt(passing)) break;
    failing = passing;
  }
  for (int bisections = 0; bisections < 3; ++bisections) {
    const double middle = 0.5 * (passing + failing);
    (attempt(middle) ? passing : failing) = middle;
  }
  return best;
}

}  // namespace kaboum::geometry
