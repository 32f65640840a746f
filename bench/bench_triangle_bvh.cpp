// Speed of the verifier's geometry on a ~10^5-triangle sphere: BVH build, closest-point and inside
// queries, triangle intersection queries and the self-intersection count.
#include <benchmark/benchmark.h>

#include <random>

#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/testing/test_shapes.hpp"

namespace {
using namespace kaboum::geometry;
using namespace kaboum::testing;

using kaboum::Vec3;
using kaboum::geometry::TriangleBvh;
using kaboum::geometry::TriangleMesh;

const TriangleMesh& sphere() {
  static const TriangleMesh mesh = kaboum::testing::makeIcosphere(6);  // 81,920 triangles
  return mesh;
}

// Points at most `offset` inside or outside the unit sphere (verifier samples are mostly close to
// the surface, 1e-3 of the radius; 0.2 shows far queries).
std::vector<Vec3> nearSurfaceQueries(double offset) {
  std::mt19937_64 engine(1);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> radius(1.0 - offset, 1.0 + offset);
  std::vector<Vec3> queries(4096);
  for (Vec3& q : queries) {
    q = Vec3(normal(engine), normal(engine), normal(engine)).normalized() * radius(engine);
  }
  return queries;
}

void BM_BvhBuild(benchmark::State& state) {
  for (auto _ : state) {
    TriangleBvh bvh(sphere());
    benchmark::DoNotOptimize(bvh);
  }
  state.counters["triangles"] = static_cast<double>(sphere().triangleCount());
}
BENCHMARK(BM_BvhBuild)->Unit(benchmark::kMillisecond);

// Argument: largest distance of the queries from the surface, in thousandths of the radius.
double queryOffset(const benchmark::State& state) {
  return 1e-3 * static_cast<double>(state.range(0));
}

void BM_BvhClosest(benchmark::State& state) {
  const TriangleBvh bvh(sphere());
  const std::vector<Vec3> queries = nearSurfaceQueries(queryOffset(state));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bvh.closest(queries[i++ % queries.size()]));
  }
}
BENCHMARK(BM_BvhClosest)->Arg(1)->Arg(200);

void BM_BvhContains(benchmark::State& state) {
  const TriangleBvh bvh(sphere());
  const std::vector<Vec3> queries = nearSurfaceQueries(queryOffset(state));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bvh.contains(queries[i++ % queries.size()]));
  }
}
BENCHMARK(BM_BvhContains)->Arg(1)->Arg(200);

void BM_BvhIntersectsTriangle(benchmark::State& state) {
  const TriangleBvh bvh(sphere());
  const std::vector<Vec3> queries = nearSurfaceQueries(0.2);
  std::size_t i = 0;
  for (auto _ : state) {
    const Vec3& q = queries[i++ % queries.size()];
    benchmark::DoNotOptimize(
        bvh.intersectsTriangle(q, q + Vec3(0.01, 0, 0), q + Vec3(0, 0.01, 0.01)));
  }
}
BENCHMARK(BM_BvhIntersectsTriangle);

void BM_CountSelfIntersections(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(kaboum::geometry::countSelfIntersections(sphere()));
}
BENCHMARK(BM_CountSelfIntersections)->Unit(benchmark::kMillisecond);

void BM_VerifyOuterContainment(benchmark::State& state) {
  const TriangleMesh larger = kaboum::testing::transformMesh(sphere(), 1.01, Vec3::Zero());
  for (auto _ : state) {
    benchmark::DoNotOptimize(kaboum::geometry::verifyContainment(
        sphere(), larger, kaboum::geometry::BoundSide::Outer, 100000, 1));
  }
}
BENCHMARK(BM_VerifyOuterContainment)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
