// Internal phase of the bounding convex decomposition (thesis §4.4.2 step 2, our hierarchical
// plane splits): the candidate cuts of a piece and the choice among them (also used by the re-cuts
// after merging), and the top-down splitting of the bound's cell, the worst concavity first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "kaboum/core/worker_pool.hpp"
#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/decomposition_cell.hpp"
#include "kaboum/geometry/decomposition_clipping.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// A candidate cut (its below side n.x <= d) and whether it passes through the worst sample.
struct Cut {
  HullPlane plane;
  bool throughWorst;
};

// The candidate cuts of a piece with the hull vertices and worst sample w of `cell`:
// axis-parallel and principal-axis planes at evenly spaced positions and through w (unless w is
// within 2% of the ends), and the pocket planes through w.
std::vector<Cut> candidateCuts(const Cell& cell, const Solid& solid);

// A cut with the candidate pieces on its two sides.
struct Candidate {
  Cut cut;
  Cell below, above;
};

// The candidates of the cuts that cut in two: `below(plane)` gives the candidate piece on the side
// n.x <= d of a plane, or nothing when that side has none (the cut is no candidate then). The
// pieces of all cuts are independent tasks of `workers`.
template <typename Below>
std::vector<Candidate> cutCandidates(const std::vector<Cut>& cuts, Below below,
                                     WorkerPool& workers) {
  std::vector<std::optional<Candidate>> children(cuts.size());
  workers.run(cuts.size(), [&](std::size_t k) {
    auto under = below(cuts[k].plane);
    if (!under) return;
    auto over = below(otherSide(cuts[k].plane));
    if (!over) return;
    children[k] = Candidate{cuts[k], std::move(*under), std::move(*over)};
  });
  std::vector<Candidate> candidates;
  for (auto& c : children) {
    if (c) candidates.push_back(std::move(*c));
  }
  return candidates;
}

// The candidate whose two pieces' larger concavity is smallest and below `bar`, among those with
// the smallest total hull volume (kShortlist of them: the hull volume beyond the solid's is what
// concavity grows with, and it is cheap to compare) and the cuts through the worst sample;
// nothing when none is below `bar`. The chosen pieces come with their concavity measured (salts
// from `measured`).
std::optional<Candidate> chooseCandidate(std::vector<Candidate> candidates, double bar,
                                         const DecompositionContext& context,
                                         std::uint64_t& measured);

// The cell of the whole bound: its triangles as polygons, the walls of its bounding box enlarged
// by `margin`, and its hull with its concavity measured (salt from `measured`). InputError when
// the hull has no volume.
Cell rootCell(const TriangleMesh& bound, double margin, const DecompositionContext& context,
              std::uint64_t& measured);

// Splits the cell with the worst concavity by its best cut until every cell is within `budget`,
// there are `limit` cells, or no cell can be split; a cell whose concavity survived kMaxStalls
// splits in a row is not split further. Returns the cells; `splits` counts the splits made.
std::vector<Cell> splitCells(Cell root, std::size_t limit, double budget,
                             const DecompositionContext& context, std::uint64_t& measured,
                             std::size_t& splits);

}  // namespace kaboum::geometry
