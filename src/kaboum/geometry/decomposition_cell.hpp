// Internal part of the bounding convex decomposition (thesis §4.4.2 step 2), shared by its
// phases: the solid the bound encloses, a cell of the hierarchical split with its piece (the hull
// of its surface and inside corners), and the concavity of a piece measured on samples.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "kaboum/core/worker_pool.hpp"
#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// The signed volume of a closed, outward mesh.
double meshVolume(const TriangleMesh& mesh);

// The largest distance from a piece's hull samples to the solid (0 when every sample is inside)
// and the first sample where it occurs; `complete` is false when the measurement stopped early
// because the distance reached the caller's limit (then `distance` is only a lower bound).
struct Farthest {
  double distance = 0.0;
  Vec3 where = Vec3::Zero();
  bool complete = true;
};

// The solid enclosed by the closed bound: inside tests and distances to its surface.
class Solid {
 public:
  Solid(const TriangleMesh& surface, double tolerance);

  // Inside, or on the surface up to the tolerance (a corner there is kept, which is harmless).
  [[nodiscard]] bool contains(const Vec3& p) const {
    return bvh_.hasTriangleWithin(p, tolerance_) || inside(p);
  }
  [[nodiscard]] Vec3 closestPoint(const Vec3& p) const { return bvh_.closest(p).point; }

  // Continues `farthest` (started at a lower bound, 0 for none) over the samples `samples` has
  // left, samples inside counting 0, until its distance reaches `stopAt` (then `complete` is
  // false and the measurement can resume with a higher limit). A sample only matters when it is
  // farther than the largest distance so far, so most samples are settled by finding one triangle
  // that close instead of the closest one; the result is bit for bit the one of a closest-point
  // query per sample.
  void largestDistance(SurfaceSampler& samples, double stopAt, Farthest& farthest) const;

 private:
  // One ray decides where every ray gives the same winding number, else the rays vote.
  [[nodiscard]] bool inside(const Vec3& p) const {
    return closed_ ? bvh_.containsInClosedMesh(p) : bvh_.contains(p);
  }

  TriangleBvh bvh_;
  double tolerance_;
  bool closed_;  // closed, edge-manifold and consistently oriented
};

// The part of the bound inside one convex cell of the hierarchical split: the bound's triangles
// clipped to the cell (convex polygons, stored flat) and the cell's walls and corners.
struct Cell {
  std::vector<Vec3> points;  // the distinct polygon corners (sorted by sortPoints)
  std::vector<Vec3> polygonPoints;
  std::vector<std::uint32_t> polygonEnds;  // end offset of every polygon in polygonPoints
  std::vector<HullPlane> walls;            // n.x <= d inside
  std::vector<Vec3> corners;               // cell corners inside the solid
  // A candidate's has no planes (buildCandidateHull), a kept cell's has (keepHull).
  ConvexHull hull;
  double hullVolume = 0.0;
  double concavity = 0.0;  // largest sampled distance from the hull to the solid
  Vec3 worstPoint = Vec3::Zero();
  int stalls = 0;  // splits in a row, up to this cell, that left the concavity nearly unchanged
};

inline bool lexicographicLess(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// Sorts the points lexicographically and drops repeated ones.
void sortPoints(std::vector<Vec3>& points);

// The hull of the cell's polygons and inside corners; false when it has no volume. qhull rejects
// some inputs with points a rounding error apart (clip points next to vertices); those are
// retried without points closer than `snap` to another, which moves the hull by at most `snap`.
bool buildHull(Cell& cell, double snap);

// The hull of a candidate child of a cut or of a merged pair, to rank and measure it: quickHull (a
// point within `snap` of the hull counts as inside), or buildHull where quickHull gives none. Its
// `planes` stay empty until keepHull.
bool buildCandidateHull(Cell& cell, double snap);

// Gives a candidate that is kept (a chosen child or an executed merge) the hull of buildHull, which
// contains every point; where qhull fails on them, the candidate hull with the planes of its
// triangles. Its concavity, measured on the candidate hull, stays: both hulls cover the same
// points up to `snap`.
void keepHull(Cell& cell, double snap);

// What the phases of step 2 share: the solid, tolerances, sample counts, seed and threads.
struct DecompositionContext {
  // Runs the candidate cuts' hulls and step 3's pieces; in decomposeBoundingEach its workers help
  // once they have no mesh left.
  WorkerPool& workers;
  const Solid& solid;
  double tolerance;           // geometric tolerance, a tiny fraction of the diagonal
  double snap;                // largest distance a hull may lose points by (see buildHull)
  std::size_t samples;        // random samples per hull for its concavity
  std::size_t bridgeSamples;  // random samples on the bridge of a merged hull
  std::uint64_t seed;
};

// The seed of the random samples a measurement with `salt` draws.
std::uint64_t sampleSeed(const DecompositionContext& context, std::uint64_t salt);

// The piece's concavity on samples of its hull (`salt` picks the random ones). The measurement
// stops once the concavity reaches `stopAt`; returns false then (the concavity is at least that).
bool measureConcavity(Cell& cell, const DecompositionContext& context, std::uint64_t salt,
                      double stopAt = std::numeric_limits<double>::infinity());

}  // namespace kaboum::geometry
