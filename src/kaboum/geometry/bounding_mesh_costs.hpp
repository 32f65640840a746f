// Internal phase of the bounding mesh (thesis §4.3.4–4.3.5, Eq. 4.4 and 4.8, Appendix A.1–A.2):
// the triangles' planes, the vertices' quadrics, and each edge's constrained problem: its merged
// quadric and the half-spaces its contraction point must stay in.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "kaboum/geometry/bound_side.hpp"
#include "kaboum/geometry/bounded_contraction.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/bounding_mesh_topology.hpp"
#include "kaboum/geometry/quadric.hpp"

namespace kaboum::geometry {

// The cost settings of a run, the plane of each triangle and the quadric of each vertex.
struct ContractionCosts {
  BoundSide side = BoundSide::Outer;
  QuadricMerge merge = QuadricMerge::Constant;
  double mergeLength = 0.0;   // l of Eq. 4.7
  double tolerance = 0.0;     // how far a contraction point may stray beyond a half-space
  double costSlack = 0.0;     // absolute rounding allowance of a cost: 10⁻¹⁰ of the diagonal²
  std::vector<Vec3> normals;  // unit normal per triangle (zero when degenerate)
  std::vector<double> offsets;      // normal · point on the triangle
  std::vector<float> crossLengths;  // |(p1 - p0) × (p2 - p0)|, for the guard's certificate
  std::vector<Quadric> quadrics;    // per vertex
};

// Takes the settings from `options` and the mesh's diagonal, and fills every triangle's plane and
// every vertex's quadric (E_planes or E_triangles, §4.3.5).
void fillCosts(ContractionCosts& costs, const ContractionMesh& mesh,
               const BoundingMeshOptions& options, double diagonal);
// Recomputes triangle t's plane from the current positions.
void updatePlane(ContractionCosts& costs, const ContractionMesh& mesh, std::uint32_t t);

// An edge's quadric in coordinates centred on the edge, with its unconstrained minimizer.
struct EdgeProblem {
  Vec3 origin;
  Quadric quadric;  // regularized, positive definite
  std::optional<Vec3> start;
  double minimum;         // the quadric at `start` (0 without one)
  double lowerBound;      // of the cost: max(minimum, 0)
  double curvatureFloor;  // the regularization: the quadric's smallest eigenvalue is at least this
};

// Edge e's problem with the current quadrics and positions.
EdgeProblem problemOf(const ContractionCosts& costs, const ContractionMesh& mesh, std::uint32_t e);

// The half-spaces of an edge's problem, with the triangle of each.
struct EdgeHalfSpaces {
  std::vector<HalfSpace> halfSpaces;
  std::vector<std::uint32_t> triangles;
};

// Adds the kept side of triangle t's plane, in coordinates centred on `origin`; nothing for a
// degenerate triangle, which has no plane to stay on.
inline void addHalfSpace(EdgeHalfSpaces& out, const ContractionCosts& costs, std::uint32_t t,
                         const Vec3& origin) {
  const Vec3& n = costs.normals[t];
  if (n.x() == 0.0 && n.y() == 0.0 && n.z() == 0.0) return;
  const double sign = costs.side == BoundSide::Outer ? 1.0 : -1.0;
  out.halfSpaces.push_back({sign * n, sign * (costs.offsets[t] - n.dot(origin))});
  out.triangles.push_back(t);
}

}  // namespace kaboum::geometry
