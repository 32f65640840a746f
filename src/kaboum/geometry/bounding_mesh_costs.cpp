#include "kaboum/geometry/bounding_mesh_costs.hpp"

#include <algorithm>
#include <limits>

namespace kaboum::geometry {
namespace {

// Each vertex's quadric: the sum over its triangles of the squared distance to the triangle's
// plane (E_planes, Eq. 4.4) or to its centroid (E_triangles).
void fillQuadrics(ContractionCosts& costs, const ContractionMesh& mesh, ContractionCost cost) {
  costs.quadrics.assign(mesh.positions.size(), Quadric{});
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Vec3 centroid =
        (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
    Quadric q;
    if (cost == ContractionCost::Triangles) {
      q = Quadric::point(centroid);
    } else if (costs.normals[t] != Vec3::Zero()) {
      q = Quadric::plane(costs.normals[t], centroid);
    } else {
      continue;
    }
    for (std::uint32_t v : tri) costs.quadrics[v] += q;
  }
}

}  // namespace

void fillCosts(ContractionCosts& costs, const ContractionMesh& mesh,
               const BoundingMeshOptions& options, double diagonal) {
  costs.side = options.side;
  costs.merge = options.merge;
  costs.mergeLength = options.mergeLength <= 0.0 ? 0.01 * diagonal : options.mergeLength;
  costs.tolerance = 1e-12 * diagonal;
  costs.costSlack = 1e-10 * diagonal * diagonal;
  const std::size_t triangleCount = mesh.triangles.size();
  costs.normals.resize(triangleCount);
  costs.offsets.resize(triangleCount);
  costs.crossLengths.resize(triangleCount);
  for (std::uint32_t t = 0; t < triangleCount; ++t) updatePlane(costs, mesh, t);
  fillQuadrics(costs, mesh, options.cost);
}

void updatePlane(ContractionCosts& costs, const ContractionMesh& mesh, std::uint32_t t) {
  const Vec3& p0 = mesh.positions[mesh.triangles[t][0]];
  const Vec3& p1 = mesh.positions[mesh.triangles[t][1]];
  const Vec3& p2 = mesh.positions[mesh.triangles[t][2]];
  const Vec3 cross = (p1 - p0).cross(p2 - p0);
  const double longest =
      std::max({(p1 - p0).squaredNorm(), (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm()});
  const double length = cross.norm();
  costs.crossLengths[t] =
      static_cast<float>(std::min<double>(length, std::numeric_limits<float>::max()));
  if (length <= 1e-12 * longest || length == 0.0) {
    costs.normals[t] = Vec3::Zero();
    costs.offsets[t] = 0.0;
    return;
  }
  costs.normals[t] = cross / length;
  costs.offsets[t] = costs.normals[t].dot((p0 + p1 + p2) / 3.0);
}

// The edge's merged quadric in coordinates centred on the edge (so large absolute coordinates lose
// no precision), with a tiny pull towards the edge midpoint that makes the problem strictly convex:
// flat and cylindrical neighbourhoods (singular quadrics) get a unique, central minimizer.
EdgeProblem problemOf(const ContractionCosts& costs, const ContractionMesh& mesh, std::uint32_t e) {
  const auto [a, b] = mesh.edgeEnds[e];
  EdgeProblem p;
  p.origin = 0.5 * (mesh.positions[a] + mesh.positions[b]);
  p.quadric = (costs.quadrics[a] + costs.quadrics[b]).centredAt(p.origin);
  p.curvatureFloor = 1e-9 * p.quadric.a.trace() + 1e-300;
  p.quadric.a += p.curvatureFloor * Eigen::Matrix3d::Identity();
  p.start = unconstrainedMinimizer(p.quadric);
  p.minimum = p.start ? p.quadric(*p.start) : 0.0;
  p.lowerBound = std::max(p.minimum, 0.0);
  return p;
}

}  // namespace kaboum::geometry
