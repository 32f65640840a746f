// Speed of mesh reading, welding, analysis and orientation repair on inputs of 10^3 to 10^6
// vertices, made by subdividing the cow (each level splits every triangle into four).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <unordered_map>

#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum {

using namespace kaboum::geometry;
using namespace kaboum::io;
using namespace kaboum::testing;

namespace {

// One 1-to-4 midpoint subdivision; the midpoints are shared between neighbours.
TriangleMesh subdivide(const TriangleMesh& mesh) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
  const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    const auto [it, inserted] =
        midpoints.try_emplace(key, static_cast<std::uint32_t>(out.vertices.size()));
    if (inserted) out.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
    return it->second;
  };
  for (const Triangle& t : mesh.triangles) {
    const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                        ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

// The cow subdivided `levels` times: 2,903 / 11,609 / 46,433 / 185,729 / 742,913 vertices.
const TriangleMesh& cow(int levels) {
  static std::vector<TriangleMesh> cache{readMesh(kaboum::testing::dataFile("meshes/cow.obj"))};
  while (static_cast<int>(cache.size()) <= levels) cache.push_back(subdivide(cache.back()));
  return cache[static_cast<std::size_t>(levels)];
}

void reportVertices(benchmark::State& state, std::size_t vertices) {
  state.counters["vertices"] = static_cast<double>(vertices);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * vertices));
}

void BM_AnalyzeMesh(benchmark::State& state) {
  const TriangleMesh& mesh = cow(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(analyzeMesh(mesh));
  reportVertices(state, mesh.vertices.size());
}

void BM_WeldTriangleSoup(benchmark::State& state) {
  const TriangleMesh& mesh = cow(static_cast<int>(state.range(0)));
  TriangleMesh soup;
  for (const Triangle& t : mesh.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.vertices.size());
    for (const std::uint32_t v : t) soup.vertices.push_back(mesh.vertices[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  for (auto _ : state) {
    state.PauseTiming();
    TriangleMesh work = soup;
    state.ResumeTiming();
    weldVertices(work);
    benchmark::DoNotOptimize(work.vertices.data());
  }
  reportVertices(state, soup.vertices.size());
}

void BM_RepairOrientation(benchmark::State& state) {
  TriangleMesh damaged = cow(static_cast<int>(state.range(0)));
  std::mt19937 random(1);
  for (Triangle& t : damaged.triangles) {
    if (random() % 3 == 0) std::swap(t[1], t[2]);
  }
  for (auto _ : state) {
    state.PauseTiming();
    TriangleMesh work = damaged;
    state.ResumeTiming();
    benchmark::DoNotOptimize(repairOrientation(work));
  }
  reportVertices(state, damaged.vertices.size());
}

// Reads the level-3 cow (185,729 vertices) written in the format `extensions[range(0)]`.
void BM_ReadMesh(benchmark::State& state) {
  static const char* extensions[] = {".obj", ".ply", ".stl", ".off"};
  const std::string path = (std::filesystem::temp_directory_path() /
                            (std::string("kaboum-bench-cow") + extensions[state.range(0)]))
                               .string();
  const TriangleMesh& mesh = cow(3);
  writeMesh(mesh, path);
  state.SetLabel(extensions[state.range(0)]);
  for (auto _ : state) benchmark::DoNotOptimize(readMesh(path));
  reportVertices(state, mesh.vertices.size());
  std::filesystem::remove(path);
}

BENCHMARK(BM_AnalyzeMesh)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WeldTriangleSoup)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RepairOrientation)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadMesh)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kaboum

BENCHMARK_MAIN();
