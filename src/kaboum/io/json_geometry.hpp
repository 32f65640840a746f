// JSON of geometry results: mesh analysis, distance statistics, the bounding mesh verifier's
// reports, bounding mesh and convex decomposition results. Objects use snake_case keys; lengths
// are in the mesh's units, with maxima also as a percentage of the bounding-box diagonal.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>

#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/convex_decomposition.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

// vertices, triangles, components, border_edges, border_loops, non_manifold_edges,
// non_manifold_vertices, degenerate_triangles, closed, edge_manifold, consistently_oriented,
// outward_oriented, volume, diagonal, box_min [x, y, z], box_max [x, y, z].
nlohmann::json toJson(const MeshAnalysis& analysis);

// min, mean, max, max_percent_of_diagonal (of `diagonal`).
nlohmann::json toJson(const DistanceStats& stats, double diagonal);

// original_to_result and result_to_original (DistanceStats), diagonal, samples.
nlohmann::json toJson(const HausdorffReport& report);

// containment_defined, note, samples_checked, violations, worst_violation,
// self_intersecting_pairs, inside_out.
nlohmann::json toJson(const ContainmentReport& report);

// Contractions per second of Algorithm 2 (0 when no time was measured), reported as
// contractions_per_second.
double contractionsPerSecond(const BoundingMeshStats& stats);

// input_vertices, output_vertices, output_triangles, contractions, seconds, runs,
// contractions_per_second, stop_reason, locked_vertices, rejected {infeasible, topology, geometry,
// crossing}, polish {moves, flips, relocations, seconds}, quadric_error.
nlohmann::json toJson(const BoundingMeshResult& result);

// Vertices per convex piece (Table 4.3's column), reported as vertices_per_piece.
struct PieceVertexCounts {
  std::size_t min = 0, max = 0;
  double mean = 0.0;
};
// `pieces` must not be empty.
PieceVertexCounts pieceVertexCounts(std::span<const ConvexPiece> pieces);

// Table 4.3's distances: original_to_approximation and approximation_to_original (DistanceStats),
// diagonal, samples, uncovered_samples, worst_uncovered.
nlohmann::json toJson(const DecompositionQuality& quality);

// input_vertices, input_triangles, holes_filled, epsilon, epsilon_percent_of_diagonal (of the
// quality's diagonal), pieces, total_vertices, vertices_per_piece {min, mean, max},
// bounded_vertices, hull_vertices, splits, refinements, stop_reason, estimated_error, seconds,
// distances (the quality).
nlohmann::json toJson(const Decomposition& decomposition, const DecompositionQuality& quality);

}  // namespace kaboum::io
