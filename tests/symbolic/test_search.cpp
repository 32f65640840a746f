// Search tests: every mode and heuristic finds plans our validator accepts; optimal modes agree;
// limits end the search cleanly; results are deterministic.
#include <gtest/gtest.h>

#include <atomic>
#include <random>

#include "kaboum/core/error.hpp"
#include "kaboum/scenarios/stacked_objects.hpp"
#include "kaboum/symbolic/heuristic.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::scenarios;
using namespace kaboum::testing;

namespace {

using testing::pddlPath;
using testing::planAndValidate;

SearchOptions options(const std::string& mode, const std::string& heuristic) {
  SearchOptions out;
  out.mode = mode;
  out.heuristic = heuristic;
  out.lazy = false;  // the single-heuristic eager search (the default is covered by test_landmarks)
  out.landmarks = false;
  out.limits.seconds = 60;
  return out;
}

TEST(Search, HeuristicSearchSolvesIpcInstancesWithValidPlans) {
  for (const testing::IpcInstance& instance : testing::smallIpcInstances()) {
    const Domain domain = loadDomain(pddlPath(instance.domain));
    const Problem problem = loadProblem(pddlPath(instance.problem), domain);
    for (const std::string heuristic : {"ff", "add"}) {
      for (const std::string mode : {"gbfs", "astar"}) {
        const PlanReport report = planAndValidate(domain, problem, options(mode, heuristic));
        EXPECT_EQ(report.search.status, PlannerStatus::Solved)
            << instance.problem << " " << mode << " " << heuristic;
      }
    }
    SearchOptions lazy = options("gbfs", "ff");
    lazy.lazy = true;
    EXPECT_EQ(planAndValidate(domain, problem, lazy).search.status, PlannerStatus::Solved);
  }
}

TEST(Search, OptimalModesAgreeOnPlanLength) {
  // Known optimal lengths: blocks 4-0 has 6 steps (Fast Downward A*+LM-cut, baseline CSV).
  const Domain domain = loadDomain(pddlPath("blocks/domain.pddl"));
  const Problem problem = loadProblem(pddlPath("blocks/probBLOCKS-4-0.pddl"), domain);
  for (const auto& [mode, heuristic] : std::vector<std::pair<std::string, std::string>>{
           {"bfs", "blind"}, {"ids", "blind"}, {"astar", "max"}, {"astar", "blind"}}) {
    const PlanReport report = planAndValidate(domain, problem, options(mode, heuristic));
    ASSERT_EQ(report.search.status, PlannerStatus::Solved) << mode;
    EXPECT_EQ(report.plan.size(), 6u) << mode << " " << heuristic;
  }
  const PlanReport dfs = planAndValidate(domain, problem, options("dfs", "blind"));
  EXPECT_EQ(dfs.search.status, PlannerStatus::Solved);
  EXPECT_GE(dfs.plan.size(), 6u);
}

// Property: BFS plans are never longer than any other mode's plans (IDS matches them), and every
// plan validates.
TEST(Search, BreadthFirstIsNeverBeatenOnStackedObjects) {
  const Domain domain = parseDomain(stackedObjectsDomain(), "stacked.pddl");
  for (int n = 2; n <= 5; ++n) {
    const Problem problem = parseProblem(stackedObjectsProblem(n), "stacked.pddl", domain);
    const PlanReport bfs = planAndValidate(domain, problem, options("bfs", "blind"));
    ASSERT_EQ(bfs.search.status, PlannerStatus::Solved);
    EXPECT_EQ(bfs.plan.size(), static_cast<std::size_t>(2 * n - 1));  // thesis Table 6.4
    for (const std::string mode : {"dfs", "ids", "gbfs", "astar"}) {
      const PlanReport other = planAndValidate(domain, problem, options(mode, "ff"));
      ASSERT_EQ(other.search.status, PlannerStatus::Solved) << mode;
      EXPECT_GE(other.plan.size(), bfs.plan.size()) << mode;
      if (mode == "ids") {
        EXPECT_EQ(other.plan.size(), bfs.plan.size());
      }
    }
  }
}

TEST(Search, HeuristicSearchScalesOnStackedObjects) {
  const Domain domain = parseDomain(stackedObjectsDomain(), "stacked.pddl");
  const Problem problem = parseProblem(stackedObjectsProblem(12), "stacked.pddl", domain);
  const PlanReport report = planAndValidate(domain, problem, options("gbfs", "ff"));
  EXPECT_EQ(report.search.status, PlannerStatus::Solved);
}

TEST(Search, RandomBlocksProblemsYieldValidPlans) {
  const Domain domain = loadDomain(pddlPath("blocks/domain.pddl"));
  std::mt19937 random(7);
  for (int trial = 0; trial < 10; ++trial) {
    const int n = 3 + trial % 5;
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), random);
    std::string objects;
    std::string init = "(handempty)";
    std::string goal;
    for (int i = 0; i < n; ++i) {
      objects += " b" + std::to_string(i);
      init += " (ontable b" + std::to_string(i) + ") (clear b" + std::to_string(i) + ")";
    }
    for (int i = 1; i < n; ++i) {
      goal += " (on b" + std::to_string(order[i]) + " b" + std::to_string(order[i - 1]) + ")";
    }
    const Problem problem =
        parseProblem("(define (problem r) (:domain blocks) (:objects" + objects + ") (:init " +
                         init + ") (:goal (and" + goal + ")))",
                     "random.pddl", domain);
    for (const std::string mode : {"gbfs", "astar", "bfs"}) {
      const PlanReport report = planAndValidate(domain, problem, options(mode, "add"));
      ASSERT_EQ(report.search.status, PlannerStatus::Solved) << mode;
      // From all blocks on the table, a tower needs a pick-up and a stack per block but one.
      const auto optimal = static_cast<std::size_t>(2 * (n - 1));
      if (mode == "bfs") {
        EXPECT_EQ(report.plan.size(), optimal);
      } else {
        EXPECT_GE(report.plan.size(), optimal) << mode;
      }
    }
  }
}

TEST(Search, ReportsUnsolvableAndLimits) {
  const Domain domain = parseDomain(stackedObjectsDomain(), "stacked.pddl");
  const Problem problem = parseProblem(stackedObjectsProblem(9), "stacked.pddl", domain);
  SearchOptions nodes = options("bfs", "blind");
  nodes.limits.expansions = 50;
  const PlanReport limited = plan(domain, problem, {}, nodes);
  EXPECT_EQ(limited.search.status, PlannerStatus::NodeLimit);
  EXPECT_EQ(limited.search.statistics.expanded, 50u);
  SearchOptions time = options("bfs", "blind");
  time.limits.seconds = 1e-6;
  EXPECT_EQ(plan(domain, problem, {}, time).search.status, PlannerStatus::TimeLimit);
  SearchOptions memory = options("bfs", "blind");
  memory.limits.memoryBytes = 64 * 1024;
  EXPECT_EQ(plan(domain, problem, {}, memory).search.status, PlannerStatus::MemoryLimit);
  const std::atomic<bool> cancel{true};
  SearchOptions cancelled = options("bfs", "blind");
  cancelled.limits.cancel = &cancel;
  EXPECT_EQ(plan(domain, problem, {}, cancelled).search.status, PlannerStatus::Cancelled);

  const Domain blocks = loadDomain(pddlPath("blocks/domain.pddl"));
  const Problem impossible = parseProblem(
      "(define (problem x) (:domain blocks) (:objects a b) (:init (handempty) (ontable a) "
      "(ontable b) (clear a) (clear b)) (:goal (and (on a b) (on b a))))",
      "x.pddl", blocks);
  for (const std::string& mode : searchModes()) {
    EXPECT_EQ(plan(blocks, impossible, {}, options(mode, "ff")).search.status,
              PlannerStatus::Unsolvable)
        << mode;
  }
}

TEST(Search, IsDeterministic) {
  const Domain domain = loadDomain(pddlPath("depot/domain.pddl"));
  const Problem problem = loadProblem(pddlPath("depot/p01.pddl"), domain);
  const PlanReport first = plan(domain, problem, {}, options("gbfs", "ff"));
  const PlanReport second = plan(domain, problem, {}, options("gbfs", "ff"));
  EXPECT_EQ(first.plan, second.plan);
  EXPECT_EQ(first.search.statistics.expanded, second.search.statistics.expanded);
}

TEST(Search, RejectsUnknownModeAndHeuristic) {
  const Domain domain = loadDomain(pddlPath("blocks/domain.pddl"));
  const Problem problem = loadProblem(pddlPath("blocks/probBLOCKS-4-0.pddl"), domain);
  EXPECT_THROW(plan(domain, problem, {}, options("beam", "ff")), InputError);
  EXPECT_THROW(plan(domain, problem, {}, options("gbfs", "lmcut")), InputError);
}

}  // namespace
}  // namespace kaboum::symbolic
