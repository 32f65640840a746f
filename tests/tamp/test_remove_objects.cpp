// The Remove n Objects scenario (seed 003 §IV-A, Table II; examples/remove-objects): the
// generator's files parse and build, n = 3 solves in both layouts with verified plans, in the line
// layout the objects leave the line in the only order the geometry allows, and bad sizes are
// rejected.
#include <gtest/gtest.h>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/scenarios/remove_objects.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/solver.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;
using scenarios::RemoveObjectsLayout;

namespace {

struct SolvedScenario {
  SolveResult result;
  std::vector<std::string> firstPickups;  // the objects in the order they are first picked up
};

SolvedScenario solveRemoveObjects(int n, RemoveObjectsLayout layout) {
  const scenarios::RemoveObjectsScenario scenario = scenarios::removeObjects(n, layout);
  const World world(io::parseSceneText(scenario.scene, "scene.yaml", "."),
                    {MeshPieces::Hulls, std::nullopt});
  Solver solver(world, symbolic::parseContingent(scenario.domain, "domain.pddl", scenario.problem,
                                                 "problem.pddl"));
  SolvedScenario solved{solver.solve(), {}};
  const symbolic::PlanTree& plan = solved.result.plan;
  for (int node = plan.root; node >= 0; node = plan.nodes[node].next) {
    for (const ActionGeometry& action : solved.result.geometry[node]) {
      const std::string& object = action.arguments.at(1);
      if (action.procedure == "pickUp" &&
          std::find(solved.firstPickups.begin(), solved.firstPickups.end(), object) ==
              solved.firstPickups.end()) {
        solved.firstPickups.push_back(object);
      }
    }
  }
  return solved;
}

void expectVerifiedPlanRemovingAll(const SolvedScenario& solved, std::size_t n) {
  ASSERT_EQ(solved.result.status, PlannerStatus::Solved) << solved.result.message;
  EXPECT_TRUE(solved.result.verification.passed()) << solved.result.message;
  EXPECT_TRUE(solved.result.verification.symbolic.valid);
  EXPECT_EQ(solved.result.verification.collidingPaths, 0U);
  EXPECT_EQ(solved.firstPickups.size(), n);
}

}  // namespace

TEST(RemoveObjects, TheExampleFilesAreTheGeneratorsOutput) {
  for (const RemoveObjectsLayout layout :
       {RemoveObjectsLayout::Random, RemoveObjectsLayout::Line}) {
    const scenarios::RemoveObjectsScenario scenario = scenarios::removeObjects(3, layout);
    const std::string stem = "remove-objects/remove-objects-" + scenarios::layoutName(layout);
    EXPECT_EQ(test::slurp(exampleFile("remove-objects/remove-objects-domain.pddl")),
              scenario.domain);
    EXPECT_EQ(test::slurp(exampleFile(stem + "-3.pddl")), scenario.problem);
    EXPECT_EQ(test::slurp(exampleFile(stem + "-3.yaml")), scenario.scene);
  }
}

TEST(RemoveObjects, TheRandomLayoutDependsOnTheSeedOnly) {
  using scenarios::removeObjects;
  EXPECT_EQ(removeObjects(20, RemoveObjectsLayout::Random, 7).scene,
            removeObjects(20, RemoveObjectsLayout::Random, 7).scene);
  EXPECT_NE(removeObjects(20, RemoveObjectsLayout::Random, 7).scene,
            removeObjects(20, RemoveObjectsLayout::Random, 8).scene);
  // Every size parses: the problem names n objects, the scene builds (no object starts in a
  // collision, which the World rejects).
  for (const RemoveObjectsLayout layout :
       {RemoveObjectsLayout::Random, RemoveObjectsLayout::Line}) {
    const scenarios::RemoveObjectsScenario scenario = removeObjects(20, layout, 7);
    const symbolic::ContingentProblem problem =
        symbolic::parseContingent(scenario.domain, "domain.pddl", scenario.problem, "problem.pddl");
    const io::SceneDescription scene = io::parseSceneText(scenario.scene, "scene.yaml", ".");
    EXPECT_EQ(scene.objects.size(), 21U) << "the table and 20 objects";
    EXPECT_NO_THROW(World(scene, {MeshPieces::Hulls, std::nullopt}));
  }
}

TEST(RemoveObjects, ThreeObjectsAtRandomPlacesAreRemovedWithAVerifiedPlan) {
  const SolvedScenario solved = solveRemoveObjects(3, RemoveObjectsLayout::Random);
  expectVerifiedPlanRemovingAll(solved, 3);
}

TEST(RemoveObjects, ThreeObjectsInALineLeaveItNearestFirst) {
  const SolvedScenario solved = solveRemoveObjects(3, RemoveObjectsLayout::Line);
  expectVerifiedPlanRemovingAll(solved, 3);
  // o3 is nearest the base, where the side grasp approaches from; o1 at the far end. Nothing in
  // the domain orders them: the palm would hit the plate behind the one grasped.
  EXPECT_EQ(solved.firstPickups, (std::vector<std::string>{"o3", "o2", "o1"}));
}

TEST(RemoveObjects, BadSizesAndLayoutsAreRejected) {
  EXPECT_THROW((void)scenarios::removeObjects(0, RemoveObjectsLayout::Line), InputError);
  EXPECT_THROW((void)scenarios::removeObjects(scenarios::kMaxRemovedObjects + 1,
                                              RemoveObjectsLayout::Random),
               InputError);
  const test::ScratchDir dir;
  const test::CliResult zero =
      test::runCli(dir, "remove-objects 0 --out-dir '" + dir.file("generated") + "'");
  EXPECT_EQ(zero.exitCode, 2);
  EXPECT_EQ(zero.err, "kaboum: error: remove objects: n must be between 1 and 20, got 0\n");
  const test::CliResult layout = test::runCli(dir, "remove-objects 3 --layout zigzag");
  EXPECT_EQ(layout.exitCode, 2);
  EXPECT_EQ(test::lineCount(layout.err), 1U);
  EXPECT_NE(layout.err.find("--layout must be random or line, got 'zigzag'"), std::string::npos);
  const test::CliResult written = test::runCli(
      dir, "remove-objects 3 --layout line --quiet --out-dir '" + dir.file("generated") + "'");
  EXPECT_EQ(written.exitCode, 0);
  EXPECT_EQ(written.out, "");
  EXPECT_EQ(test::slurp(dir.file("generated/remove-objects-line-3.yaml")),
            scenarios::removeObjects(3, RemoveObjectsLayout::Line).scene);
}

}  // namespace kaboum::tamp
