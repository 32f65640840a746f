#include "kaboum/io/json_geometry.hpp"

#include <algorithm>

namespace kaboum::io {

using namespace kaboum::geometry;

nlohmann::json toJson(const MeshAnalysis& analysis) {
  const MeshAnalysis& a = analysis;
  return {{"vertices", a.vertices},
          {"triangles", a.triangles},
          {"components", a.components},
          {"border_edges", a.borderEdges},
          {"border_loops", a.borderLoops},
          {"non_manifold_edges", a.nonManifoldEdges},
          {"non_manifold_vertices", a.nonManifoldVertices},
          {"degenerate_triangles", a.degenerateTriangles},
          {"closed", a.closed},
          {"edge_manifold", a.edgeManifold},
          {"consistently_oriented", a.consistentlyOriented},
          {"outward_oriented", a.outwardOriented},
          {"volume", a.volume},
          {"diagonal", a.diagonal},
          {"box_min", {a.boxMin.x(), a.boxMin.y(), a.boxMin.z()}},
          {"box_max", {a.boxMax.x(), a.boxMax.y(), a.boxMax.z()}}};
}

nlohmann::json toJson(const DistanceStats& stats, double diagonal) {
  return {{"min", stats.min},
          {"mean", stats.mean},
          {"max", stats.max},
          {"max_percent_of_diagonal", 100.0 * stats.max / diagonal}};
}

nlohmann::json toJson(const HausdorffReport& report) {
  return {{"original_to_result", toJson(report.originalToResult, report.diagonal)},
          {"result_to_original", toJson(report.resultToOriginal, report.diagonal)},
          {"diagonal", report.diagonal},
          {"samples", report.samples}};
}

nlohmann::json toJson(const ContainmentReport& report) {
  return {{"containment_defined", report.defined},
          {"note", report.note},
          {"samples_checked", report.checked},
          {"violations", report.violations},
          {"worst_violation", report.worstViolation},
          {"self_intersecting_pairs", report.selfIntersectingPairs},
          {"inside_out", report.insideOut}};
}

double contractionsPerSecond(const BoundingMeshStats& stats) {
  return stats.seconds > 0.0 ? static_cast<double>(stats.contractions) / stats.seconds : 0.0;
}

nlohmann::json toJson(const BoundingMeshResult& result) {
  const BoundingMeshStats& s = result.stats;
  return {{"input_vertices", s.inputVertices},
          {"output_vertices", s.outputVertices},
          {"output_triangles", result.mesh.triangles.size()},
          {"contractions", s.contractions},
          {"seconds", s.seconds},
          {"runs", s.runs},
          {"contractions_per_second", contractionsPerSecond(s)},
          {"stop_reason", s.stopReason},
          {"locked_vertices", s.lockedVertices},
          {"rejected",
           {{"infeasible", s.rejectedInfeasible},
            {"topology", s.rejectedTopology},
            {"geometry", s.rejectedGeometry},
            {"crossing", s.rejectedCrossing}}},
          {"polish",
           {{"moves", s.polishMoves},
            {"flips", s.polishFlips},
            {"relocations", s.polishRelocations},
            {"seconds", s.polishSeconds}}},
          {"quadric_error", s.quadricError}};
}

PieceVertexCounts pieceVertexCounts(std::span<const ConvexPiece> pieces) {
  PieceVertexCounts counts{pieces.front().mesh.vertexCount(), 0, 0.0};
  for (const ConvexPiece& piece : pieces) {
    counts.min = std::min(counts.min, piece.mesh.vertexCount());
    counts.max = std::max(counts.max, piece.mesh.vertexCount());
    counts.mean += static_cast<double>(piece.mesh.vertexCount());
  }
  counts.mean /= static_cast<double>(pieces.size());
  return counts;
}

nlohmann::json toJson(const DecompositionQuality& quality) {
  return {{"original_to_approximation", toJson(quality.originalToApproximation, quality.diagonal)},
          {"approximation_to_original", toJson(quality.approximationToOriginal, quality.diagonal)},
          {"diagonal", quality.diagonal},
          {"samples", quality.samples},
          {"uncovered_samples", quality.uncovered},
          {"worst_uncovered", quality.worstUncovered}};
}

nlohmann::json toJson(const Decomposition& decomposition, const DecompositionQuality& quality) {
  const DecompositionStats& s = decomposition.stats;
  const PieceVertexCounts counts = pieceVertexCounts(decomposition.pieces);
  return {{"input_vertices", s.inputVertices},
          {"input_triangles", s.inputTriangles},
          {"holes_filled", s.holesFilled},
          {"epsilon", s.epsilon},
          {"epsilon_percent_of_diagonal", 100.0 * s.epsilon / quality.diagonal},
          {"pieces", decomposition.pieces.size()},
          {"total_vertices", s.totalVertices},
          {"vertices_per_piece", {{"min", counts.min}, {"mean", counts.mean}, {"max", counts.max}}},
          {"bounded_vertices", s.boundedVertices},
          {"hull_vertices", s.hullVertices},
          {"splits", s.splits},
          {"refinements", s.refinements},
          {"stop_reason", s.stopReason},
          {"estimated_error", s.estimatedError},
          {"seconds", s.seconds},
          {"distances", toJson(quality)}};
}

}  // namespace kaboum::io
