#include "kaboum/geometry/decomposition_refine.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include "kaboum/geometry/decomposition_clipping.hpp"
#include "kaboum/geometry/decomposition_split.hpp"

namespace kaboum::geometry {
namespace {

constexpr std::size_t kRefineNeighbours = 4;  // neighbours a re-cut of the worst piece tries

// The candidate hull of a region's points: its cells' hull vertices, or for a cell without a hull
// its polygon corners and inside corners.
std::optional<Cell> regionHull(const std::vector<Cell>& region,
                               const DecompositionContext& context) {
  Cell hull;
  for (const Cell& cell : region) {
    const std::vector<Vec3>& vertices = cell.hull.mesh.vertices;
    if (!vertices.empty()) {
      hull.points.insert(hull.points.end(), vertices.begin(), vertices.end());
      continue;
    }
    hull.points.insert(hull.points.end(), cell.points.begin(), cell.points.end());
    hull.points.insert(hull.points.end(), cell.corners.begin(), cell.corners.end());
  }
  sortPoints(hull.points);
  if (!buildCandidateHull(hull, context.snap)) return std::nullopt;
  return hull;
}

// The cut of a region chosen by chooseCandidate among the candidate cuts of the hull `vertices`
// with the worst sample `worstPoint`, with its parts' larger concavity; nothing when none is below
// `bar`.
std::optional<std::pair<HullPlane, double>> bestRegionCut(const std::vector<Cell>& region,
                                                          const std::vector<Vec3>& vertices,
                                                          const Vec3& worstPoint, double bar,
                                                          const DecompositionContext& context,
                                                          std::uint64_t& measured) {
  Cell shape;
  shape.hull.mesh.vertices = vertices;
  shape.worstPoint = worstPoint;
  std::vector<Candidate> candidates = cutCandidates(
      candidateCuts(shape, context.solid),
      [&](const HullPlane& plane) {
        return regionHull(clipRegion(region, plane, context, false), context);
      },
      context.workers);
  const std::optional<Candidate> chosen =
      chooseCandidate(std::move(candidates), bar, context, measured);
  if (!chosen) return std::nullopt;
  return std::pair{chosen->cut.plane, std::max(chosen->below.concavity, chosen->above.concavity)};
}

// The two pieces `cut` makes of a region, measured again on more samples; nothing unless both are
// below `bar`.
std::optional<std::pair<Piece, Piece>> cutPieces(const std::vector<Cell>& region,
                                                 const HullPlane& cut, double bar,
                                                 const DecompositionContext& context,
                                                 std::uint64_t& measured) {
  Piece below, above;
  below.region = clipRegion(region, cut, context, true);
  above.region = clipRegion(region, otherSide(cut), context, true);
  auto belowHull = regionHull(below.region, context);
  auto aboveHull = regionHull(above.region, context);
  if (!belowHull || !aboveHull) return std::nullopt;
  below.cell = std::move(*belowHull);
  above.cell = std::move(*aboveHull);
  DecompositionContext thorough = context;
  thorough.samples = context.bridgeSamples;
  const std::uint64_t salt = measured;
  measured += 2;
  if (!measureConcavity(below.cell, thorough, salt, bar) ||
      !measureConcavity(above.cell, thorough, salt + 1, bar)) {
    return std::nullopt;
  }
  keepHull(below.cell, context.snap);
  keepHull(above.cell, context.snap);
  return std::pair{std::move(below), std::move(above)};
}

std::vector<Cell> joinedRegion(const Piece& a, const Piece& b) {
  std::vector<Cell> region = a.region;
  region.insert(region.end(), b.region.begin(), b.region.end());
  return region;
}

std::vector<Vec3> joinedVertices(const Piece& a, const Piece& b) {
  std::vector<Vec3> vertices = a.cell.hull.mesh.vertices;
  vertices.insert(vertices.end(), b.cell.hull.mesh.vertices.begin(),
                  b.cell.hull.mesh.vertices.end());
  return vertices;
}

// The pieces touching piece `worst`, nearest its worst sample first (by how far that sample lies
// beyond their facet planes), at most kRefineNeighbours of them.
std::vector<std::size_t> nearestNeighbours(const std::vector<Piece>& pieces, std::size_t worst,
                                           double touchTolerance) {
  const Cell& cell = pieces[worst].cell;
  std::vector<std::pair<double, std::size_t>> byExcess;
  for (std::size_t q = 0; q < pieces.size(); ++q) {
    if (q == worst || !boxesTouch(cell, pieces[q].cell, touchTolerance)) continue;
    double excess = 0.0;
    for (const HullPlane& h : pieces[q].cell.hull.planes) {
      excess = std::max(excess, h.normal.dot(cell.worstPoint) - h.offset);
    }
    byExcess.emplace_back(excess, q);
  }
  std::sort(byExcess.begin(), byExcess.end());
  std::vector<std::size_t> nearest;
  for (const auto& [excess, q] : byExcess) {
    if (nearest.size() == kRefineNeighbours) break;
    nearest.push_back(q);
  }
  return nearest;
}

// The touching pair of `pieces` whose merged piece has the smallest concavity below `bar` (bridge
// measure, as in MergeSearch), with that piece; nothing when none is below `bar`.
std::optional<std::pair<std::pair<std::size_t, std::size_t>, Cell>> cheapestMergeBelow(
    const std::vector<Piece>& pieces, double bar, const DecompositionContext& context,
    double touchTolerance, std::uint64_t& measured) {
  std::optional<std::pair<std::pair<std::size_t, std::size_t>, Cell>> best;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const Cell& a = pieces[i].cell;
      const Cell& b = pieces[j].cell;
      if (std::max(a.concavity, b.concavity) >= bar || !boxesTouch(a, b, touchTolerance)) continue;
      std::optional<Cell> merged = mergedCell(a, b, context.snap);
      if (!merged) continue;
      MergedConcavity measurement(*merged, a, b, context, measured++);
      if (!measurement.measure(*merged, context.solid, bar)) continue;
      bar = merged->concavity;
      best = std::pair{std::pair{i, j}, std::move(*merged)};
    }
  }
  return best;
}

}  // namespace

std::size_t refinePieces(std::vector<Piece>& pieces, std::size_t rounds,
                         const DecompositionContext& context, double touchTolerance,
                         std::uint64_t& measured) {
  const auto byConcavity = [](const Piece& a, const Piece& b) {
    return a.cell.concavity < b.cell.concavity;
  };
  std::size_t moves = 0;
  for (; moves < rounds; ++moves) {
    const auto worstIt = std::max_element(pieces.begin(), pieces.end(), byConcavity);
    const auto worst = static_cast<std::size_t>(worstIt - pieces.begin());
    const Piece& piece = *worstIt;
    const double bar = piece.cell.concavity;
    // Move 1: re-cut with a neighbour.
    bool moved = false;
    for (const std::size_t q : nearestNeighbours(pieces, worst, touchTolerance)) {
      const std::vector<Cell> region = joinedRegion(piece, pieces[q]);
      const auto found = bestRegionCut(region, joinedVertices(piece, pieces[q]),
                                       piece.cell.worstPoint, bar, context, measured);
      if (!found) continue;
      auto made = cutPieces(region, found->first, bar, context, measured);
      if (!made) break;
      pieces[worst] = std::move(made->first);
      pieces[q] = std::move(made->second);
      moved = true;
      break;
    }
    if (moved) continue;
    // Move 2: cut the worst piece in two, merge the cheapest touching pair.
    const auto own = bestRegionCut(piece.region, piece.cell.hull.mesh.vertices,
                                   piece.cell.worstPoint, bar, context, measured);
    if (!own) break;
    auto made = cutPieces(piece.region, own->first, bar, context, measured);
    if (!made) break;
    std::vector<Piece> next;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (i != worst) next.push_back(pieces[i]);
    }
    next.push_back(std::move(made->first));
    next.push_back(std::move(made->second));
    auto merge = cheapestMergeBelow(next, bar, context, touchTolerance, measured);
    if (!merge) break;
    const auto [i, j] = merge->first;
    Piece joined{std::move(merge->second), joinedRegion(next[i], next[j])};
    keepHull(joined.cell, context.snap);
    next[i] = std::move(joined);
    next.erase(next.begin() + static_cast<std::ptrdiff_t>(j));
    pieces = std::move(next);
  }
  return moves;
}

}  // namespace kaboum::geometry
