// `kaboum decompose`: bounding convex decomposition (thesis §4.4.2) with Table 4.3's figures.
#include <fmt/format.h>

#include <fstream>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/convex_decomposition.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/io/json_geometry.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "mesh_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::io;

namespace {

struct DecomposeArgs {
  std::string input, output;
  std::string epsilon = "3%";
  std::size_t maxPieces = 11;
  std::size_t refineRounds = 0;
  std::size_t samples = 100000;
  bool json = false;
  bool quiet = false;
};

// One OBJ object `piece_i` per piece; indices are global, as OBJ requires.
void writePieces(const std::vector<ConvexPiece>& pieces, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(locate(path, "cannot be written"));
  out << "# kaboum decompose: " << pieces.size() << " convex pieces\n";
  std::size_t offset = 1;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    out << "o piece_" << i << "\n";
    for (const Vec3& v : pieces[i].mesh.vertices) {
      out << fmt::format("v {:.17g} {:.17g} {:.17g}\n", v.x(), v.y(), v.z());
    }
    for (const Triangle& t : pieces[i].mesh.triangles) {
      out << "f " << t[0] + offset << " " << t[1] + offset << " " << t[2] + offset << "\n";
    }
    offset += pieces[i].mesh.vertexCount();
  }
  if (!out.flush()) throw InputError(locate(path, "cannot be written"));
}

int runDecompose(const DecomposeArgs& args) {
  const TriangleMesh mesh = readMesh(args.input);
  DecompositionOptions options;
  options.epsilon = parseEpsilon(args.epsilon, boundingBoxDiagonal(mesh));
  options.maxPieces = args.maxPieces;
  options.refineRounds = args.refineRounds;
  if (!args.quiet) std::cerr << "decompose: " << args.input << "\n";
  Decomposition result;
  DecompositionQuality quality;
  try {
    result = decomposeBounding(mesh, options);
    if (!args.quiet) std::cerr << "decompose: measuring distances\n";
    quality = measureDecomposition(result.closedInput, result.pieces, args.samples, 1);
  } catch (const InputError& e) {
    throw InputError(locate(args.input, e.what()));
  }
  writePieces(result.pieces, args.output);
  const DecompositionStats& s = result.stats;
  const double diagonal = quality.diagonal;

  if (args.json) {
    nlohmann::json out = toJson(result, quality);
    out.update({{"input", args.input}, {"output", args.output}, {"max_pieces", args.maxPieces}});
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << fmt::format(
      "input:  {} vertices, {} triangles ({})\n", s.inputVertices, s.inputTriangles,
      s.holesFilled == 0 ? std::string("closed")
                         : fmt::format("open: {} holes filled", s.holesFilled));
  std::cout << fmt::format("output: {} convex pieces, {} vertices -> {}\n", result.pieces.size(),
                           s.totalVertices, args.output);
  const PieceVertexCounts counts = pieceVertexCounts(result.pieces);
  std::cout << fmt::format("vertices per convex: min {}, mean {:.1f}, max {}\n", counts.min,
                           counts.mean, counts.max);
  std::cout << fmt::format("epsilon: {:.4g} ({:.3f}% of diagonal), max pieces {}; stopped: {}\n",
                           s.epsilon, 100.0 * s.epsilon / diagonal, args.maxPieces, s.stopReason);
  std::cout << "distance original->approximation: "
            << describe(quality.originalToApproximation, diagonal) << "\n";
  std::cout << "distance approximation->original: "
            << describe(quality.approximationToOriginal, diagonal) << "\n";
  std::cout << fmt::format(
      "time: {:.3f} s ({} splits, {} re-cuts; step 1 bound {} vertices; hulls {} "
      "vertices before simplification)\n",
      s.seconds, s.splits, s.refinements, s.boundedVertices, s.hullVertices);
  if (quality.uncovered > 0) {
    std::cout << fmt::format("warning: {} of {} surface samples outside every piece\n",
                             quality.uncovered, quality.samples);
  }
  return 0;
}

VerbRunner setupDecompose(CLI::App& command) {
  auto args = std::make_shared<DecomposeArgs>();
  command.add_option("input", args->input, "Input mesh (STL, OBJ, PLY, OFF, DAE, WRL)")->required();
  command
      .add_option("-o,--output", args->output, "Output OBJ, one object piece_i per convex piece")
      ->required();
  command
      .add_option("--epsilon", args->epsilon,
                  "Largest distance from the pieces to the input: a distance, or E% of the "
                  "bounding-box diagonal")
      ->capture_default_str();
  command.add_option("--max-pieces", args->maxPieces, "Stop splitting at this many pieces")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}));
  command
      .add_option("--refine", args->refineRounds,
                  "After merging, up to N re-cuts of the worst piece (tighter, 1.3-1.6x the "
                  "time; docs/decomposition.md)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{0}, std::size_t{1000}));
  command
      .add_option("--samples", args->samples,
                  "Random surface samples for the reported distances (plus all vertices and "
                  "edge midpoints)")
      ->capture_default_str();
  command.add_flag("--json", args->json, "Print one JSON object instead of text");
  command.add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  return [args] { return runDecompose(*args); };
}

const VerbRegistration registration{
    "decompose", "Decompose a mesh into convex pieces whose union contains it (§4.4.2)",
    &setupDecompose};

}  // namespace
}  // namespace kaboum::cli
