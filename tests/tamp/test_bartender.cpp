// The Bartender scenario with geometry (examples/bartender, thesis §6.2.1): a plan that branches on
// sensing whether a bottle is empty, the empty branch handing the bottle from one arm to the other
// through the shared middle of the table, every path certified and verified, the plan file read
// back and verified independently.
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string example(const std::string& file) {
  return exampleFile("bartender/" + file);
}

const World& bartender() {
  static const World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  return world;
}

// Solves examples/bartender's `problem` with search `mode` (paths verified if `verify`).
SolveResult solveBartender(const std::string& problem, const std::string& mode, bool verify,
                           std::unique_ptr<Solver>* solverOut = nullptr) {
  SolveOptions options;
  options.search.mode = mode;
  options.search.limits.seconds = 120;
  options.verify = verify;
  auto solver = std::make_unique<Solver>(
      bartender(), symbolic::loadContingent(example("domain.pddl"), example(problem)), options);
  SolveResult result = solver->solve();
  if (solverOut != nullptr) *solverOut = std::move(solver);
  return result;
}

}  // namespace

TEST(Bartender, OneBottleBranchesOnSensingAndHandsTheEmptyBottleOver) {
  std::unique_ptr<Solver> solver;
  const SolveResult result = solveBartender("problem-1.pddl", "astar", true, &solver);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(result.verification.collidingPaths, 0U);
  const symbolic::TreeMetrics metrics = symbolic::measure(result.plan);
  EXPECT_EQ(metrics.leaves, 2.0) << "one leaf per outcome of senseifempty";
  EXPECT_EQ(metrics.branches, 1.0);
  // The geometric actions of the plan, by procedure and robot: robot1 cannot reach the dishwasher.
  std::vector<std::string> geometric;
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) {
      geometric.push_back(action.procedure + "(" + action.arguments.front() + ")");
    }
  }
  std::sort(geometric.begin(), geometric.end());
  EXPECT_EQ(geometric,
            (std::vector<std::string>{"moveHome(robot1)", "pickUp(robot1)", "pickUp(robot2)",
                                      "putDown(robot1)", "putDown(robot2)"}));
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) {
      if (action.procedure == "putDown" && action.arguments.front() == "robot2") {
        EXPECT_EQ(action.arguments.back(), "dishwasher");
      }
    }
  }
  // The plan file reads back and passes the independent check.
  const nlohmann::json file = planFileJson(
      *solver, result, {example("domain.pddl"), example("problem-1.pddl"), example("scene.yaml")});
  const PlanCheck check = verifyPlanFile(
      bartender(), symbolic::loadContingent(example("domain.pddl"), example("problem-1.pddl")),
      file, "plan.json");
  EXPECT_TRUE(check.passed());
}

// Two bottles, four outcomes of sensing: every search mode finds a plan that the validator accepts
// branch by branch (paths are verified in the test above; here the search is what differs).
TEST(Bartender, TwoBottlesSolveWithEverySearchMode) {
  for (const std::string mode : {"gbfs", "astar", "bfs", "dfs"}) {
    const SolveResult result = solveBartender("problem-2.pddl", mode, false);
    ASSERT_EQ(result.status, PlannerStatus::Solved) << mode << ": " << result.message;
    EXPECT_TRUE(result.verification.symbolic.valid) << mode << ": " << result.message;
    EXPECT_EQ(symbolic::measure(result.plan).leaves, 4.0) << mode;
  }
}

TEST(Bartender, IterativeDeepeningFindsTheHandover) {
  const SolveResult result = solveBartender("problem-1.pddl", "ids", true);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(symbolic::measure(result.plan).actions, 6.0)
      << "sense, pick, place in the middle, retract, pick, place: the shortest handover";
}

}  // namespace kaboum::tamp
