// `kaboum bound`: single-sided simplification with the bounding mesh algorithm (thesis §4.3).
#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/io/json_geometry.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "mesh_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::io;

namespace {

struct BoundArgs {
  std::string input, output;
  BoundSide side = BoundSide::Outer;
  std::size_t vertices = 0;
  double ratio = 0.0;
  std::string epsilon;
  std::string cost = "planes";
  std::string merge = "constant";
  std::size_t samples = 200000;
  bool polish = false;
  int relocations = 10;
  bool json = false;
  bool quiet = false;
};

int runBound(const BoundArgs& args) {
  if (args.vertices == 0 && args.ratio == 0.0 && args.epsilon.empty()) {
    throw InputError("bound: give a target with --vertices, --ratio or --epsilon");
  }
  const LoadedMesh loaded = loadOrientedMesh(args.input);
  const TriangleMesh& mesh = loaded.mesh;
  BoundingMeshOptions options;
  options.side = args.side;
  options.cost = args.cost == "triangles" ? ContractionCost::Triangles : ContractionCost::Planes;
  options.merge = args.merge == "sum"    ? QuadricMerge::Sum
                  : args.merge == "full" ? QuadricMerge::Full
                                         : QuadricMerge::Constant;
  options.polish = args.polish;
  options.polishRelocations = args.relocations;
  const double diagonal = loaded.diagonal;
  if (args.vertices > 0) options.targetVertices = args.vertices;
  if (args.ratio > 0.0) {
    options.targetVertices =
        static_cast<std::size_t>(std::ceil(args.ratio * static_cast<double>(mesh.vertices.size())));
  }
  // An --epsilon search simplifies several times (copying the options for each run); each run gets
  // its own numbered line.
  int run = 0;
  bool runFinished = true;
  if (!args.quiet) {
    const bool numbered = !args.epsilon.empty();
    options.progress = [numbered, &run, &runFinished](double fraction) {
      if (runFinished) {
        if (run > 0) std::cerr << "\n";
        ++run;
      }
      runFinished = fraction >= 1.0;
      const double percent = 100.0 * std::min(fraction, 1.0);
      std::cerr << (numbered ? fmt::format("\rbound run {}: {:3.0f}%", run, percent)
                             : fmt::format("\rbound: {:3.0f}%", percent))
                << std::flush;
    };
    options.polishProgress = [started = false](double fraction) mutable {
      std::cerr << (started ? "\r" : "\n") << fmt::format("polish: {:3.0f}%", 100.0 * fraction)
                << std::flush;
      started = true;
    };
  }

  BoundingMeshResult result;
  HausdorffReport hausdorff;
  try {
    if (args.epsilon.empty()) {
      result = simplifyBounding(mesh, options);
      hausdorff = measureHausdorff(mesh, result.mesh, args.samples, 1);
    } else {
      const double epsilon = parseEpsilon(args.epsilon, diagonal);
      result = simplifyBoundingWithin(mesh, options, epsilon, args.samples, hausdorff);
    }
  } catch (const InputError& e) {
    throw InputError(locate(args.input, e.what()));
  }
  if (!args.quiet) std::cerr << "\n";
  writeMesh(result.mesh, args.output);
  const BoundingMeshStats& s = result.stats;

  if (args.json) {
    nlohmann::json out = toJson(result);
    out.update({{"input", args.input},
                {"output", args.output},
                {"side", sideName(args.side)},
                {"input_triangles", mesh.triangles.size()},
                {"input_closed", loaded.closed},
                {"orientation_repaired", loaded.orientationRepaired},
                {"hausdorff", toJson(hausdorff)}});
    out["polish"]["enabled"] = args.polish;
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << fmt::format("input:  {} vertices, {} triangles ({}{})\n", s.inputVertices,
                           mesh.triangles.size(), loaded.closed ? "closed" : "open",
                           loaded.orientationRepaired ? ", orientation repaired" : "");
  std::cout << fmt::format("output: {} vertices, {} triangles, {} bound -> {}\n", s.outputVertices,
                           result.mesh.triangles.size(), sideName(args.side), args.output);
  std::cout << fmt::format("contractions: {} in {:.3f} s ({:.0f} contractions/s); stopped: {}\n",
                           s.contractions, s.seconds, contractionsPerSecond(s), s.stopReason);
  if (s.runs > 1) {
    std::cout << fmt::format("distance search: {} runs of the bounding mesh algorithm\n", s.runs);
  }
  if (args.polish) {
    std::cout << fmt::format("polish: {} vertex moves, {} edge flips, {} relocations in {:.3f} s\n",
                             s.polishMoves, s.polishFlips, s.polishRelocations, s.polishSeconds);
  }
  if (s.lockedVertices > 0) {
    std::cout << fmt::format("kept fixed: {} vertices on borders or non-manifold parts\n",
                             s.lockedVertices);
  }
  std::cout << fmt::format("quadric error: {:.4g} ({:.3f}% of diagonal)\n", s.quadricError,
                           100.0 * s.quadricError / diagonal);
  std::cout << "distance input->result: " << describe(hausdorff.originalToResult, diagonal) << "\n";
  std::cout << "distance result->input: " << describe(hausdorff.resultToOriginal, diagonal) << "\n";
  if (!loaded.closed) {
    std::cout << "note: the input is open; containment is only defined for closed meshes (its "
                 "borders were kept fixed)\n";
  }
  return 0;
}

VerbRunner setupBound(CLI::App& command) {
  auto args = std::make_shared<BoundArgs>();
  command.add_option("input", args->input, "Input mesh (STL, OBJ, PLY, OFF, DAE, WRL)")->required();
  command.add_option("-o,--output", args->output, "Output mesh (.obj, .stl, .ply, .off)")
      ->required();
  addSideFlags(command, args->side);
  auto* vertices = command.add_option("--vertices", args->vertices, "Stop at this many vertices")
                       ->check(CLI::PositiveNumber);
  auto* ratio = command.add_option("--ratio", args->ratio, "Stop at this fraction of the vertices")
                    ->check(CLI::Range(1e-9, 1.0));
  vertices->excludes(ratio);
  command.add_option("--epsilon", args->epsilon,
                     "Largest distance between input and result (measured both ways on dense "
                     "samples): a distance, or E% of the bounding-box diagonal");
  command.add_option("--cost", args->cost, "Contraction cost: planes (E_planes) or triangles")
      ->check(CLI::IsMember({"planes", "triangles"}));
  command.add_option("--merge", args->merge, "Quadric merge: sum, constant or full")
      ->check(CLI::IsMember({"sum", "constant", "full"}));
  command.add_option("--samples", args->samples,
                     "Random surface samples for the reported distances (plus all vertices and "
                     "edge midpoints)");
  command.add_flag("--polish", args->polish,
                   "Finish with vertex moves and edge flips that lower both distances, keeping the "
                   "side (slower: 7-62 ms per output vertex)");
  command
      .add_option("--relocations", args->relocations,
                  "With --polish: at most this many vertices moved from where the surfaces are "
                  "closest to where they are farthest apart (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command.add_flag("--json", args->json, "Print one JSON object instead of text");
  command.add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  return [args] { return runBound(*args); };
}

const VerbRegistration registration{
    "bound", "Simplify a mesh to an outer or inner bounding mesh (bounding mesh algorithm)",
    &setupBound};

}  // namespace
}  // namespace kaboum::cli
