// Bounding convex decomposition time and Table 4.3's figures (pieces, vertices per piece,
// distances) for every KR5 link (dart-doc) and every Comau Smart SiX link of the Bimanual Assembly
// scenario
// (../shared, skipped when absent), per link and per whole robot on two threads.
// Run: build/release/bench/bench_decomposition --benchmark_repetitions=3
//          --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "kaboum/geometry/convex_decomposition.hpp"
#include "kaboum/io/mesh_io.hpp"

namespace {

namespace fs = std::filesystem;

struct Link {
  std::string robot, name;
  kaboum::TriangleMesh mesh;
};

const std::vector<Link>& links() {
  static const std::vector<Link> all = [] {
    std::vector<Link> result;
    const fs::path kr5 = "/usr/share/doc/dart/data/urdf/KR5/meshes";
    for (const char* name :
         {"base_link", "shoulder", "bicep", "elbow", "forearm", "wrist", "palm"}) {
      const fs::path path = kr5 / (std::string(name) + ".STL");
      if (fs::exists(path)) result.push_back({"KR5", name, kaboum::readMesh(path.string())});
    }
    const fs::path comau =
        fs::path(KABOUM_DATA_DIR) / "../../shared/scenarios/bimanual-assembly/robots";
    for (int i = 0; i <= 6; ++i) {
      const fs::path path = comau / ("link" + std::to_string(i) + ".wrl");
      if (fs::exists(path)) {
        result.push_back({"Comau", "link" + std::to_string(i), kaboum::readMesh(path.string())});
      }
    }
    return result;
  }();
  return all;
}

// One link: time per decomposition; counters give the result's Table 4.3 columns (distances in %
// of the diagonal, measured once outside the timed loop).
void BM_DecomposeLink(benchmark::State& state, const Link* link) {
  const kaboum::DecompositionOptions options;  // 3% of the diagonal, at most 11 pieces
  kaboum::Decomposition result;
  for (auto _ : state) {
    result = kaboum::decomposeBounding(link->mesh, options);
    benchmark::DoNotOptimize(result.pieces.data());
  }
  const kaboum::DecompositionQuality quality =
      kaboum::measureDecomposition(result.closedInput, result.pieces, 100000, 1);
  std::size_t minVertices = result.stats.totalVertices, maxVertices = 0;
  for (const auto& piece : result.pieces) {
    minVertices = std::min(minVertices, piece.vertices().size());
    maxVertices = std::max(maxVertices, piece.vertices().size());
  }
  const double percent = 100.0 / quality.diagonal;
  state.counters["input_vertices"] = static_cast<double>(result.stats.inputVertices);
  state.counters["pieces"] = static_cast<double>(result.pieces.size());
  state.counters["vertices"] = static_cast<double>(result.stats.totalVertices);
  state.counters["vertices_min"] = static_cast<double>(minVertices);
  state.counters["vertices_max"] = static_cast<double>(maxVertices);
  state.counters["vertices_mean"] =
      static_cast<double>(result.stats.totalVertices) / static_cast<double>(result.pieces.size());
  state.counters["estimated_error_pct"] = result.stats.estimatedError * percent;
  state.counters["orig_to_approx_max_pct"] = quality.originalToApproximation.max * percent;
  state.counters["orig_to_approx_mean_pct"] = quality.originalToApproximation.mean * percent;
  state.counters["approx_to_orig_max_pct"] = quality.approximationToOriginal.max * percent;
  state.counters["approx_to_orig_mean_pct"] = quality.approximationToOriginal.mean * percent;
  state.counters["uncovered"] = static_cast<double>(quality.uncovered);
}

// A whole robot: every link on two threads (decomposeBoundingEach), wall-clock time.
void BM_DecomposeRobot(benchmark::State& state, const std::string& robot) {
  std::vector<kaboum::TriangleMesh> meshes;
  for (const Link& link : links()) {
    if (link.robot == robot) meshes.push_back(link.mesh);
  }
  if (meshes.empty()) {
    state.SkipWithError("robot meshes not found");
    return;
  }
  std::size_t pieces = 0;
  for (auto _ : state) {
    const auto results = kaboum::decomposeBoundingEach(meshes, {}, 2);
    pieces = 0;
    for (const auto& r : results) pieces += r.pieces.size();
  }
  state.counters["links"] = static_cast<double>(meshes.size());
  state.counters["pieces"] = static_cast<double>(pieces);
}

const bool registered = [] {
  for (const Link& link : links()) {
    benchmark::RegisterBenchmark(("BM_DecomposeLink/" + link.robot + "/" + link.name).c_str(),
                                 BM_DecomposeLink, &link)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  for (const std::string robot : {"KR5", "Comau"}) {
    benchmark::RegisterBenchmark(("BM_DecomposeRobot/" + robot).c_str(), BM_DecomposeRobot, robot)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
