// Topology and geometry checks of a triangle mesh: is it the closed, consistently oriented
// 2-manifold that §3.1 and the bounding mesh algorithm (§4.3, "Limitations") assume?
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// What analyzeMesh finds. Components are sets of triangles connected through shared edges;
// triangles with a repeated vertex index have no edges and belong to no component.
struct MeshAnalysis {
  std::size_t vertices = 0, triangles = 0, components = 0;
  std::size_t borderEdges = 0, borderLoops = 0;  // open mesh when borderEdges > 0
  std::size_t nonManifoldEdges = 0;              // edges with more than two incident triangles
  std::size_t nonManifoldVertices = 0;  // vertices whose triangle fan is not one disk/half-disk
  std::size_t degenerateTriangles = 0;  // zero area (repeated index or collinear)
  bool closed = false, edgeManifold = false, consistentlyOriented = false;
  bool outwardOriented = false;  // at least one closed component, and signed volume > 0 for
                                 // every closed component of a consistently oriented mesh
  double volume = 0.0;           // signed, sum over components
  double diagonal = 0.0;         // bounding-box diagonal of the referenced vertices
  Vec3 boxMin = Vec3::Zero(), boxMax = Vec3::Zero();
};

MeshAnalysis analyzeMesh(const TriangleMesh& mesh);

// Bounding-box diagonal of all vertices (0 for none): the length unit of relative tolerances and
// of distances reported "in % of the diagonal". Cheaper than a full analyzeMesh.
double boundingBoxDiagonal(const TriangleMesh& mesh);

// True for a zero-area triangle: a repeated index, or |(b-a)x(c-a)| <= 1e-12 * (longest edge)^2
// (collinear up to rounding).
bool isDegenerateTriangle(const TriangleMesh& mesh, const Triangle& triangle);

// Triangle adjacency across edges, built by sorting half-edges (no hashing, no per-edge heap
// use). Edge k of triangle t runs from corner k to corner (k+1)%3 and is entry 3t+k.
struct EdgeNeighbors {
  static constexpr std::uint32_t kBorder = 0xffffffffu;       // edge of one triangle only
  static constexpr std::uint32_t kNonManifold = 0xfffffffeu;  // edge of three or more
  static constexpr std::uint32_t kNoEdge = 0xfffffffdu;       // triangle has a repeated index
  // The other triangle when exactly two share the edge, else one of the constants above.
  std::vector<std::uint32_t> across;
  std::size_t borderEdges = 0, nonManifoldEdges = 0;
  std::size_t inconsistentEdges = 0;  // two-triangle edges both traversed the same way
};

EdgeNeighbors findEdgeNeighbors(const TriangleMesh& mesh);

}  // namespace kaboum::geometry
