// Contingent planning benchmarks: Force Sensing for n containers (thesis Table 3.1; the plan has
// 2^n branches; knowledge states chosen automatically, factored here) and the small public
// instances copied to data/pddl/contingent. Counters: solved, tree actions, leaves, depth, expanded
// knowledge states, initial worlds. Grounding and world enumeration are part of each iteration. The
// per-domain coverage table on the full public sets comes from bench/contingent_benchmarks.sh
// (docs/contingent.md).
#include <benchmark/benchmark.h>

#include "kaboum/scenarios/force_sensing.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace {
using namespace kaboum::scenarios;
using namespace kaboum::testing;

using namespace kaboum::symbolic;

void solve(benchmark::State& state, const ContingentProblem& contingent) {
  ContingentOptions options;
  options.limits.seconds = 300;
  ContingentResult result;
  double worlds = 0;
  for (auto _ : state) {
    KnowledgeTask task(contingent, ProcedureRegistry{}, std::size_t{1} << 22);
    result = solveContingent(task, options);
    worlds = task.possibleWorlds(task.initialBelief());
  }
  const TreeMetrics metrics = measure(result.plan);
  state.counters["solved"] = result.status == kaboum::PlannerStatus::Solved ? 1 : 0;
  state.counters["actions"] = metrics.actions;
  state.counters["leaves"] = metrics.leaves;
  state.counters["depth"] = static_cast<double>(metrics.depth);
  state.counters["expanded"] = static_cast<double>(result.statistics.expanded);
  state.counters["worlds"] = worlds;
}

void BM_ForceSensing(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  state.SetLabel("n=" + std::to_string(n));
  solve(state, parseContingent(forceSensingDomain(), "force-sensing-domain.pddl",
                               forceSensingProblem(n), "force-sensing.pddl"));
}
BENCHMARK(BM_ForceSensing)
    ->DenseRange(2, 16, 2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

void BM_PublicInstance(benchmark::State& state) {
  static const char* const kInstances[][3] = {
      {"medpks", "d.pddl", "p.pddl"},      {"ebtcs", "d.pddl", "p.pddl"},
      {"unix", "d.pddl", "p.pddl"},        {"doors", "d.pddl", "p.pddl"},
      {"colorballs", "d.pddl", "p.pddl"},  {"wumpus", "d.pddl", "p.pddl"},
      {"blocks", "domain.pddl", "p3.pddl"}};
  const auto& instance = kInstances[state.range(0)];
  state.SetLabel(instance[0]);
  const std::string dir =
      kaboum::testing::dataFile(std::string("pddl/contingent/") + instance[0]) + "/";
  solve(state, loadContingent(dir + instance[1], dir + instance[2]));
}
BENCHMARK(BM_PublicInstance)->DenseRange(0, 6)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
