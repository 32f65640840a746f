// Internal phase of the bounding mesh (thesis §4.3, the guarantees of Algorithm 2;
// docs/bounding-mesh.md, "No self-intersections, no folds" and "High-valence stars"): the guard
// that refuses a contraction whose new fan would cross the mesh, with its spatial hash of the live
// triangles and the angular indexes of the stars of high-valence vertices (hubs).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kaboum/geometry/bounding_mesh_costs.hpp"
#include "kaboum/geometry/bounding_mesh_topology.hpp"
#include "kaboum/geometry/separation_certificate.hpp"
#include "kaboum/geometry/triangle_grid.hpp"

namespace kaboum::geometry {

// Vertices of at least this valence are hubs: their stars leave the spatial hash for an angular
// index (see newFanCrossesMesh). Real robot meshes have valences of at most 40.
inline constexpr std::uint32_t kHubValence = 64;

// A hub (a vertex of valence ≥ kHubValence) and the angular index of its star: each star triangle
// (v, p, q) is registered by the box of its directions from v (directionBox of p, q).
struct Hub {
  std::uint32_t vertex = kNoIndex;
  std::optional<TriangleGrid> directions, coarse;  // coarse: kHubCoarse times larger cells
  // Since the hub last moved: a box containing every star triangle, the least distance from the
  // hub to a far edge, the longest edge (bounded by a box diagonal), and the star triangles
  // without a direction box (while there are any, queries enumerate the whole star).
  Box3 starBox;
  double minHeight = 0.0, maxEdge = 0.0;
  std::uint32_t unindexed = 0;
  // Edges at the hub keyed above their plane-independent lower bound (Bounded, Solved or
  // Infeasible; perhaps some no longer): the only ones a change of its planes must re-key.
  std::vector<std::uint32_t> raised;
};

// The hubs, and where each vertex's hub record is.
struct Hubs {
  std::vector<Hub> slots;             // free when their vertex is kNoIndex
  std::vector<std::uint32_t> slotOf;  // per vertex: its slot in `slots`, or kNoIndex
};

// The contraction of edge (a, b): b merges into a, which moves to `position`.
struct Contraction {
  std::uint32_t a, b;
  Vec3 position;
};

// A triangle of the fan a contraction would create.
struct NewTriangle {
  Triangle ids;
  std::array<Vec3, 3> corners;
  Vec3 unitNormal;
  double crossLength, sizeSquared;
  Box3 box;
};

// The guard's indexes of the live triangles (each one either in the spatial hash or in the indexes
// of its hub corners), and its scratch.
struct CrossingGuard {
  std::vector<Box3> boxes;           // each live triangle's box as registered in its index
  std::optional<TriangleGrid> grid;  // the live triangles with no hub corner (inGrid)
  std::vector<std::uint8_t> inGrid;
  Hubs hubs;
  std::size_t verticesAtGridBuild = 0;
  // Scratch of newFanCrossesMesh, reused so the main loop does not allocate once warmed up.
  std::vector<NewTriangle> newTriangles;
  std::vector<PlanedTriangle> newPlaned;  // views of newTriangles for certainlyApart
  std::vector<std::uint32_t> nearby;
};

// Triangle t's box at the current positions.
inline Box3 boxOf(const ContractionMesh& mesh, std::uint32_t t) {
  const Triangle& tri = mesh.triangles[t];
  return triangleBox(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
}

// Boxes every triangle, makes hubs of the vertices of valence ≥ kHubValence, indexes their stars
// and puts the other triangles in a spatial hash with cells of about two edge lengths.
void buildGuard(CrossingGuard& guard, const ContractionMesh& mesh, double diagonal);
// Rebuilds the spatial hash with √2 times larger cells once half the vertices it was built for
// are gone (the triangles grew).
void coarsenGridIfSparse(CrossingGuard& guard, const ContractionMesh& mesh);

// Makes v a hub with an empty index (reusing a free slot and its table when there is one), or
// empties the record of hub v, whose star triangles are all out of its index.
void acquireHub(Hubs& hubs, const ContractionMesh& mesh, std::uint32_t v);
// Frees v's slot if v is a hub.
void releaseHub(Hubs& hubs, std::uint32_t v);
inline bool isHub(const Hubs& hubs, std::uint32_t v) {
  return hubs.slotOf[v] != kNoIndex;
}
inline bool hasHubCorner(const Hubs& hubs, const ContractionMesh& mesh, std::uint32_t t) {
  const Triangle& tri = mesh.triangles[t];
  return isHub(hubs, tri[0]) || isHub(hubs, tri[1]) || isHub(hubs, tri[2]);
}

// Removes triangle t, with the geometry it was indexed with, from the index of each hub corner.
void unindexAtHubs(CrossingGuard& guard, const ContractionMesh& mesh, std::uint32_t t);
// Takes triangle t out of the spatial hash, if it is there.
void removeFromGrid(CrossingGuard& guard, std::uint32_t t);
// Registers triangle t, whose geometry changed and which is in no hub's index, under its new box:
// in the indexes of its hub corners if it has any, else in the spatial hash.
void placeTriangle(CrossingGuard& guard, const ContractionMesh& mesh, std::uint32_t t,
                   const Box3& box);

// Whether the fan that contraction c would make of fanA and fanB (the triangles at c.a and c.b)
// would cross any other triangle of the mesh or itself.
bool newFanCrossesMesh(CrossingGuard& guard, ContractionMesh& mesh, const ContractionCosts& costs,
                       const Contraction& c, std::span<const std::uint32_t> fanA,
                       std::span<const std::uint32_t> fanB);

}  // namespace kaboum::geometry
