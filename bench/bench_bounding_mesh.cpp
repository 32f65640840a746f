// Bounding mesh throughput and peak memory versus input size (the scaling table of
// docs/benchmarks.md). Inputs are real meshes, enlarged by Loop subdivision. Run:
// build/release/bench/bench_bounding_mesh
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>

#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/subdivision.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/test_shapes.hpp"

// GCC cannot see that the replaced operator new below pairs with the replaced delete.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

// Heap accounting: current and peak bytes live on the heap, for the memory-per-vertex counter.
namespace {
using namespace kaboum::geometry;
using namespace kaboum::io;
using namespace kaboum::testing;
std::atomic<std::size_t> liveBytes{0}, peakBytes{0};
void* track(void* p) {
  if (p == nullptr) throw std::bad_alloc();
  const std::size_t now = liveBytes += malloc_usable_size(p);
  std::size_t peak = peakBytes.load();
  while (now > peak && !peakBytes.compare_exchange_weak(peak, now)) {
  }
  return p;
}
}  // namespace
void* operator new(std::size_t size) {
  return track(std::malloc(size));
}
void* operator new[](std::size_t size) {
  return track(std::malloc(size));
}
void operator delete(void* p) noexcept {
  if (p != nullptr) liveBytes -= malloc_usable_size(p);
  std::free(p);
}
void operator delete[](void* p) noexcept {
  operator delete(p);
}
void operator delete(void* p, std::size_t) noexcept {
  operator delete(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  operator delete(p);
}

namespace {

std::string meshPath(const std::string& name) {
  const auto shared = kaboum::testing::sharedDir();
  if (shared && std::filesystem::exists(*shared / "meshes" / name)) {
    return (*shared / "meshes" / name).string();
  }
  return kaboum::testing::dataFile("meshes/" + name);
}

// Loop-subdivided copies of spot.obj: 2.9k, 11.7k, 46.8k, 187k and 749k vertices.
const kaboum::geometry::TriangleMesh& spot(int level) {
  static std::vector<kaboum::geometry::TriangleMesh> levels;
  if (levels.empty()) levels.push_back(kaboum::io::readMesh(meshPath("spot.obj")));
  while (static_cast<int>(levels.size()) <= level) {
    levels.push_back(kaboum::geometry::subdivideLoop(levels.back()));
  }
  return levels[static_cast<std::size_t>(level)];
}

void BoundOuterTenPercent(benchmark::State& state) {
  const kaboum::geometry::TriangleMesh& mesh = spot(static_cast<int>(state.range(0)));
  kaboum::geometry::BoundingMeshOptions options;
  options.targetVertices = mesh.vertices.size() / 10;
  std::size_t contractions = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const std::size_t before = liveBytes.load();
    peakBytes = before;
    const kaboum::geometry::BoundingMeshResult result =
        kaboum::geometry::simplifyBounding(mesh, options);
    state.counters["peak_bytes_per_input_vertex"] =
        static_cast<double>(peakBytes.load() - before) / static_cast<double>(mesh.vertices.size());
    contractions = result.stats.contractions;
    seconds = result.stats.seconds;
    benchmark::DoNotOptimize(result.mesh.triangles.data());
  }
  state.counters["input_vertices"] = static_cast<double>(mesh.vertices.size());
  state.counters["contractions_per_second"] = static_cast<double>(contractions) / seconds;
}
BENCHMARK(BoundOuterTenPercent)
    ->DenseRange(0, 4)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

// No pathological slow case: the same number of contractions (2,000, taken off the
// rim) next to two vertices of valence `range(0)` (makeDoubleCone).
void BoundNextToHighValence(benchmark::State& state) {
  const kaboum::geometry::TriangleMesh mesh =
      kaboum::testing::makeDoubleCone(static_cast<int>(state.range(0)));
  kaboum::geometry::BoundingMeshOptions options;
  options.targetVertices = mesh.vertices.size() - 2000;
  std::size_t contractions = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const std::size_t before = liveBytes.load();
    peakBytes = before;
    const kaboum::geometry::BoundingMeshResult result =
        kaboum::geometry::simplifyBounding(mesh, options);
    state.counters["peak_bytes_per_input_vertex"] =
        static_cast<double>(peakBytes.load() - before) / static_cast<double>(mesh.vertices.size());
    contractions = result.stats.contractions;
    seconds = result.stats.seconds;
    benchmark::DoNotOptimize(result.mesh.triangles.data());
  }
  state.counters["apex_valence"] = static_cast<double>(state.range(0));
  state.counters["contractions_per_second"] = static_cast<double>(contractions) / seconds;
}
BENCHMARK(BoundNextToHighValence)
    ->Arg(2500)
    ->Arg(5000)
    ->Arg(10000)
    ->Arg(20000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
