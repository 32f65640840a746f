// The Stacked n Objects scenario with geometry (thesis §6.2.2; `kaboum stacked N --scene`,
// examples/stacked): a mobile manipulator moves o1 under the stack o2..on using three stands,
// placements found on the tops of the stacks, every path certified and verified.
#include <gtest/gtest.h>

#include "../support/test_support.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/scenarios/stacked_objects.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/solver.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

// The scene for n objects, its URDF named by absolute path.
World stackedWorld(int n) {
  return World(
      parseSceneText(scenarios::stackedObjectsScene(n, exampleFile("robots/mobile-5axis.urdf")),
                     "stacked.yaml", "."),
      {MeshPieces::Hulls, std::nullopt});
}

symbolic::ContingentProblem stackedProblem(int n) {
  return symbolic::parseContingent(scenarios::stackedObjectsGeometryDomain(), "domain.pddl",
                                   scenarios::stackedObjectsGeometryProblem(n), "problem.pddl");
}

}  // namespace

// Breadth-first, the shortest plan: 2n − 1 moves of Table 6.3, each a pickup and a putdown
// (Figure 6.5 for n = 3: o3 to stack3, o2 on it, o1 to stack1, o2 and o3 back on top). The
// placements are the quadtree's (the centre of the stand first), so that equal arrangements are
// equal geometric states.
TEST(StackedObjects, ThreeObjectsBreadthFirstStackedOnTheStandsAndVerified) {
  const int n = 3;
  const World world = stackedWorld(n);
  SolveOptions options;
  options.search.mode = "bfs";
  options.search.limits.seconds = 120;
  options.geometry.placementStrategy = SearchStrategy::Quadtree;
  Solver solver(world, stackedProblem(n), options);
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(symbolic::measure(result.plan).actions, 2.0 * (2 * n - 1));
  // Where the plan ends: o1 on stack1's stand, o2 on o1, o3 on o2, each placed flat.
  std::size_t last = 0;
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) last = std::max(last, action.to);
  }
  const GeometricState& end = solver.attachments().map().state(last);
  const PlacementGeometry placements(world);
  QueryScratch scratch = world.scratch();
  const auto id = [&](const std::string& name) { return world.find(name).value().index; };
  const std::vector<std::string> below{"stack1-stand", "o1", "o2"};
  for (int i = 1; i <= n; ++i) {
    const std::string block = "o" + std::to_string(i);
    EXPECT_TRUE(placements.isInside(end, id(block), id("stack1"))) << block;
    EXPECT_EQ(placements.isOnSupportSurface(end, id(block), scratch),
              (Support{Support::Kind::Object, id(below[static_cast<std::size_t>(i - 1)])}))
        << block;
  }
  EXPECT_FALSE(world.firstCollision(end).has_value());
}

// The verb writes the domain, the problem and the scene; `kaboum solve` solves them and the plan
// passes the verification. Bad sizes and a missing URDF: one line, exit code 2.
TEST(StackedObjects, TheVerbWritesASceneThatSolveSolves) {
  test::ScratchDir dir;
  const std::string urdf = " --urdf '" + exampleFile("robots/mobile-5axis.urdf") + "'";
  const test::CliResult written =
      test::runCli(dir, "stacked 2 --scene --out-dir '" + dir.file("gen") + "'" + urdf);
  ASSERT_EQ(written.exitCode, 0) << written.err;
  EXPECT_EQ(test::lineCount(written.out), 3U) << written.out;
  const std::string files = "'" + dir.file("gen/stacked-geometry-domain.pddl") + "' '" +
                            dir.file("gen/stacked-geometry-2.pddl") + "' '" +
                            dir.file("gen/stacked-geometry-2.yaml") + "'";
  const test::CliResult solved =
      test::runCli(dir, "solve " + files + " --search bfs --placement quadtree --no-cache");
  EXPECT_EQ(solved.exitCode, 0) << solved.err;
  EXPECT_NE(solved.err.find("solved, 6 action(s)"), std::string::npos) << solved.err;
  EXPECT_NE(solved.err.find(" 0 colliding"), std::string::npos) << solved.err;
  const std::string elsewhere = " --out-dir '" + dir.file("x") + "'";
  for (const auto& [arguments, message] : std::vector<std::pair<std::string, std::string>>{
           {"stacked 21 --scene" + urdf + elsewhere, "n must be at most 20"},
           {"stacked 1 --scene" + urdf + elsewhere, "n must be at least 2"},
           {"stacked 3 --scene --urdf '" + dir.file("none.urdf") + "'" + elsewhere,
            "--urdf: no such file"},
           {"solve " + files + " --placement spiral", "--placement"}}) {
    const test::CliResult bad = test::runCli(dir, arguments);
    EXPECT_EQ(bad.exitCode, 2) << arguments;
    EXPECT_EQ(test::lineCount(bad.err), 1U) << bad.err;
    EXPECT_NE(bad.err.find(message), std::string::npos) << bad.err;
  }
}

}  // namespace kaboum::tamp
