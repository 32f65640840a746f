// Speed of the convex narrow phase on the issue-3 workload (random polytope pairs, ~40%
// overlapping): GJK boolean and distance per vertex count, cold and warm-started along a motion.
// `kaboum-compare collision` runs the same workload against FCL, Bullet and libccd side by side.
#include <benchmark/benchmark.h>

#include "kaboum/collision/convex_polytope.hpp"
#include "kaboum/collision/gjk.hpp"
#include "kaboum/testing/polytope_pairs.hpp"

namespace {
using namespace kaboum::collision;
using namespace kaboum::testing;

using kaboum::Vec3;
using kaboum::collision::ConvexPolytope;
using kaboum::collision::TransformedSupport;
using kaboum::testing::PolytopePair;

struct Workload {
  std::vector<PolytopePair> pairs;
  std::vector<ConvexPolytope> a, b;

  explicit Workload(int vertexCount)
      : pairs(kaboum::testing::randomPolytopePairs(1024, vertexCount, 1)) {
    for (const PolytopePair& pair : pairs) {
      a.emplace_back(pair.localA);
      b.emplace_back(pair.localB);
    }
  }
  TransformedSupport placedA(std::size_t i) const { return {a[i], pairs[i].poseA}; }
  TransformedSupport placedB(std::size_t i) const { return {b[i], pairs[i].poseB}; }
};

void BM_Intersects(benchmark::State& state) {
  const Workload workload(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % workload.pairs.size();
    benchmark::DoNotOptimize(
        kaboum::collision::intersects(workload.placedA(k), workload.placedB(k)));
  }
}
BENCHMARK(BM_Intersects)->Arg(8)->Arg(16)->Arg(32)->Arg(64);

void BM_Distance(benchmark::State& state) {
  const Workload workload(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % workload.pairs.size();
    benchmark::DoNotOptimize(kaboum::collision::distance(workload.placedA(k), workload.placedB(k)));
  }
}
BENCHMARK(BM_Distance)->Arg(8)->Arg(16)->Arg(32)->Arg(64);

// One pair along a slow motion (B approaching, passing through and leaving A), one cache per
// query kind: what a motion check sees from step to step.
void BM_IntersectsWarmAlongMotion(benchmark::State& state) {
  const Workload workload(static_cast<int>(state.range(0)));
  const TransformedSupport a(workload.a[0], Eigen::Isometry3d::Identity());
  std::vector<Eigen::Isometry3d> poses;
  for (int step = 0; step < 1000; ++step) {
    Eigen::Isometry3d pose(Eigen::AngleAxisd(0.003 * step, Vec3(1, 2, 3).normalized()));
    pose.translation() = Vec3(3.0 - 0.006 * step, 0.2, 0.1);
    poses.push_back(pose);
  }
  kaboum::collision::GjkCache<TransformedSupport, TransformedSupport> cache;
  std::size_t i = 0;
  for (auto _ : state) {
    const TransformedSupport b(workload.b[0], poses[i++ % poses.size()]);
    benchmark::DoNotOptimize(kaboum::collision::intersects(a, b, 0.0, &cache));
  }
}
BENCHMARK(BM_IntersectsWarmAlongMotion)->Arg(8)->Arg(64);

}  // namespace

BENCHMARK_MAIN();
