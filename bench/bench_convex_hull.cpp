// Convex hulls side by side: qhull (convexHull, the hull every kept piece is built from) against
// kaboum's quickHull (which ranks a decomposition's candidate cuts), on the same point sets: every
// KR5 link's vertices (dart-doc), each link's part below a cut through its middle (the crossings of
// its edges with the cut are coplanar, as in a decomposition's cells), and points on a sphere
// (all of them hull vertices).
// Run: build/release/bench/bench_convex_hull --benchmark_repetitions=3
//          --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "kaboum/geometry/convex_hull.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/quick_hull.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace {
using namespace kaboum::geometry;
using namespace kaboum::io;
using namespace kaboum::testing;

using kaboum::Vec3;

struct PointSet {
  std::string name;
  std::vector<Vec3> points;
  double tolerance;  // of quickHull: 1e-8 of the diagonal, as in the decomposition
};

PointSet pointSet(std::string name, std::vector<Vec3> points) {
  const double diagonal =
      kaboum::geometry::boundingBoxDiagonal(kaboum::geometry::TriangleMesh{points, {}});
  return {std::move(name), std::move(points), 1e-8 * diagonal};
}

const std::vector<PointSet>& pointSets() {
  static const std::vector<PointSet> sets = [] {
    std::vector<PointSet> result;
    const std::filesystem::path kr5 = kaboum::testing::kr5MeshDir();
    for (const char* name :
         {"base_link", "shoulder", "bicep", "elbow", "forearm", "wrist", "palm"}) {
      const std::filesystem::path path = kr5 / (std::string(name) + ".STL");
      if (!std::filesystem::exists(path)) continue;
      const kaboum::geometry::TriangleMesh mesh = kaboum::io::readMesh(path.string());
      const kaboum::geometry::MeshAnalysis analysis = kaboum::geometry::analyzeMesh(mesh);
      result.push_back(pointSet(std::string("KR5_") + name, mesh.vertices));
      result.push_back(pointSet(std::string("KR5_") + name + "_below_cut",
                                kaboum::testing::pointsBelowCut(
                                    mesh, 0.5 * (analysis.boxMin.z() + analysis.boxMax.z()))));
    }
    std::mt19937 rng(1);
    std::normal_distribution<double> gauss;
    for (const int n : {64, 400}) {
      std::vector<Vec3> sphere;
      for (int i = 0; i < n; ++i)
        sphere.push_back(Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized());
      result.push_back(pointSet("sphere_" + std::to_string(n), sphere));
    }
    return result;
  }();
  return sets;
}

void BM_Qhull(benchmark::State& state, const PointSet* set) {
  for (auto _ : state) {
    const kaboum::geometry::ConvexHull hull = kaboum::geometry::convexHull(set->points);
    benchmark::DoNotOptimize(hull.mesh.triangles.data());
  }
  state.counters["points"] = static_cast<double>(set->points.size());
}

void BM_QuickHull(benchmark::State& state, const PointSet* set) {
  for (auto _ : state) {
    const std::optional<kaboum::geometry::TriangleMesh> hull =
        kaboum::geometry::quickHull(set->points, set->tolerance);
    if (!hull) {
      state.SkipWithError("no hull");
      break;
    }
    benchmark::DoNotOptimize(hull->triangles.data());
  }
  state.counters["points"] = static_cast<double>(set->points.size());
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (const PointSet& set : pointSets()) {
    benchmark::RegisterBenchmark(("BM_Qhull/" + set.name).c_str(), BM_Qhull, &set)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("BM_QuickHull/" + set.name).c_str(), BM_QuickHull, &set)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
