// Internal part of the bounding convex decomposition (thesis §4.4.2 step 2): a cell cut by a
// plane. The part on one side keeps the bound's polygons clipped exactly, the cell's walls and the
// cut, and the cell corners in the solid, so that its piece contains the solid on that side
// (docs/decomposition.md, "What is guaranteed").
#pragma once

#include <optional>
#include <vector>

#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/decomposition_cell.hpp"

namespace kaboum::geometry {

// The plane of `plane` with the other side as below.
HullPlane otherSide(const HullPlane& plane);

// Keeps the part of every polygon of `from` with n.x <= d + tolerance (Sutherland-Hodgman).
void clipPolygons(const Cell& from, const HullPlane& plane, double tolerance, Cell& to);

// The part of `parent` on the side n.x <= d of `cut` with its candidate hull, or nothing when it
// has no volume. Its polygons are left out (clipPolygons adds them to the cell that is kept).
std::optional<Cell> childCell(const Cell& parent, const HullPlane& cut,
                              const DecompositionContext& context);

// The part of a region on the side n.x <= d of `cut`: every cell clipped to it (its polygons only
// when `polygons`), cells left with neither surface nor inside corners dropped.
std::vector<Cell> clipRegion(const std::vector<Cell>& region, const HullPlane& cut,
                             const DecompositionContext& context, bool polygons);

}  // namespace kaboum::geometry
