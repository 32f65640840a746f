// Internal phase of the bounding convex decomposition (thesis §4.4.2 step 2, merging): the leaves
// of the split merged down to the piece limit, touching pairs whose merged piece has the smallest
// concavity first, and the bridge measure of a merged piece's concavity (also used by re-cuts).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "kaboum/geometry/decomposition_cell.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// Whether the bounding boxes of the pieces' hulls, the first enlarged by `tolerance`, meet.
bool boxesTouch(const Cell& a, const Cell& b, double tolerance);

// The hull of two pieces together (pieces' vertices only: cells are not needed after splitting).
std::optional<Cell> mergedCell(const Cell& a, const Cell& b, double snap);

// The measurement of the concavity of the merged hull of pieces a and b: the larger of theirs and
// of the samples of the bridge between them (every random sample goes where the merge adds
// concavity, so a narrow gap between the parts is rarely missed). It stops like measureConcavity
// and resumes where it stopped when asked again with a higher limit, which gives what measuring
// afresh would: the parts are alive pieces, whose concavities are measured and do not change.
class MergedConcavity {
 public:
  MergedConcavity(const Cell& merged, const Cell& a, const Cell& b,
                  const DecompositionContext& context, std::uint64_t salt);
  MergedConcavity(const MergedConcavity&) = delete;
  MergedConcavity& operator=(const MergedConcavity&) = delete;

  // Measures on until the concavity reaches `stopAt` and writes it to `merged`; true when complete.
  bool measure(Cell& merged, const Solid& solid, double stopAt);

 private:
  TriangleMesh bridge_;
  SurfaceSampler samples_;  // on bridge_
  Farthest farthest_;
};

// A piece with the leaf cells it covers (their polygons, walls and inside corners).
struct Piece {
  Cell cell;
  std::vector<Cell> region;
};

// The leaves merged: neighbouring pieces (bounding boxes touching within `touchTolerance`) down to
// `maxPieces`, then on while the merged concavity stays within `budget`. Greedy takes the pair
// whose merged piece has the smallest concavity. While at most kLookaheadWindow forced merges are
// left, each of the kLookaheadWidth cheapest pairs is scored instead by the largest concavity at
// the piece limit after completing the remaining merges greedily, and the best score wins (greedy's
// own pair among equals, so the result is never worse than greedy's by this estimate). A piece is
// identified by the leaves it covers and a state by its pieces, so every merged piece is built and
// measured once and every greedy completion followed once, however many look-aheads meet them.
// Concavities are measured lazily: a merged piece starts with its parts' larger concavity as a
// lower bound; its hull is built (by quickHull) and measured only when that bound could win, and
// the measurement stops once it passes the best pair's (or a completion's bar). An executed merge
// gets qhull's hull (keepHull).
std::vector<Piece> mergeLeaves(std::vector<Cell> leaves, std::size_t maxPieces, double budget,
                               const DecompositionContext& context, double touchTolerance,
                               std::uint64_t& measured);

}  // namespace kaboum::geometry
