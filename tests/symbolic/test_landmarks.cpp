// Landmark and heuristic tests: the landmarks and orderings of Stacked 3 Objects worked out by
// hand, heuristic values on its initial state computed by hand, and LAMA-style search (landmark
// count alternated with FF, eager and lazy) finding valid plans on the copied IPC problems.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "kaboum/scenarios/stacked_objects.hpp"
#include "kaboum/symbolic/landmarks.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::scenarios;
using namespace kaboum::testing;

namespace {

using testing::pddlPath;
using testing::planAndValidate;

// "(ishighest o1)" for atoms, "(getonebelow o2)=stack1" for object-fluent values.
std::string factName(const GroundTask& task, int fact) {
  if (fact < static_cast<int>(task.atomNames.size())) return task.atomNames[fact];
  for (std::size_t f = 0; f < task.valueFacts.size(); ++f) {
    for (const auto& [value, id] : task.valueFacts[f]) {
      if (id == fact) return task.fluentNames[f] + "=" + task.objectNames[value];
    }
  }
  return "?";
}

struct Stacked3 {
  Domain domain = parseDomain(stackedObjectsDomain(), "stacked.pddl");
  Problem problem = parseProblem(stackedObjectsProblem(3), "stacked.pddl", domain);
  GroundTask task = ground(domain, problem);
};

// Stacked 3: stack1 holds o2 under o3, stack2 holds o1, stack3 is empty; the goal is the tower
// o3 on o2 on o1 on stack1. Backchaining by hand: (gob o1)=stack1 needs (ishighest o1) and
// (ishighest stack1); the latter's only first achievers move o2 away from stack1, needing
// (ishighest o2) and (gob o2)=stack1; (ishighest o2) needs o3 moved: (ishighest o3) and the goal
// (gob o3)=o2, which holds initially. (gob o2)=o1 needs (ishighest o2) and (ishighest o1).
TEST(Landmarks, StackedThreeHasExactlyTheHandDerivedLandmarksAndOrderings) {
  const Stacked3 stacked;
  const RelaxedTask relaxed(stacked.task);
  const LandmarkGraph graph = findLandmarks(relaxed);
  std::map<std::string, std::set<std::string>> orderings;  // landmark -> landmarks before it
  std::set<std::string> goals;
  for (std::size_t l = 0; l < graph.facts.size(); ++l) {
    const std::string name = factName(stacked.task, graph.facts[l]);
    auto& before = orderings[name];
    for (const int b : graph.before[l]) before.insert(factName(stacked.task, graph.facts[b]));
    if (graph.goal[l]) goals.insert(name);
  }
  const std::map<std::string, std::set<std::string>> expected = {
      {"(getonebelow o1)=stack1", {"(ishighest o1)", "(ishighest stack1)"}},
      {"(getonebelow o2)=o1", {"(ishighest o1)", "(ishighest o2)"}},
      {"(getonebelow o3)=o2", {}},
      {"(ishighest stack1)", {"(ishighest o2)", "(getonebelow o2)=stack1"}},
      {"(ishighest o2)", {"(ishighest o3)", "(getonebelow o3)=o2"}},
      {"(ishighest o1)", {}},
      {"(ishighest o3)", {}},
      {"(getonebelow o2)=stack1", {}}};
  EXPECT_EQ(orderings, expected);
  EXPECT_EQ(goals, (std::set<std::string>{"(getonebelow o1)=stack1", "(getonebelow o2)=o1",
                                          "(getonebelow o3)=o2"}));
}

// By hand on the initial state of Stacked 3 (unit costs): (ishighest o2) costs 1 (move o3),
// (ishighest stack1) 2 (then move o2), (gob o1)=stack1 3 and (gob o2)=o1 2. h_max = 3,
// h_add = 3 + 2 = 5. Landmark count: the two false goals, (ishighest stack1), (ishighest o2).
TEST(Landmarks, HeuristicValuesOnStackedThreeMatchHandComputation) {
  const Stacked3 stacked;
  AttachmentRuntime attachments(stacked.domain, stacked.problem, {});
  StateEvaluator evaluator(stacked.task, attachments);
  std::vector<std::uint64_t> initial(evaluator.layout().words());
  evaluator.initialState(initial);
  const StateView state = evaluator.view(initial);
  const auto value = [&](const std::string& name) {
    return makeHeuristic(name, stacked.task)->evaluate(state, nullptr);
  };
  EXPECT_EQ(value("max"), 3);
  EXPECT_EQ(value("add"), 5);
  EXPECT_EQ(value("lmcount"), 4);
  EXPECT_EQ(value("blind"), 0);
  // FF: move o3 away, move o2 away (possibly onto o1, which already achieves (gob o2)=o1),
  // move o1 onto stack1, move o2 onto o1: 3 or 4 distinct operators, between h_max and h_add.
  EXPECT_GE(value("ff"), 3);
  EXPECT_LE(value("ff"), 4);

  // The landmark heuristic prefers the only moves that achieve (ishighest o2): o3 off o2.
  std::vector<int> preferred;
  makeHeuristic("lmcount", stacked.task)->evaluate(state, &preferred);
  ASSERT_FALSE(preferred.empty());
  for (const int op : preferred) {
    EXPECT_EQ(stacked.task.operators[op].name.rfind("move o3 ", 0), 0u)
        << stacked.task.operators[op].name;
  }
}

TEST(Landmarks, CountIsZeroExactlyWhenTheGoalLandmarksHold) {
  const Stacked3 stacked;
  const RelaxedTask relaxed(stacked.task);
  AttachmentRuntime attachments(stacked.domain, stacked.problem, {});
  StateEvaluator evaluator(stacked.task, attachments);
  std::vector<std::uint64_t> state(evaluator.layout().words());
  evaluator.initialState(state);
  LandmarkCountHeuristic heuristic(stacked.task);
  // Replay the optimal plan: the count never increases and reaches 0 at the goal.
  SearchOptions bfs;
  bfs.mode = "bfs";
  const PlanReport report = plan(stacked.domain, stacked.problem, {}, bfs);
  ASSERT_EQ(report.search.status, PlannerStatus::Solved);
  int previous = heuristic.evaluate(evaluator.view(state), nullptr);
  std::vector<std::uint64_t> next(state.size());
  for (const int op : report.search.plan) {
    ASSERT_TRUE(evaluator.apply(stacked.task.operators[op], evaluator.view(state), next));
    state.swap(next);
    const int h = heuristic.evaluate(evaluator.view(state), nullptr);
    EXPECT_LE(h, previous);
    previous = h;
  }
  EXPECT_TRUE(evaluator.isGoal(evaluator.view(state)));
  EXPECT_EQ(previous, 0);
}

TEST(Landmarks, LamaStyleSearchSolvesIpcInstancesWithValidPlans) {
  for (const testing::IpcInstance& instance : testing::smallIpcInstances()) {
    const Domain domain = loadDomain(pddlPath(instance.domain));
    const Problem problem = loadProblem(pddlPath(instance.problem), domain);
    for (const bool lazy : {false, true}) {
      SearchOptions options;
      options.mode = "gbfs";
      options.landmarks = true;
      options.lazy = lazy;
      options.limits.seconds = 60;
      const PlanReport report = planAndValidate(domain, problem, options);
      EXPECT_EQ(report.search.status, PlannerStatus::Solved) << instance.problem << " " << lazy;
    }
    SearchOptions alone;
    alone.heuristic = "lmcount";
    alone.limits.seconds = 60;
    EXPECT_EQ(planAndValidate(domain, problem, alone).search.status, PlannerStatus::Solved)
        << instance.problem << " lmcount";
  }
}

TEST(Landmarks, LamaStyleSearchIsDeterministic) {
  const Domain domain = loadDomain(pddlPath("depot/domain.pddl"));
  const Problem problem = loadProblem(pddlPath("depot/p01.pddl"), domain);
  SearchOptions options;
  options.landmarks = true;
  options.lazy = true;
  const PlanReport first = plan(domain, problem, {}, options);
  const PlanReport second = plan(domain, problem, {}, options);
  EXPECT_EQ(first.plan, second.plan);
  EXPECT_EQ(first.search.statistics.expanded, second.search.statistics.expanded);
}

}  // namespace
}  // namespace kaboum::symbolic
