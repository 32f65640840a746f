// Kinematics throughput: FK, closed-form IK (thesis A.3; thesis: ~1.5 µs per call), numeric IK on
// the 7-DOF WAM, and constraint sampling (Algorithm 3) in the two Figure 5.4 setups.
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>

#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/constraint_sampler.hpp"
#include "kaboum/kinematics/numeric_ik.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace {

using namespace kaboum;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::testing;

const std::string kKr5 = kaboum::testing::kr5Urdf();
const std::string kWam = kaboum::testing::wamUrdf();

struct Robot {
  explicit Robot(const std::string& path) : model(loadUrdf(path)), chain(model) {}
  RobotModel model;
  KinematicChain chain;
};

const Robot& kr5() {
  static const Robot robot(kKr5);
  return robot;
}
const Robot& wam() {
  static const Robot robot(kWam);
  return robot;
}

// `count` random configurations of `chain`, flattened.
std::vector<double> configurations(const KinematicChain& chain, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> q(static_cast<std::size_t>(count * chain.dof()));
  for (int i = 0; i < count; ++i) {
    randomConfiguration(chain, rng,
                        std::span(q).subspan(static_cast<std::size_t>(i * chain.dof()),
                                             static_cast<std::size_t>(chain.dof())));
  }
  return q;
}

void fk(benchmark::State& state, const Robot& robot) {
  const auto n = static_cast<std::size_t>(robot.chain.dof());
  const std::vector<double> q = configurations(robot.chain, 1024, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(robot.chain.toolPose(std::span(q).subspan(i * n, n)));
    i = (i + 1) % 1024;
  }
  state.SetItemsProcessed(state.iterations());
}
void BM_FkKr5(benchmark::State& state) {
  fk(state, kr5());
}
void BM_FkWam(benchmark::State& state) {
  fk(state, wam());
}
BENCHMARK(BM_FkKr5);
BENCHMARK(BM_FkWam);

void BM_FkJacobianWam(benchmark::State& state) {
  const auto& chain = wam().chain;
  const auto n = static_cast<std::size_t>(chain.dof());
  const std::vector<double> q = configurations(chain, 1024, 2);
  Jacobian jacobian(6, chain.dof());
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(chain.toolPoseAndJacobian(std::span(q).subspan(i * n, n), jacobian));
    i = (i + 1) % 1024;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FkJacobianWam);

std::vector<Pose> reachablePoses(const KinematicChain& chain, int count, std::uint64_t seed) {
  const std::vector<double> q = configurations(chain, count, seed);
  const auto n = static_cast<std::size_t>(chain.dof());
  std::vector<Pose> poses;
  for (int i = 0; i < count; ++i) {
    poses.push_back(chain.toolPose(std::span(q).subspan(static_cast<std::size_t>(i) * n, n)));
  }
  return poses;
}

// One family solve for one (k0, k1, k2) branch: the unit the thesis timed.
void BM_ClosedFormIkOneBranchKr5(benchmark::State& state) {
  const auto ik = ArmIk::fit(kr5().chain);
  const SixAxisArm& arm = ik->sixAxis();
  std::mt19937_64 rng(3);
  std::vector<Pose> flanges;
  for (int i = 0; i < 1024; ++i) {
    SixAxisArm::Angles theta{};
    for (auto& t : theta) t = (uniformUnit(rng) * 2 - 1) * std::numbers::pi;
    flanges.push_back(arm.flangePose(theta));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(arm.solve(flanges[i], 1, 1, 1));
    i = (i + 1) % flanges.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClosedFormIkOneBranchKr5);

// All eight branches mapped to URDF joints, limit-checked and verified by FK.
void BM_ClosedFormIkAllSolutionsKr5(benchmark::State& state) {
  const auto ik = ArmIk::fit(kr5().chain);
  const std::vector<Pose> targets = reachablePoses(kr5().chain, 1024, 4);
  ArmIk::Solutions solutions;
  std::size_t i = 0;
  double found = 0;
  for (auto _ : state) {
    ik->solve(targets[i], solutions);
    found += solutions.count;
    i = (i + 1) % targets.size();
  }
  state.counters["solutions_per_pose"] = found / static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClosedFormIkAllSolutionsKr5);

// Random reachable WAM poses from random starts (up to 50 restarts).
void BM_NumericIkWam(benchmark::State& state) {
  const std::vector<Pose> targets = reachablePoses(wam().chain, 256, 5);
  NumericIk ik(wam().chain, {.seed = 6});
  std::vector<double> q(7);
  std::size_t i = 0;
  double solved = 0, starts = 0;
  for (auto _ : state) {
    solved += ik.solve(targets[i], {}, q) ? 1 : 0;
    starts += ik.startsUsed();
    i = (i + 1) % targets.size();
  }
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["success_rate"] = solved / iterations;
  state.counters["starts_per_solve"] = starts / iterations;
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NumericIkWam)->Unit(benchmark::kMicrosecond);

// The Figure 5.4 setups on the KR5 (base_link at the origin, tool z along the roll axis).
struct Figure54 {
  Pose base = Pose::Identity();
  Pose tool = Pose(Eigen::Translation3d(0.1, 0, 0)) *
              Pose(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()));
  ConstraintProblem problem;
  explicit Figure54(bool cylinder) {
    std::vector<Pose> poses(kr5().model.links().size());
    kr5().model.linkPoses(std::vector<double>(6, 0.0), poses);
    base = poses[static_cast<std::size_t>(*kr5().model.findLink("base_link"))].inverse();
    problem.addRobot(kr5().chain, base);
    using Shape = PrimitiveShape;
    if (!cylinder) {
      const auto plane = problem.attachToTool(0, tool, Shape::makePlane({0, 0, 0}, {0, 0, 1}));
      const auto center = problem.attachToTool(0, tool, Shape::makePoint({0, 0, 0}));
      const auto table =
          problem.attachToObject(Pose::Identity(), Shape::makePlane({0, 0, 0}, {0, 0, 1}));
      problem.addConstraint(ConstraintType::Parallel, plane, table);
      problem.addConstraint(ConstraintType::Distance, center, table, 0.15);
      return;
    }
    const auto toolZ = problem.attachToTool(0, tool, Shape::makeLine({0, 0, 0}, {0, 0, 1}));
    const auto toolX = problem.attachToTool(0, tool, Shape::makeLine({0, 0, 0}, {1, 0, 0}));
    const auto center = problem.attachToTool(0, tool, Shape::makePoint({0, 0, 0}));
    const auto axis =
        problem.attachToObject(Pose::Identity(), Shape::makeLine({0.4, 0, 0}, {0, 0, 1}));
    const auto top =
        problem.attachToObject(Pose::Identity(), Shape::makePlane({0.4, 0, 0.2}, {0, 0, 1}));
    problem.addConstraint(ConstraintType::Parallel, toolZ, axis);
    problem.addConstraint(ConstraintType::Distance, center, axis, 0.04);
    problem.addConstraint(ConstraintType::Coincident, toolX, top);
  }
};

// One random start projected by Algorithm 3 (maxAttempts = 1): rate of successful projections.
void constraintSampling(benchmark::State& state, bool cylinder) {
  const Figure54 setup(cylinder);
  ConstraintSampler sampler(setup.problem, {.maxAttempts = 1, .seed = 7});
  std::vector<double> q(6);
  double successes = 0, iterations = 0;
  for (auto _ : state) {
    successes += sampler.sample(q) ? 1 : 0;
    iterations += sampler.lastIterations();
  }
  const auto calls = static_cast<double>(state.iterations());
  state.counters["success_rate"] = successes / calls;
  state.counters["gauss_newton_steps"] = iterations / calls;
  state.counters["samples_per_second"] = benchmark::Counter(successes, benchmark::Counter::kIsRate);
}
void BM_ConstraintSamplingTable(benchmark::State& state) {
  constraintSampling(state, false);
}
void BM_ConstraintSamplingCylinderRim(benchmark::State& state) {
  constraintSampling(state, true);
}
BENCHMARK(BM_ConstraintSamplingTable)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ConstraintSamplingCylinderRim)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
