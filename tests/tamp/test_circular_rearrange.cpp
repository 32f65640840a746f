// The Bimanual Circular Rearrange scenario with geometry (examples/circular-rearrange, thesis
// §6.2.1, Table 6.1, Figure 6.3): the example's files are the generator's for three bottles, every
// generated size loads collision-free, three bottles are rearranged with every path certified and
// the plan verified independently, by the library and by `kaboum solve` and `kaboum verify-plan`
// with the handover variant of the domain.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/scenarios/circular_rearrange.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"
#include "plan_actions.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;
using namespace kaboum::scenarios;

namespace {

std::string example(const std::string& file) {
  return exampleFile("circular-rearrange/" + file);
}

const World& threeBottles() {
  static const World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  return world;
}

symbolic::ContingentProblem problem() {
  return symbolic::loadContingent(example("domain.pddl"), example("problem-3.pddl"));
}

}  // namespace

TEST(CircularRearrange, TheExampleIsTheGeneratorsOutputForThreeBottles) {
  EXPECT_EQ(test::slurp(example("domain.pddl")), circularRearrangeDomain());
  EXPECT_EQ(test::slurp(example("domain-handover.pddl")), circularRearrangeDomain(true));
  EXPECT_EQ(test::slurp(example("problem-3.pddl")), circularRearrangeProblem(3));
  EXPECT_EQ(test::slurp(example("scene.yaml")), circularRearrangeScene(3));
}

TEST(CircularRearrange, EverySizeThatFitsTheTableLoadsCollisionFree) {
  for (const int n : {2, 5, 9, kCircularRearrangeMaxObjects}) {
    const World world(
        parseSceneText(circularRearrangeScene(n), "scene.yaml", exampleFile("circular-rearrange")),
        {MeshPieces::Hulls, std::nullopt});
    EXPECT_EQ(world.description().locations.size(), static_cast<std::size_t>(n) + 1) << n;
    EXPECT_FALSE(world.firstCollision(world.initialState()).has_value()) << n;
    (void)symbolic::parseContingent(circularRearrangeDomain(true), "domain.pddl",
                                    circularRearrangeProblem(n), "problem.pddl");
  }
  EXPECT_THROW((void)circularRearrangeProblem(1), InputError);
  EXPECT_THROW((void)circularRearrangeScene(kCircularRearrangeMaxObjects + 1), InputError);
}

TEST(CircularRearrange, ThreeBottlesAreRearrangedAndThePlanVerifies) {
  SolveOptions options;
  options.search.mode = "gbfs";
  Solver solver(threeBottles(), problem(), options);
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(result.verification.collidingPaths, 0U);
  const nlohmann::json file = planFileJson(
      solver, result, {example("domain.pddl"), example("problem-3.pddl"), example("scene.yaml")});
  // Each bottle's goal location holds another bottle at first: some bottle is put down at least
  // twice, and each of the three at its goal.
  const std::vector<std::string> plan = planActions(file);
  const auto putDowns = std::count_if(plan.begin(), plan.end(), [](const std::string& action) {
    return action.starts_with("(putdown");
  });
  EXPECT_GE(putDowns, 4) << file["nodes"].dump();
  EXPECT_GE(plan.size(), 8U);
  const PlanCheck check = verifyPlanFile(threeBottles(), problem(), file, "plan.json");
  EXPECT_TRUE(check.passed()) << check.verification.symbolic.message
                              << (check.failures.empty() ? "" : check.failures.front());
}

TEST(CircularRearrangeCli, GeneratesSolvesWithHandoverAndVerifiesThePlanFile) {
  test::ScratchDir dir;
  test::CliResult run =
      test::runCli(dir, "circular-rearrange 3 --out-dir '" + dir.file("cell") + "'");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out, dir.file("cell/circular-rearrange-domain.pddl") + "\n" +
                         dir.file("cell/circular-rearrange-3.pddl") + "\n" +
                         dir.file("cell/circular-rearrange-handover-domain.pddl") + "\n" +
                         dir.file("cell/circular-rearrange-3.yaml") + "\n");
  const std::string files = "'" + dir.file("cell/circular-rearrange-handover-domain.pddl") + "' '" +
                            dir.file("cell/circular-rearrange-3.pddl") + "' '" +
                            dir.file("cell/circular-rearrange-3.yaml") + "' ";
  const std::string plan = dir.file("plan.json");
  // The search with geometry from the start hands a bottle over; the symbolic plan refined
  // first does without.
  run = test::runCli(dir, "solve " + files + "--search gbfs --integrated --no-verify --quiet " +
                              "--plan-out " + plan + test::sharedCacheOption());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::vector<std::string> steps = planActions(nlohmann::json::parse(test::slurp(plan)));
  EXPECT_TRUE(std::any_of(steps.begin(), steps.end(), [](const std::string& action) {
    return action.starts_with("(handover");
  })) << "a bottle changes hands in the air";
  run = test::runCli(dir, "verify-plan " + files + plan + " --quiet" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "verdict:    valid", run.out);

  run = test::runCli(dir, "circular-rearrange 1 --out-dir '" + dir.file("cell") + "'");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(run.err, "kaboum: error: circular rearrange: n must be from 2 to 16, got 1\n");
}

}  // namespace kaboum::tamp
