// Symbolic planner benchmarks: Stacked n Objects per search mode (thesis Table 6.4) and the IPC
// classical instances of the shared folder's pddl/classical when present (coverage against Fast
// Downward's recorded figures, see docs/benchmarks.md, "Symbolic planning"). Counters: solved, plan
// length, expanded and generated states.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "kaboum/scenarios/stacked_objects.hpp"
#include "kaboum/symbolic/planner.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace {
using namespace kaboum::scenarios;
using namespace kaboum::testing;

using namespace kaboum::symbolic;

void report(benchmark::State& state, const PlanReport& result) {
  const bool solved = result.search.status == kaboum::PlannerStatus::Solved;
  state.counters["solved"] = solved ? 1 : 0;
  state.counters["plan_length"] = solved ? static_cast<double>(result.plan.size()) : -1;
  state.counters["expanded"] = static_cast<double>(result.search.statistics.expanded);
  state.counters["generated"] = static_cast<double>(result.search.statistics.generated);
}

// Args: n, mode index into searchModes(); gbfs with its defaults (lazy, FF alternated with the
// landmark count), astar with max (admissible).
void BM_StackedObjects(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  SearchOptions options;
  options.mode = searchModes()[static_cast<std::size_t>(state.range(1))];
  options.heuristic = options.mode == "astar" ? "max" : "ff";
  options.limits.seconds = 300;
  state.SetLabel(options.mode + " n=" + std::to_string(n));
  const Domain domain = parseDomain(stackedObjectsDomain(), "stacked-domain.pddl");
  const Problem problem = parseProblem(stackedObjectsProblem(n), "stacked.pddl", domain);
  PlanReport result;
  for (auto _ : state) result = plan(domain, problem, {}, options);
  report(state, result);
}

void stackedArguments(benchmark::internal::Benchmark* bench) {
  // mode indices: 0 dfs, 1 bfs, 2 ids, 3 gbfs, 4 astar
  for (const int n : {2, 3, 4, 5, 6, 7, 8}) bench->Args({n, 0})->Args({n, 1})->Args({n, 2});
  for (const int n : {4, 6, 7, 8}) bench->Args({n, 4});
  for (const int n : {10, 20, 30, 40}) bench->Args({n, 3});
}
BENCHMARK(BM_StackedObjects)->Apply(stackedArguments)->Unit(benchmark::kMillisecond);

// One benchmark per IPC instance: the default (LAMA-like) setting, 60 s.
void registerClassical() {
  const auto shared = kaboum::testing::sharedDir();
  if (!shared) return;
  const std::filesystem::path root = *shared / "pddl/classical";
  if (!std::filesystem::exists(root)) return;
  for (const std::string domainName : {"blocks", "gripper", "logistics00", "depot", "miconic"}) {
    const auto dir = root / domainName;
    std::vector<std::filesystem::path> problems;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().filename() != "domain.pddl") problems.push_back(entry.path());
    }
    std::sort(problems.begin(), problems.end());
    for (const auto& problem : problems) {
      const std::string name = "BM_Classical/" + domainName + "/" + problem.stem().string();
      benchmark::RegisterBenchmark(name.c_str(),
                                   [domainFile = (dir / "domain.pddl").string(),
                                    problemFile = problem.string()](benchmark::State& state) {
                                     SearchOptions options;
                                     options.limits.seconds = 60;
                                     PlanReport result;
                                     for (auto _ : state)
                                       result = planFiles(domainFile, problemFile, {}, options);
                                     report(state, result);
                                   })
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  registerClassical();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
