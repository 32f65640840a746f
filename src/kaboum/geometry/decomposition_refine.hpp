// Internal phase of the bounding convex decomposition (thesis §4.4.2 step 2, re-cuts after
// merging, opt-in): the worst piece re-cut with a neighbour, or alone while another pair merges,
// so that the partition itself changes where merging left a loose piece.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kaboum/geometry/decomposition_cell.hpp"
#include "kaboum/geometry/decomposition_merge.hpp"

namespace kaboum::geometry {

// Lowers the largest concavity left by merging with two moves on the worst piece: re-cut it and a
// neighbour with one plane (the plane may cross their cells, so the border between them leaves
// the cuts of the split; the nearest neighbours are tried in turn, up to the first whose best
// cut gets below the bar), or else cut it in two and merge the cheapest touching pair instead. A
// move is kept when every piece it makes, measured again on more samples, is below the worst
// piece's concavity. Repeated until no move helps the worst piece or `rounds` moves are made;
// returns how many.
std::size_t refinePieces(std::vector<Piece>& pieces, std::size_t rounds,
                         const DecompositionContext& context, double touchTolerance,
                         std::uint64_t& measured);

}  // namespace kaboum::geometry
