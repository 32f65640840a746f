// Internal phase of the bounding mesh (thesis §4.3, Algorithm 2, and its "Limitations"): the mesh
// under contraction as flat arrays, with per-vertex corner lists, numbered edges and the vertices
// that must never move (on borders, non-manifold edges and non-manifold vertices).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

inline constexpr std::uint32_t kNoIndex = 0xffffffffu;  // no vertex, corner, edge or slot

// The mesh being simplified. Corner 3t + k is corner k of triangle t; contracted-away triangles
// and vertices stay in the arrays, marked dead.
struct ContractionMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<std::uint8_t> triangleAlive;
  std::vector<std::uint32_t> firstCorner, nextCorner;  // per-vertex linked list of corners 3t+k
  std::vector<std::uint32_t> triangleCount;            // live triangles at each vertex
  std::vector<std::uint8_t> vertexAlive, vertexLocked;
  std::vector<std::uint32_t> version;  // grows whenever the vertex's neighbourhood changes
  std::size_t aliveVertices = 0;
  // Edges: cornerEdge[3t + k] is the edge from corner k of triangle t to corner k + 1.
  std::vector<std::uint32_t> cornerEdge;
  std::vector<std::array<std::uint32_t, 2>> edgeEnds;  // (survivor, merged) of a contraction
  // Marks of vertices (markA, markB) and triangles, set to `stamp` by the query that owns it.
  std::vector<std::uint32_t> markA, markB, triangleMark;
  std::uint32_t stamp = 0;
};

inline bool triangleHas(const ContractionMesh& mesh, std::uint32_t t, std::uint32_t v) {
  const Triangle& tri = mesh.triangles[t];
  return tri[0] == v || tri[1] == v || tri[2] == v;
}

// Versions only grow, so the sum of edge e's end versions is unchanged exactly when both are.
inline std::uint32_t versionSum(const ContractionMesh& mesh, std::uint32_t e) {
  return mesh.version[mesh.edgeEnds[e][0]] + mesh.version[mesh.edgeEnds[e][1]];
}

// Calls f(t) for each live triangle t at vertex v, unlinking corners of dead triangles on the way.
template <class F>
void forEachTriangle(ContractionMesh& mesh, std::uint32_t v, F&& f) {
  std::uint32_t previous = kNoIndex;
  for (std::uint32_t c = mesh.firstCorner[v]; c != kNoIndex;) {
    const std::uint32_t next = mesh.nextCorner[c];
    if (!mesh.triangleAlive[c / 3]) {
      (previous == kNoIndex ? mesh.firstCorner[v] : mesh.nextCorner[previous]) = next;
    } else {
      f(c / 3);
      previous = c;
    }
    c = next;
  }
}

// The live triangles at v.
void gatherFan(ContractionMesh& mesh, std::uint32_t v, std::vector<std::uint32_t>& fan);
// The vertices sharing a live triangle with v.
void gatherNeighbours(ContractionMesh& mesh, std::uint32_t v, std::vector<std::uint32_t>& out);

// Takes over the input's arrays with every vertex and triangle alive and nothing locked, and links
// each vertex's corners.
void buildAdjacency(ContractionMesh& mesh, const TriangleMesh& input);
// Numbers the edges, locks the vertices of border and non-manifold edges and returns the interior
// edges. Throws InputError if the orientation is inconsistent.
std::vector<std::uint32_t> classifyEdges(ContractionMesh& mesh);
// Locks the interior vertices whose link is not a single cycle (e.g. two cones touching at a tip).
void lockNonManifoldVertices(ContractionMesh& mesh);
// Marks the vertices without triangles dead and counts the others.
void retireUnusedVertices(ContractionMesh& mesh);
// The diagonal of the bounding box of the live vertices (0 when there are none).
double liveDiagonal(const ContractionMesh& mesh);
// The live vertices that never move.
std::size_t lockedVertexCount(const ContractionMesh& mesh);

// The live triangles and the vertices they use, renumbered in order of first use.
TriangleMesh compactMesh(const ContractionMesh& mesh);

}  // namespace kaboum::geometry
