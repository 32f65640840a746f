// `kaboum solve --geometry exact` (thesis §6.2.3, Proposition 4): the same planner with exact
// predicates on the original meshes solves examples/pick-and-place, its plan verifies, and its
// statistics say so; --epsilon overrides the scene's ε; bad values of both options give one line
// and exit code 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/solver.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/exact_predicates.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string example(const std::string& file) {
  return exampleFile("pick-and-place/" + file);
}

std::string exampleFiles() {
  return "'" + example("domain.pddl") + "' '" + example("problem.pddl") + "' '" +
         example("scene.yaml") + "'" + test::sharedCacheOption();
}

}  // namespace

TEST(ExactGeometry, SolvesPickAndPlaceWithAVerifiedPlan) {
  World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  const verify::ExactPredicates exact(world);
  world.usePredicates(&exact);
  Solver solver(world, symbolic::loadContingent(example("domain.pddl"), example("problem.pddl")));
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(result.verification.collidingPaths, 0U);
  EXPECT_GE(result.verification.paths, 6U);
  EXPECT_GT(result.geometric.checks.stateChecks, 0U);
  EXPECT_GT(result.geometric.checks.motionChecks, 0U);
}

TEST(ExactGeometry, TheCliSaysTheGeometryAndTheEpsilonItUsed) {
  test::ScratchDir dir;
  // The example's scene stating ε = 1%, overridden by the example's 5 mm (whose decomposition the
  // other tests cache).
  std::string scene = test::slurp(example("scene.yaml"));
  scene.replace(scene.find("  epsilon: 0.005"), 16, "  epsilon: 1%   ");
  const std::string files = "'" + example("domain.pddl") + "' '" + example("problem.pddl") + "' '" +
                            dir.write("scene.yaml", scene) + "'" + test::sharedCacheOption();
  const test::CliResult run =
      test::runCli(dir, "solve " + files + " --geometry exact --epsilon 0.005 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json statistics = nlohmann::json::parse(run.out)["statistics"];
  EXPECT_EQ(statistics["geometry"], "exact");
  EXPECT_EQ(statistics["epsilon"], "0.005");
  EXPECT_EQ(statistics["plan_actions"], 2);
  EXPECT_EQ(statistics["collision_checks"].get<std::size_t>(),
            statistics["state_checks"].get<std::size_t>() +
                statistics["motion_checks"].get<std::size_t>());
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "exact predicates, epsilon 0.005", run.err);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "0 colliding", run.err);
  const test::CliResult bounded = test::runCli(dir, "solve " + exampleFiles() + " --json --quiet");
  ASSERT_EQ(bounded.exitCode, 0) << bounded.err;
  const nlohmann::json defaults = nlohmann::json::parse(bounded.out)["statistics"];
  EXPECT_EQ(defaults["geometry"], "bounded");
  EXPECT_EQ(defaults["epsilon"], "0.005");  // the scene file's
}

TEST(ExactGeometry, BadOptionValuesGiveOneLineAndExitCodeTwo) {
  test::ScratchDir dir;
  for (const std::string option :
       {"--epsilon -0.01", "--epsilon 0", "--epsilon 0%", "--epsilon abc", "--epsilon 150%",
        "--epsilon 1mm", "--epsilon ''", "--geometry convex"}) {
    const test::CliResult run = test::runCli(dir, "solve " + exampleFiles() + " " + option);
    EXPECT_EQ(run.exitCode, 2) << option;
    EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, option.substr(0, option.find(' ')), run.err);
  }
}

}  // namespace kaboum::tamp
