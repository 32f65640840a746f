// Internal phase of the bounding convex decomposition (thesis §4.4.2 step 3): every piece
// replaced by a convex piece with fewer vertices that still contains it.
#pragma once

#include <utility>

#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::geometry {

// The convex hull of an outer bounding mesh of `piece`, with its largest distance to the piece. It
// contains the piece and is convex; as the distance to a convex set is a convex function, its
// largest distance to the piece is attained at its vertices, which is measured exactly. The
// quadric-error limit of the bounding mesh algorithm only estimates that distance, so it is
// searched: halved from 8·budget until the result is within `budget`, then bisected towards the
// failing limit; the result with the fewest vertices within `budget` is kept, the piece itself if
// there is none.
std::pair<ConvexHull, double> simplifyPiece(const ConvexHull& piece, double budget);

}  // namespace kaboum::geometry
