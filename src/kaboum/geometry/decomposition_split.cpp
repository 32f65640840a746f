#include "kaboum/geometry/decomposition_split.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"

namespace kaboum::geometry {
namespace {

constexpr int kCutsPerAxis = 5;  // evenly spaced candidate planes per axis, plus one at the worst
                                 // concavity sample
// A cell whose concavity survived this many splits in a row (each keeping more than kStallRatio
// of it) is not split further: the splits are better spent elsewhere (a round pocket, say, needs
// more cuts through it than the piece limit allows).
constexpr int kMaxStalls = 8;
constexpr double kStallRatio = 0.9;
constexpr std::size_t kShortlist = 1;  // least-volume cuts whose children's concavity is measured
constexpr int kPocketNormals = 6;  // cut planes through the worst sample, turned about its depth

// Candidate cut directions: the coordinate axes and the principal axes of the hull's vertices.
std::vector<Vec3> cutAxes(const Cell& cell) {
  std::vector<Vec3> axes{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  const auto& vertices = cell.hull.mesh.vertices;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : vertices) mean += v;
  mean /= static_cast<double>(vertices.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& v : vertices) covariance += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  for (int i = 2; i >= 0; --i) {
    const Vec3 axis = solver.eigenvectors().col(i).normalized();
    const bool coordinateAxis = std::any_of(axes.begin(), axes.begin() + 3, [&](const Vec3& a) {
      return std::abs(a.dot(axis)) > 1.0 - 1e-6;
    });
    if (!coordinateAxis && axis.allFinite()) axes.push_back(axis);
  }
  return axes;
}

// Normals of planes through the cell's worst concavity sample w that contain its depth direction
// (from w to the nearest point of the solid), kPocketNormals of them evenly turned about it: one of
// them cuts the pocket or bore under w through its middle, whatever its orientation (V-HACD and
// CoACD search cut planes through the most concave points in the same spirit).
std::vector<Vec3> pocketNormals(const Cell& cell, const Solid& solid) {
  const Vec3 depth = solid.closestPoint(cell.worstPoint) - cell.worstPoint;
  if (!(depth.norm() > 0.0)) return {};
  const Vec3 d = depth.normalized();
  const Vec3 u = d.unitOrthogonal(), v = d.cross(u);
  std::vector<Vec3> normals;
  for (int k = 0; k < kPocketNormals; ++k) {
    const double angle = M_PI * k / kPocketNormals;
    normals.push_back(std::cos(angle) * u + std::sin(angle) * v);
  }
  return normals;
}

// The split of `cell` chosen by chooseCandidate among its candidate cuts; nothing when no
// candidate cuts it in two (a side without volume). The children come with their concavity
// measured and their polygons clipped. They are ranked and measured on quickHull's hulls; only
// the chosen children get qhull's (keepHull).
std::optional<std::pair<Cell, Cell>> bestSplit(const Cell& cell,
                                               const DecompositionContext& context,
                                               std::uint64_t& measured) {
  std::vector<Candidate> candidates = cutCandidates(
      candidateCuts(cell, context.solid),
      [&](const HullPlane& plane) { return childCell(cell, plane, context); }, context.workers);
  std::optional<Candidate> chosen = chooseCandidate(
      std::move(candidates), std::numeric_limits<double>::infinity(), context, measured);
  if (!chosen) return std::nullopt;
  keepHull(chosen->below, context.snap);
  keepHull(chosen->above, context.snap);
  clipPolygons(cell, chosen->cut.plane, context.tolerance, chosen->below);
  clipPolygons(cell, otherSide(chosen->cut.plane), context.tolerance, chosen->above);
  return std::pair{std::move(chosen->below), std::move(chosen->above)};
}

}  // namespace

std::vector<Cut> candidateCuts(const Cell& cell, const Solid& solid) {
  std::vector<Cut> cuts;
  for (const Vec3& axis : cutAxes(cell)) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Vec3& v : cell.hull.mesh.vertices) {
      lo = std::min(lo, axis.dot(v));
      hi = std::max(hi, axis.dot(v));
    }
    for (int k = 1; k <= kCutsPerAxis; ++k) {
      cuts.push_back({{axis, lo + (hi - lo) * k / (kCutsPerAxis + 1)}, false});
    }
    const double worst = axis.dot(cell.worstPoint);
    if (worst > lo + 0.02 * (hi - lo) && worst < hi - 0.02 * (hi - lo)) {
      cuts.push_back({{axis, worst}, true});
    }
  }
  for (const Vec3& normal : pocketNormals(cell, solid)) {
    cuts.push_back({{normal, normal.dot(cell.worstPoint)}, true});
  }
  return cuts;
}

std::optional<Candidate> chooseCandidate(std::vector<Candidate> candidates, double bar,
                                         const DecompositionContext& context,
                                         std::uint64_t& measured) {
  if (candidates.empty()) return std::nullopt;
  const auto volume = [](const Candidate& c) { return c.below.hullVolume + c.above.hullVolume; };
  const std::size_t shortlist = std::min(kShortlist, candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(shortlist),
                    candidates.end(),
                    [&](const auto& a, const auto& b) { return volume(a) < volume(b); });
  // The measured candidates (the shortlist and the cuts through the worst sample), each with the
  // salt of its children's samples. They are measured least total volume first, which tends to
  // set a low bar early so that the others stop sooner; the winner is the one whose larger child
  // concavity is smallest, the first in candidate order among equals, whatever the order of
  // measurement.
  struct ToMeasure {
    std::size_t index;
    std::uint64_t salt;
  };
  std::vector<ToMeasure> toMeasure;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i >= shortlist && !candidates[i].cut.throughWorst) continue;
    toMeasure.push_back({i, measured});
    measured += 2;
  }
  std::stable_sort(toMeasure.begin(), toMeasure.end(), [&](const auto& a, const auto& b) {
    return volume(candidates[a.index]) < volume(candidates[b.index]);
  });
  std::size_t best = candidates.size();
  double bestConcavity = bar;
  for (const ToMeasure& m : toMeasure) {
    Candidate& c = candidates[m.index];
    // A candidate loses as soon as one child reaches the best concavity so far (passes it, for a
    // candidate earlier in candidate order than the best, which wins a tie).
    const double stopAt =
        best < candidates.size() && m.index < best
            ? std::nextafter(bestConcavity, std::numeric_limits<double>::infinity())
            : bestConcavity;
    if (!measureConcavity(c.below, context, m.salt, stopAt) ||
        !measureConcavity(c.above, context, m.salt + 1, stopAt)) {
      continue;
    }
    bestConcavity = std::max(c.below.concavity, c.above.concavity);
    best = m.index;
  }
  if (best == candidates.size()) return std::nullopt;
  return std::move(candidates[best]);
}

Cell rootCell(const TriangleMesh& bound, double margin, const DecompositionContext& context,
              std::uint64_t& measured) {
  Cell root;
  for (const Triangle& t : bound.triangles) {
    for (const std::uint32_t v : t) root.polygonPoints.push_back(bound.vertices[v]);
    root.polygonEnds.push_back(static_cast<std::uint32_t>(root.polygonPoints.size()));
  }
  root.points = root.polygonPoints;
  sortPoints(root.points);
  const MeshAnalysis boundAnalysis = analyzeMesh(bound);
  const Vec3 lo = boundAnalysis.boxMin - Vec3::Constant(margin);
  const Vec3 hi = boundAnalysis.boxMax + Vec3::Constant(margin);
  for (int axis = 0; axis < 3; ++axis) {
    root.walls.push_back({Vec3::Unit(axis), hi[axis]});
    root.walls.push_back({-Vec3::Unit(axis), -lo[axis]});
  }
  if (!buildHull(root, context.snap)) throw InputError("mesh encloses no volume");
  measureConcavity(root, context, measured++);
  return root;
}

std::vector<Cell> splitCells(Cell root, std::size_t limit, double budget,
                             const DecompositionContext& context, std::uint64_t& measured,
                             std::size_t& splits) {
  std::vector<Cell> leaves;
  std::vector<Cell> open{std::move(root)};  // cells that may still be split
  const auto byConcavity = [](const Cell& a, const Cell& b) { return a.concavity < b.concavity; };
  while (!open.empty()) {
    const auto worst = std::max_element(open.begin(), open.end(), byConcavity);
    if (worst->concavity <= budget) break;
    if (leaves.size() + open.size() >= limit) break;
    Cell cell = std::move(*worst);
    open.erase(worst);
    auto split = bestSplit(cell, context, measured);
    if (!split) {
      leaves.push_back(std::move(cell));
      continue;
    }
    ++splits;
    for (Cell* child : {&split->first, &split->second}) {
      child->stalls = child->concavity > kStallRatio * cell.concavity ? cell.stalls + 1 : 0;
      (child->stalls >= kMaxStalls ? leaves : open).push_back(std::move(*child));
    }
  }
  for (Cell& cell : open) leaves.push_back(std::move(cell));
  return leaves;
}

}  // namespace kaboum::geometry
