// Seed 004's Tables scenario (examples/tables, §V, Table I): a mobile manipulator among three
// tables whose places hold one item each. A goal that names an occupied place makes the planner
// move the occupant first; that comes from the geometry (putDown finds no room there), not from the
// domain. One problem of each class is solved and its plan verified, by the library and by
// `kaboum solve` and `kaboum verify-plan`.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"
#include "plan_actions.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string example(const std::string& file) {
  return exampleFile("tables/" + file);
}

const World& tables() {
  static const World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  return world;
}

// Solves examples/tables/`problem`.pddl with A* (the search of the example's figures), checks the
// solver's verification and the plan file's independent one, and returns the plan's actions.
std::vector<std::string> solveAndVerify(const std::string& problem) {
  const std::string problemFile = example(problem + ".pddl");
  SolveOptions options;
  options.search.mode = "astar";
  Solver solver(tables(), symbolic::loadContingent(example("domain.pddl"), problemFile), options);
  const SolveResult result = solver.solve();
  EXPECT_EQ(result.status, PlannerStatus::Solved) << problem << ": " << result.message;
  if (result.status != PlannerStatus::Solved) return {};
  EXPECT_TRUE(result.verification.passed()) << problem << ": " << result.message;
  EXPECT_EQ(result.verification.collidingPaths, 0U) << problem;
  const nlohmann::json file =
      planFileJson(solver, result, {example("domain.pddl"), problemFile, example("scene.yaml")});
  const PlanCheck check = verifyPlanFile(
      tables(), symbolic::loadContingent(example("domain.pddl"), problemFile), file, "plan.json");
  EXPECT_TRUE(check.passed()) << problem << ": " << check.verification.symbolic.message
                              << (check.failures.empty() ? "" : check.failures.front());
  return planActions(file);
}

// Where `action` is in `plan`; plan.size() when it is not there.
std::size_t stepOf(const std::vector<std::string>& plan, const std::string& action) {
  return static_cast<std::size_t>(std::find(plan.begin(), plan.end(), action) - plan.begin());
}

// The step that puts `item` down anywhere but `place`, after `from`; plan.size() when none does.
std::size_t stepPuttingAside(const std::vector<std::string>& plan, const std::string& item,
                             const std::string& place, std::size_t from) {
  const std::string prefix = "(putdown mobile " + item + " ";
  for (std::size_t step = from; step < plan.size(); ++step) {
    if (plan[step].starts_with(prefix) && plan[step] != prefix + place + ")") return step;
  }
  return plan.size();
}

// In `plan`, the occupant of `place` is picked up from it and put down elsewhere before `item` is
// put down there.
void expectOccupantMovedFirst(const std::vector<std::string>& plan, const std::string& occupant,
                              const std::string& place, const std::string& item) {
  const std::size_t pickedUp = stepOf(plan, "(pickup mobile " + occupant + " " + place + ")");
  const std::size_t putAside = stepPuttingAside(plan, occupant, place, pickedUp);
  const std::size_t placed = stepOf(plan, "(putdown mobile " + item + " " + place + ")");
  ASSERT_LT(placed, plan.size()) << item << " is not put down in " << place;
  EXPECT_LT(pickedUp, placed) << occupant << " is not picked up from " << place << " first";
  EXPECT_LT(putAside, placed) << occupant << " is not put aside before " << item << " comes";
}

}  // namespace

// The premise of the scenario, in the scene's initial state: a bottle and a cereal box (the one
// turned on its table) find room in each of the three free places and in none of the occupied ones
// (not even on top of the occupant).
TEST(Tables, APlaceHoldsOneItem) {
  const World& world = tables();
  const PlacementGeometry placements(world);
  QueryScratch scratch = world.scratch();
  const GeometricState& initial = world.initialState();
  const std::vector<std::pair<std::string, std::string>> occupants{
      {"left-1", "bottle1"},  {"left-2", "cereal1"},  {"left-3", ""},
      {"front-1", "bottle2"}, {"front-2", ""},        {"front-3", "cereal2"},
      {"right-1", "cereal3"}, {"right-2", "bottle3"}, {"right-3", ""}};
  for (const char* item : {"bottle1", "cereal3"}) {
    const std::size_t object = world.find(item).value().index;
    for (const auto& [place, occupant] : occupants) {
      if (occupant == item) continue;
      const FreeSpace found = placements.freeSpaceFound(
          initial, object, world.find(place).value().index, FreeSpaceOptions{}, scratch);
      EXPECT_EQ(found.pose.has_value(), occupant.empty()) << item << " in " << place;
    }
  }
}

// Class I, problem 13: three items to the three free places, each picked up and put down once.
TEST(Tables, ClassIPutsThreeItemsInFreePlaces) {
  const std::vector<std::string> plan = solveAndVerify("class-1-13");
  EXPECT_EQ(plan.size(), 6U) << ::testing::PrintToString(plan);
  for (const char* step : {"(putdown mobile cereal1 right-3)", "(putdown mobile bottle2 left-3)",
                           "(putdown mobile cereal3 front-2)"}) {
    EXPECT_LT(stepOf(plan, step), plan.size()) << step;
  }
}

// Class II, problem 3: the bottle's goal place holds a cereal box, which is moved out of the way
// first: the shortest plan has four actions.
TEST(Tables, ClassIIMovesTheOccupantBeforePlacingTheGoalItem) {
  const std::vector<std::string> plan = solveAndVerify("class-2-03");
  EXPECT_EQ(plan.size(), 4U) << ::testing::PrintToString(plan);
  expectOccupantMovedFirst(plan, "cereal2", "front-3", "bottle3");
  EXPECT_EQ(plan.back(), "(putdown mobile bottle3 front-3)");
}

// Class III, problem 3: a chain of three occupied goal places, cleared from its free end: four
// items each moved once.
TEST(Tables, ClassIIIClearsAChainOfOccupiedPlaces) {
  const std::vector<std::string> plan = solveAndVerify("class-3-03");
  EXPECT_EQ(plan.size(), 8U) << ::testing::PrintToString(plan);
  expectOccupantMovedFirst(plan, "cereal1", "left-2", "cereal3");
  expectOccupantMovedFirst(plan, "cereal3", "right-1", "bottle2");
  expectOccupantMovedFirst(plan, "bottle2", "front-1", "bottle1");
}

// The command line: `kaboum solve` writes the plan file of a class II problem, and `kaboum
// verify-plan` accepts it.
TEST(TablesCli, SolveWritesAPlanThatVerifyPlanAccepts) {
  test::ScratchDir dir;
  const std::string files = "'" + example("domain.pddl") + "' '" + example("class-2-01.pddl") +
                            "' '" + example("scene.yaml") + "' ";
  const std::string plan = dir.file("plan.json");
  test::CliResult run = test::runCli(dir, "solve " + files + "--search astar --quiet --plan-out '" +
                                              plan + "'" + test::sharedCacheOption());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out,
            "(plan\n  (pickup mobile bottle2 front-1)\n  (putdown mobile bottle2 left-3)\n"
            "  (pickup mobile bottle1 left-1)\n  (putdown mobile bottle1 front-1))\n");
  run = test::runCli(dir,
                     "verify-plan " + files + "'" + plan + "' --quiet" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "verdict:    valid", run.out);
}

}  // namespace kaboum::tamp
