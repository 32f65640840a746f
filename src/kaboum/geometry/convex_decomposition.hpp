// Bounding convex decomposition (thesis §4.4, Definition 3, the §4.4.2 procedure): a small set of
// convex polyhedra with few vertices whose union contains the input mesh, within a distance ε.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum {
class WorkerPool;
}

namespace kaboum::geometry {

struct DecompositionOptions {
  // Largest distance from the union of the pieces to the (hole-filled) input, in mesh units; when
  // 0, `epsilonPercent` of the input's bounding-box diagonal.
  double epsilon = 0.0;
  double epsilonPercent = 3.0;
  std::size_t maxPieces = 11;  // splitting stops here even if ε is not reached
  // Random surface samples of every candidate piece's hull for its concavity (plus its vertices
  // and edge midpoints).
  std::size_t concavitySamples = 600;
  // Random samples of the bridge between two pieces when their merge is priced (the merged hull's
  // triangles not spanned by one piece's vertices; plus their vertices and edge midpoints).
  std::size_t bridgeSamples = 2000;
  // At most this many moves after merging that re-cut the worst piece (with a neighbour, or alone
  // and merge another pair instead); 0 (the default) keeps the merged pieces as they are. 10 lowers
  // the 14 robot links' mean distance from 3.27% to 3.16% of the diagonal for 1.3-1.6x the time.
  std::size_t refineRounds = 0;
  std::uint64_t seed = 1;
};

// One convex polyhedron: the closed, outward triangle mesh over its vertices (every vertex is a
// hull vertex) and its facet planes (n.x <= d inside).
struct ConvexPiece {
  TriangleMesh mesh;
  std::vector<HullPlane> planes;

  [[nodiscard]] const std::vector<Vec3>& vertices() const { return mesh.vertices; }
  // p is inside or within `tolerance` of every facet plane.
  [[nodiscard]] bool contains(const Vec3& p, double tolerance = 0.0) const;
};

struct DecompositionStats {
  std::size_t inputVertices = 0, inputTriangles = 0;
  std::size_t holesFilled = 0;      // border loops capped (hole_filling.hpp)
  std::size_t componentsKept = 0;   // open or self-intersecting components step 1 left unbounded
  std::size_t boundedVertices = 0;  // after §4.4.2 step 1 (outer bounding mesh at ε/10)
  std::size_t hullVertices = 0;     // all pieces before step 3
  std::size_t totalVertices = 0;    // all pieces after step 3
  double epsilon = 0.0;             // absolute ε used
  double diagonal = 0.0;            // bounding-box diagonal of the input
  double estimatedError = 0.0;      // step 1 bound + largest concavity + largest step-3 growth
  std::size_t splits = 0, merges = 0;
  std::size_t refinements = 0;  // re-cut moves kept after merging
  std::string stopReason;       // "within epsilon" or "piece limit reached"
  double seconds = 0.0;
};

struct Decomposition {
  std::vector<ConvexPiece> pieces;
  TriangleMesh closedInput;  // the welded, outward, hole-filled input the pieces contain
  DecompositionStats stats;
};

// The §4.4.2 procedure. Input: any triangle mesh that can be oriented consistently (welded here;
// open meshes are closed by fillHoles first). Step 1 bounds it from outside at ε/10 (bounding
// mesh algorithm, per component; open or self-intersecting components are left as they are), step 2
// splits the bound hierarchically by planes, each cell C giving the piece conv((bound surface ∩ C)
// ∪ (corners of C inside the bound)), which contains the bound's solid inside C, so the union
// contains the whole solid (docs/decomposition.md has the argument), and step 3 replaces every
// piece by the convex hull of an outer bounding mesh of it. The distance budget is split between
// the steps; ε is met up to the sampling of the concavity measure unless `maxPieces` stops the
// splitting first. Deterministic for a given seed. Throws InputError for an empty mesh, non-finite
// coordinates, a mesh that cannot be oriented, or one with no volume.
Decomposition decomposeBounding(const TriangleMesh& mesh, const DecompositionOptions& options);
// The same, the candidate cuts' hulls and step 3's pieces run as tasks of `workers` (which may be
// running other batches: a task of another mesh's decomposition, say); equal to the result above.
Decomposition decomposeBounding(const TriangleMesh& mesh, const DecompositionOptions& options,
                                WorkerPool& workers);

// decomposeBounding for every mesh (e.g. every collision mesh of a robot's links), run on
// `threads` threads, the largest meshes first; the results do not depend on the thread count. An
// InputError names the failing mesh by its index.
std::vector<Decomposition> decomposeBoundingEach(std::span<const TriangleMesh> meshes,
                                                 const DecompositionOptions& options,
                                                 unsigned threads = 2);

// Table 4.3's distances, on dense samples. originalToApproximation: from the original surface to
// the nearest piece surface. approximationToOriginal: from the boundary of the union (piece
// surface samples not within 1e-9 of the diagonal of another piece) to `original`'s surface (pass
// Decomposition::closedInput for an open input). uncovered counts original
// samples outside every piece (by more than 1e-9 of the diagonal); it is zero for a bounding
// decomposition.
struct DecompositionQuality {
  DistanceStats originalToApproximation, approximationToOriginal;
  double diagonal = 0.0;
  std::size_t samples = 0, uncovered = 0;
  double worstUncovered = 0.0;  // largest facet-plane violation of an uncovered sample
};
DecompositionQuality measureDecomposition(const TriangleMesh& original,
                                          std::span<const ConvexPiece> pieces,
                                          std::size_t randomSamples, std::uint64_t seed);

// All pieces in one mesh (vertices and triangles concatenated), e.g. for distance measurements.
TriangleMesh mergePieces(std::span<const ConvexPiece> pieces);

}  // namespace kaboum::geometry
