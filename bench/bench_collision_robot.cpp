// The KR5's robot-level predicates beyond the scene check: self-collision, swept motions, swept
// self-collision and isInside, among 50 random convex obstacles. The full-robot scene check is
// benchmarked once, side by side with FCL: `kaboum-compare collision --section robot`
// (bench/compare/bench_full_robot.cpp).
#include <benchmark/benchmark.h>

#include <random>

#include "kaboum/collision/predicates.hpp"
#include "kaboum/collision/swept.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/testing/robot_collision_models.hpp"
#include "kaboum/testing/scene_generator.hpp"

namespace {

using namespace kaboum;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;
using namespace kaboum::collision;

const std::string kKr5 = kaboum::testing::kr5Urdf();

struct Kr5World {
  RobotCollisionModel robot = kaboum::testing::robotCollisionModel(kKr5);
  CollisionScene scene =
      randomObstacleScene(Aabb{Vec3(-0.8, -1.2, -0.8), Vec3(0.8, 0.4, 0.8)}, 50, 12, 0.04, 1);
  std::vector<std::vector<double>> configurations;
  std::vector<std::vector<Pose>> poses;

  Kr5World() {
    std::mt19937_64 rng(1);
    for (int i = 0; i < 1024; ++i) {
      const std::vector<double> q = randomConfiguration(robot.model(), rng);
      std::vector<Pose> p(robot.model().links().size());
      robot.model().linkPoses(q, p);
      configurations.push_back(q);
      poses.push_back(p);
    }
    std::vector<Pose> home(robot.model().links().size());
    robot.model().linkPoses(std::vector<double>(6, 0.0), home);
    robot.allowPairsCollidingAt(home);
  }
};

const Kr5World& world() {
  static const Kr5World instance;
  return instance;
}

void BM_Kr5SelfCheck(benchmark::State& state) {
  const Kr5World& w = world();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(w.robot.selfCollides(w.poses[i++ % w.poses.size()], {}, 0.0));
}
BENCHMARK(BM_Kr5SelfCheck);

// Calls check(qa, qb) once per benchmark iteration on the straight motion between consecutive
// random configurations.
template <class Check>
void alongMotions(benchmark::State& state, const Kr5World& w, Check&& check) {
  const std::size_t count = w.configurations.size();
  std::size_t i = 0;
  for (auto _ : state) {
    check(w.configurations[i % count], w.configurations[(i + 1) % count]);
    ++i;
  }
}

// Swept motions against the scene at ε = range(0) µm.
void BM_Kr5SweptMotion(benchmark::State& state) {
  const Kr5World& w = world();
  RobotSweep sweep(w.robot);
  const double epsilon = static_cast<double>(state.range(0)) * 1e-6;
  std::size_t samples = 0;
  alongMotions(state, w, [&](const std::vector<double>& qa, const std::vector<double>& qb) {
    benchmark::DoNotOptimize(sweep.firstSceneCollision(qa, qb, {}, w.scene, {}, 0.0, epsilon));
    samples += sweep.sampleCount();
  });
  state.counters["fk_samples"] =
      static_cast<double>(samples) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_Kr5SweptMotion)->Arg(1000)->Arg(4000);

// Swept self-collision (RobotSweep::selfCollides) along the same motions, ε in µm.
void BM_Kr5SweptSelfCollision(benchmark::State& state) {
  const Kr5World& w = world();
  RobotSweep sweep(w.robot);
  const double epsilon = static_cast<double>(state.range(0)) * 1e-6;
  std::size_t hits = 0;
  alongMotions(state, w, [&](const std::vector<double>& qa, const std::vector<double>& qb) {
    hits += sweep.selfCollides(qa, qb, {}, 0.0, epsilon) ? 1 : 0;
  });
  state.counters["colliding"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_Kr5SweptSelfCollision)->Arg(1000)->Arg(4000);

void BM_IsInside(benchmark::State& state) {
  const Kr5World& w = world();
  const ConvexContainer container(
      std::vector<Vec3>{Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(1, 1, -1),
                        Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(-1, 1, 1), Vec3(1, 1, 1)});
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t o = i++ % w.scene.size();
    benchmark::DoNotOptimize(
        isInside(w.scene.body(o), w.scene.pose(o, {}), container, Pose::Identity()));
  }
}
BENCHMARK(BM_IsInside);

}  // namespace

BENCHMARK_MAIN();
