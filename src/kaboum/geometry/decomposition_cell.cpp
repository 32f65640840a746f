#include "kaboum/geometry/decomposition_cell.hpp"

#include <optional>
#include <utility>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/quick_hull.hpp"

namespace kaboum::geometry {
namespace {

bool isClosedAndOriented(const TriangleMesh& surface) {
  const MeshAnalysis analysis = analyzeMesh(surface);
  return analysis.closed && analysis.edgeManifold && analysis.consistentlyOriented;
}

// Drops points closer than `snap` to an earlier kept point; `points` are sorted by x first.
std::vector<Vec3> thinOut(const std::vector<Vec3>& points, double snap) {
  std::vector<Vec3> kept;
  for (const Vec3& p : points) {
    bool near = false;
    for (auto k = kept.rbegin(); k != kept.rend() && p.x() - k->x() <= snap && !near; ++k) {
      near = (p - *k).norm() <= snap;
    }
    if (!near) kept.push_back(p);
  }
  return kept;
}

// The points a cell's piece is the hull of: its polygon corners and its inside corners.
std::vector<Vec3> hullPoints(const Cell& cell) {
  std::vector<Vec3> points = cell.points;
  points.insert(points.end(), cell.corners.begin(), cell.corners.end());
  return points;
}

}  // namespace

double meshVolume(const TriangleMesh& mesh) {
  double sixVolume = 0.0;
  for (const Triangle& t : mesh.triangles) {
    sixVolume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return sixVolume / 6.0;
}

Solid::Solid(const TriangleMesh& surface, double tolerance)
    : bvh_(surface), tolerance_(tolerance), closed_(isClosedAndOriented(surface)) {}

void Solid::largestDistance(SurfaceSampler& samples, double stopAt, Farthest& farthest) const {
  farthest.complete = farthest.distance < stopAt;
  if (!farthest.complete) return;
  for (Vec3 p; samples.next(p);) {
    if (samples.produced() == 1) farthest.where = p;
    // Beyond the largest distance so far: it counts unless it is inside (many samples on cut
    // faces are, and then need no closest point).
    if (bvh_.hasTriangleWithin(p, farthest.distance) || inside(p)) continue;
    farthest.distance = bvh_.closest(p).distance;
    farthest.where = p;
    if (farthest.distance >= stopAt) {
      farthest.complete = false;
      return;
    }
  }
}

void sortPoints(std::vector<Vec3>& points) {
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
}

bool buildHull(Cell& cell, double snap) {
  std::vector<Vec3> points = hullPoints(cell);
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1) {
      sortPoints(points);
      points = thinOut(points, snap);
    }
    if (points.size() < 4) return false;
    try {
      cell.hull = convexHull(points, "piece");
      cell.hullVolume = meshVolume(cell.hull.mesh);
      return cell.hullVolume > 0.0;
    } catch (const InputError&) {
      // flat (the cell holds a sliver of the surface only) or qhull's precision check failed
    }
  }
  return false;
}

bool buildCandidateHull(Cell& cell, double snap) {
  std::optional<TriangleMesh> mesh = quickHull(hullPoints(cell), snap);
  if (!mesh) return buildHull(cell, snap);
  cell.hull = ConvexHull{std::move(*mesh), {}, {}};
  cell.hullVolume = meshVolume(cell.hull.mesh);
  return cell.hullVolume > 0.0;
}

void keepHull(Cell& cell, double snap) {
  if (!cell.hull.planes.empty()) return;  // built by buildHull already
  ConvexHull candidate = cell.hull;
  if (buildHull(cell, snap)) return;
  cell.hull = std::move(candidate);
  const TriangleMesh& mesh = cell.hull.mesh;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 normal = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                            .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                            .normalized();
    cell.hull.planes.push_back({normal, normal.dot(mesh.vertices[t[0]])});
  }
  cell.hullVolume = meshVolume(mesh);
}

std::uint64_t sampleSeed(const DecompositionContext& context, std::uint64_t salt) {
  return context.seed * 1000003u + salt;
}

bool measureConcavity(Cell& cell, const DecompositionContext& context, std::uint64_t salt,
                      double stopAt) {
  SurfaceSampler samples(cell.hull.mesh, context.samples, sampleSeed(context, salt));
  Farthest farthest;
  context.solid.largestDistance(samples, stopAt, farthest);
  cell.concavity = farthest.distance;
  cell.worstPoint = farthest.where;
  return farthest.complete;
}

}  // namespace kaboum::geometry
