// The bounding convex decomposition's entry points and its pipeline (thesis §4.4.2): preparing
// the input (step 0), the outer bound (step 1), then the phases of step 2 (decomposition_split,
// _merge and _refine) and step 3 (decomposition_simplify); measuring a decomposition.
#include "kaboum/geometry/convex_decomposition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <utility>

#include "kaboum/core/error.hpp"
#include "kaboum/core/worker_pool.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/decomposition_cell.hpp"
#include "kaboum/geometry/decomposition_merge.hpp"
#include "kaboum/geometry/decomposition_refine.hpp"
#include "kaboum/geometry/decomposition_simplify.hpp"
#include "kaboum/geometry/decomposition_split.hpp"
#include "kaboum/geometry/hole_filling.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"

namespace kaboum::geometry {
namespace {

// How ε is shared between the three steps of §4.4.2 (the distances add up by the triangle
// inequality): the outer bound of step 1, the concavity left by step 2, the growth in step 3.
constexpr double kBoundShare = 0.1;
constexpr double kConcavityShare = 0.55;
constexpr double kSimplifyShare = 0.35;
static_assert(kBoundShare + kConcavityShare + kSimplifyShare <= 1.0);
constexpr std::size_t kSplitBeyondLimit = 3;  // split up to this many times the piece limit

// The edge-connected components of `mesh` as separate meshes, each with a flag: closed (every
// edge has exactly two triangles).
std::vector<std::pair<TriangleMesh, bool>> splitComponents(const TriangleMesh& mesh) {
  const EdgeNeighbors neighbors = findEdgeNeighbors(mesh);
  const std::size_t count = mesh.triangles.size();
  constexpr std::uint32_t kUnset = 0xffffffffu;
  std::vector<std::uint32_t> component(count, kUnset);
  std::vector<std::pair<TriangleMesh, bool>> components;
  std::vector<std::uint32_t> vertexMap(mesh.vertices.size(), kUnset);
  std::vector<std::uint32_t> stack, touched;
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (component[seed] != kUnset) continue;
    auto& [part, closed] = components.emplace_back(TriangleMesh{}, true);
    const auto id = static_cast<std::uint32_t>(components.size() - 1);
    component[seed] = id;
    stack.assign(1, static_cast<std::uint32_t>(seed));
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      Triangle local{};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.triangles[t][k];
        if (vertexMap[v] == kUnset) {
          vertexMap[v] = static_cast<std::uint32_t>(part.vertices.size());
          part.vertices.push_back(mesh.vertices[v]);
          touched.push_back(v);
        }
        local[k] = vertexMap[v];
        const std::uint32_t other = neighbors.across[3 * t + k];
        if (other >= count) {
          closed = false;  // border, non-manifold edge or repeated index
        } else if (component[other] == kUnset) {
          component[other] = id;
          stack.push_back(other);
        }
      }
      part.triangles.push_back(local);
    }
    for (const std::uint32_t v : touched) vertexMap[v] = kUnset;  // shared with later components
    touched.clear();
  }
  return components;
}

// Welded, outward, hole-filled copy of the input; InputError for unusable input.
TriangleMesh closedInput(const TriangleMesh& mesh, DecompositionStats& stats) {
  if (mesh.triangles.empty()) throw InputError("mesh has no triangles");
  for (const Vec3& v : mesh.vertices) {
    if (!v.allFinite()) throw InputError("mesh has a non-finite vertex coordinate");
  }
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t i : t) {
      if (i >= mesh.vertices.size()) throw InputError("mesh has a vertex index out of range");
    }
  }
  TriangleMesh closed = mesh;
  weldVertices(closed);
  bool flipped = false;
  if (!orientOutward(closed, flipped)) {
    throw InputError(
        "mesh cannot be oriented consistently (non-orientable or non-manifold surface)");
  }
  stats.holesFilled = fillHoles(closed).loops;
  if (!(meshVolume(closed) > 1e-12 * std::pow(boundingBoxDiagonal(closed), 3))) {
    throw InputError("mesh encloses no volume (flat, or its holes could not be closed outward)");
  }
  return closed;
}

// §4.4.2 step 1: an outer bounding mesh within `maxError` (Hausdorff distance measured on samples)
// of every edge-connected component on its own (components may overlap; the solid is their union).
// The bounding mesh algorithm keeps its result outside an embedded closed input; a component
// that is open (non-manifold edges) or self-intersecting (common in CAD exports; hole caps can
// fold) has no well-defined outside and is kept as it is: step 2 contains its whole surface.
// `boundError` receives the largest distance measured, `componentsKept` counts the kept ones.
TriangleMesh outerBound(const TriangleMesh& closed, double maxError, double& boundError,
                        std::size_t& componentsKept) {
  TriangleMesh bound;
  for (auto& [part, partClosed] : splitComponents(closed)) {
    if (partClosed && countSelfIntersections(part) == 0) {
      BoundingMeshOptions boundOptions;
      boundOptions.side = BoundSide::Outer;
      HausdorffReport boundDistance;
      part = simplifyBoundingWithin(part, boundOptions, maxError, 2000, boundDistance, 3).mesh;
      boundError = std::max(boundError, boundDistance.resultToOriginal.max);
    } else {
      ++componentsKept;
    }
    const auto offset = static_cast<std::uint32_t>(bound.vertices.size());
    bound.vertices.insert(bound.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const Triangle& t : part.triangles) {
      bound.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }
  return bound;
}

// decomposeBounding, with the candidate cuts' hulls and step 3's pieces as tasks of `workers`.
Decomposition decomposeOn(const TriangleMesh& mesh, const DecompositionOptions& options,
                          WorkerPool& workers) {
  const auto start = std::chrono::steady_clock::now();
  if (std::isnan(options.epsilon) || options.epsilon < 0.0) {
    throw InputError("epsilon must be a positive distance");
  }
  Decomposition result;
  DecompositionStats& stats = result.stats;
  stats.inputVertices = mesh.vertexCount();
  stats.inputTriangles = mesh.triangleCount();
  result.closedInput = closedInput(mesh, stats);
  const TriangleMesh& closed = result.closedInput;
  stats.diagonal = boundingBoxDiagonal(closed);
  stats.epsilon =
      options.epsilon > 0.0 ? options.epsilon : options.epsilonPercent / 100.0 * stats.diagonal;
  if (!(stats.epsilon > 0.0) || !std::isfinite(stats.epsilon)) {
    throw InputError("epsilon must be a positive distance");
  }
  if (options.maxPieces == 0) throw InputError("the piece limit must be at least 1");
  const double tolerance = 1e-12 * stats.diagonal;

  // Step 1: an outer bounding mesh at about ε/10.
  double boundError = 0.0;
  const TriangleMesh bound =
      outerBound(closed, kBoundShare * stats.epsilon, boundError, stats.componentsKept);
  stats.boundedVertices = bound.vertexCount();

  // Step 2: hierarchical plane splits, the worst concavity first. Splitting goes past the piece
  // limit; merging brings the count back (better cuts than a top-down split stopped early), and
  // re-cuts may change the partition after that.
  const Solid solid(bound, 1e-9 * stats.diagonal);
  const DecompositionContext context{workers,
                                     solid,
                                     tolerance,
                                     1e-8 * stats.diagonal,
                                     options.concavitySamples,
                                     options.bridgeSamples,
                                     options.seed};
  const double concavityBudget = kConcavityShare * stats.epsilon;
  std::uint64_t measured = 0;  // measurements made, each drawing samples with its own salt
  Cell root = rootCell(bound, 0.01 * stats.diagonal, context, measured);
  const std::size_t splitLimit = std::max<std::size_t>(kSplitBeyondLimit * options.maxPieces, 2);
  std::vector<Cell> leaves =
      splitCells(std::move(root), splitLimit, concavityBudget, context, measured, stats.splits);
  const std::size_t leafCount = leaves.size();
  const double touchTolerance = 1e-6 * stats.diagonal;
  std::vector<Piece> pieces = mergeLeaves(std::move(leaves), options.maxPieces, concavityBudget,
                                          context, touchTolerance, measured);
  stats.refinements = refinePieces(pieces, options.refineRounds, context, touchTolerance, measured);
  stats.merges = leafCount - pieces.size();
  const bool limited = std::any_of(pieces.begin(), pieces.end(), [&](const Piece& piece) {
    return piece.cell.concavity > concavityBudget;
  });
  const bool atLimit = stats.splits + 1 >= splitLimit || pieces.size() >= options.maxPieces;
  stats.stopReason = !limited  ? "within epsilon"
                     : atLimit ? "piece limit reached"
                               : "cuts stopped reducing the concavity";

  // Step 3: fewer vertices per piece, staying outside it and convex (pieces shared with idle
  // workers).
  std::vector<std::pair<ConvexHull, double>> simplified(pieces.size());
  workers.run(pieces.size(), [&](std::size_t i) {
    simplified[i] = simplifyPiece(pieces[i].cell.hull, kSimplifyShare * stats.epsilon);
  });
  double worstConcavity = 0.0, worstGrowth = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    stats.hullVertices += pieces[i].cell.hull.mesh.vertexCount();
    worstConcavity = std::max(worstConcavity, pieces[i].cell.concavity);
    auto& [hull, growth] = simplified[i];
    worstGrowth = std::max(worstGrowth, growth);
    stats.totalVertices += hull.mesh.vertexCount();
    result.pieces.push_back({std::move(hull.mesh), std::move(hull.planes)});
  }
  stats.estimatedError = boundError + worstConcavity + worstGrowth;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

bool ConvexPiece::contains(const Vec3& p, double tolerance) const {
  return std::all_of(planes.begin(), planes.end(),
                     [&](const HullPlane& h) { return h.normal.dot(p) <= h.offset + tolerance; });
}

Decomposition decomposeBounding(const TriangleMesh& mesh, const DecompositionOptions& options) {
  WorkerPool inlineWorkers(1);
  return decomposeOn(mesh, options, inlineWorkers);
}

Decomposition decomposeBounding(const TriangleMesh& mesh, const DecompositionOptions& options,
                                WorkerPool& workers) {
  return decomposeOn(mesh, options, workers);
}

std::vector<Decomposition> decomposeBoundingEach(std::span<const TriangleMesh> meshes,
                                                 const DecompositionOptions& options,
                                                 unsigned threads) {
  std::vector<Decomposition> results(meshes.size());
  std::vector<std::exception_ptr> errors(meshes.size());
  // Largest meshes first, so that no thread is left with a large one at the end.
  std::vector<std::size_t> order(meshes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return meshes[a].triangleCount() > meshes[b].triangleCount();
  });
  // One task per mesh; a worker with no mesh left takes tasks of the others' batches.
  WorkerPool workers(threads);
  workers.run(meshes.size(), [&](std::size_t k) {
    const std::size_t i = order[k];
    try {
      results[i] = decomposeOn(meshes[i], options, workers);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    if (!errors[i]) continue;
    try {
      std::rethrow_exception(errors[i]);
    } catch (const InputError& error) {
      throw InputError(fmt::format("mesh {}: {}", i, error.what()));
    }
  }
  return results;
}

TriangleMesh mergePieces(std::span<const ConvexPiece> pieces) {
  TriangleMesh merged;
  for (const ConvexPiece& piece : pieces) {
    const auto offset = static_cast<std::uint32_t>(merged.vertices.size());
    merged.vertices.insert(merged.vertices.end(), piece.mesh.vertices.begin(),
                           piece.mesh.vertices.end());
    for (const Triangle& t : piece.mesh.triangles) {
      merged.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }
  return merged;
}

DecompositionQuality measureDecomposition(const TriangleMesh& original,
                                          std::span<const ConvexPiece> pieces,
                                          std::size_t randomSamples, std::uint64_t seed) {
  if (pieces.empty()) throw InputError("no convex pieces to measure");
  DecompositionQuality quality;
  quality.diagonal = boundingBoxDiagonal(original);
  const double tolerance = 1e-7 * quality.diagonal;
  const TriangleBvh originalBvh(original);
  const TriangleBvh piecesBvh(mergePieces(pieces));
  const auto accumulate = [](DistanceStats& stats, double d, std::size_t& count) {
    stats.min = count == 0 ? d : std::min(stats.min, d);
    stats.max = std::max(stats.max, d);
    stats.mean += d;
    ++count;
  };

  std::size_t count = 0;
  for (const Vec3& p : sampleSurface(original, randomSamples, seed)) {
    accumulate(quality.originalToApproximation, piecesBvh.closest(p).distance, count);
    double outside = std::numeric_limits<double>::infinity();  // least plane violation
    for (const ConvexPiece& piece : pieces) {
      double violation = 0.0;
      for (const HullPlane& h : piece.planes) {
        violation = std::max(violation, h.normal.dot(p) - h.offset);
      }
      outside = std::min(outside, violation);
    }
    if (outside > tolerance) {
      ++quality.uncovered;
      quality.worstUncovered = std::max(quality.worstUncovered, outside);
    }
  }
  quality.originalToApproximation.mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  quality.samples = count;

  count = 0;
  const std::size_t perPiece = randomSamples / pieces.size() + 1;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (const Vec3& p : sampleSurface(pieces[i].mesh, perPiece, seed + i + 1)) {
      bool inOther = false;
      for (std::size_t j = 0; j < pieces.size() && !inOther; ++j) {
        inOther = j != i && pieces[j].contains(p, tolerance);
      }
      if (!inOther)
        accumulate(quality.approximationToOriginal, originalBvh.closest(p).distance, count);
    }
  }
  quality.approximationToOriginal.mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  quality.samples += count;
  return quality;
}

}  // namespace kaboum::geometry
