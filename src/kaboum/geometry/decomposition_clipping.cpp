#include "kaboum/geometry/decomposition_clipping.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace kaboum::geometry {
namespace {

// Where the edge pq crosses the plane (signed distances sp, sq of opposite signs), computed from
// the lexicographically smaller end so that both triangles of an edge give the same bits.
Vec3 crossing(const Vec3& p, const Vec3& q, double sp, double sq) {
  if (lexicographicLess(q, p)) return q + (p - q) * (sq / (sq - sp));
  return p + (q - p) * (sp / (sp - sq));
}

bool crosses(double sp, double sq, double tolerance) {
  return (sp < -tolerance && sq > tolerance) || (sp > tolerance && sq < -tolerance);
}

// The distinct corners the clipped polygons of `from` would have on the side n.x <= d +
// tolerance: its own points on that side and the crossings of its polygon edges (without
// building the polygons, which only the chosen split needs).
void clipPoints(const Cell& from, const HullPlane& plane, double tolerance, Cell& to) {
  to.points.clear();
  const auto side = [&](const Vec3& p) { return plane.normal.dot(p) - plane.offset; };
  for (const Vec3& p : from.points) {
    if (side(p) <= tolerance) to.points.push_back(p);
  }
  const auto kept = static_cast<std::ptrdiff_t>(to.points.size());
  std::uint32_t begin = 0;
  for (const std::uint32_t end : from.polygonEnds) {
    const double first = side(from.polygonPoints[begin]);
    double sp = first;  // of the edge's start, carried over from the previous edge's end
    for (std::uint32_t i = begin; i < end; ++i) {
      const bool closing = i + 1 == end;
      const Vec3& p = from.polygonPoints[i];
      const Vec3& q = from.polygonPoints[closing ? begin : i + 1];
      const double sq = closing ? first : side(q);
      if (crosses(sp, sq, tolerance)) to.points.push_back(crossing(p, q, sp, sq));
      sp = sq;
    }
    begin = end;
  }
  std::sort(to.points.begin() + kept, to.points.end(), lexicographicLess);
  std::inplace_merge(to.points.begin(), to.points.begin() + kept, to.points.end(),
                     lexicographicLess);
  to.points.erase(std::unique(to.points.begin(), to.points.end()), to.points.end());
}

// The walls of the part of `from` on the side n.x <= d of `cut` (those of `from` and the cut, last)
// and its corners that lie in the solid: the inside corners of `from` on that side, and the new
// corners where the cut meets two other walls. The walls include the bound's enlarged bounding
// box, so every cell is bounded.
void clipCorners(const Cell& from, const HullPlane& cut, const Solid& solid, double tolerance,
                 Cell& to) {
  to.walls = from.walls;
  to.walls.push_back(cut);
  const std::vector<HullPlane>& walls = to.walls;
  to.corners.clear();
  for (const Vec3& c : from.corners) {
    if (cut.normal.dot(c) <= cut.offset + tolerance) to.corners.push_back(c);
  }
  const std::size_t n = walls.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      Eigen::Matrix3d normals;
      normals << walls[i].normal.transpose(), walls[j].normal.transpose(), cut.normal.transpose();
      if (std::abs(normals.determinant()) < 1e-9) continue;
      const Vec3 corner =
          normals.partialPivLu().solve(Vec3(walls[i].offset, walls[j].offset, cut.offset));
      const bool feasible = std::all_of(walls.begin(), walls.end(), [&](const HullPlane& w) {
        return w.normal.dot(corner) <= w.offset + tolerance;
      });
      if (feasible && solid.contains(corner)) to.corners.push_back(corner);
    }
  }
}

}  // namespace

HullPlane otherSide(const HullPlane& plane) {
  return {-plane.normal, -plane.offset};
}

void clipPolygons(const Cell& from, const HullPlane& plane, double tolerance, Cell& to) {
  to.polygonPoints.clear();
  to.polygonEnds.clear();
  std::uint32_t begin = 0;
  for (const std::uint32_t end : from.polygonEnds) {
    const std::size_t before = to.polygonPoints.size();
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3& p = from.polygonPoints[i];
      const Vec3& q = from.polygonPoints[i + 1 < end ? i + 1 : begin];
      const double sp = plane.normal.dot(p) - plane.offset;
      const double sq = plane.normal.dot(q) - plane.offset;
      if (sp <= tolerance) to.polygonPoints.push_back(p);
      if (crosses(sp, sq, tolerance)) to.polygonPoints.push_back(crossing(p, q, sp, sq));
    }
    if (to.polygonPoints.size() > before) {
      to.polygonEnds.push_back(static_cast<std::uint32_t>(to.polygonPoints.size()));
    }
    begin = end;
  }
}

std::optional<Cell> childCell(const Cell& parent, const HullPlane& cut,
                              const DecompositionContext& context) {
  Cell child;
  clipPoints(parent, cut, context.tolerance, child);
  if (child.points.empty()) return std::nullopt;
  clipCorners(parent, cut, context.solid, context.tolerance, child);
  if (!buildCandidateHull(child, context.snap)) return std::nullopt;
  return child;
}

std::vector<Cell> clipRegion(const std::vector<Cell>& region, const HullPlane& cut,
                             const DecompositionContext& context, bool polygons) {
  std::vector<Cell> clipped;
  const auto side = [&](const Vec3& p) { return cut.normal.dot(p) - cut.offset; };
  for (const Cell& cell : region) {
    // A cell whose surface and inside corners all lie clearly on one side is not crossed where it
    // holds solid: it stays whole on that side (the cut adds no corner in the solid) and is left
    // out on the other.
    const auto clearly = [&](auto test) {
      return std::all_of(cell.points.begin(), cell.points.end(), test) &&
             std::all_of(cell.corners.begin(), cell.corners.end(), test);
    };
    if (clearly([&](const Vec3& p) { return side(p) > context.tolerance; })) continue;
    if (clearly([&](const Vec3& p) { return side(p) < -context.tolerance; })) {
      clipped.push_back(cell);
      continue;
    }
    Cell child;
    clipPoints(cell, cut, context.tolerance, child);
    clipCorners(cell, cut, context.solid, context.tolerance, child);
    if (child.points.empty() && child.corners.empty()) continue;
    if (polygons) {
      clipPolygons(cell, cut, context.tolerance, child);
      if (!buildCandidateHull(child, context.snap)) child.hull = {};
    }
    clipped.push_back(std::move(child));
  }
  return clipped;
}

}  // namespace kaboum::geometry
