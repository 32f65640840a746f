// Reading back and independently checking a plan file (`kaboum verify-plan`): the solver's plan
// of examples/pick-and-place verifies; tampered copies give the right verdict or a one-line error.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;
using json = nlohmann::json;

namespace {

std::string example(const std::string& file) {
  return exampleFile("pick-and-place/" + file);
}

const World& world() {
  static const World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  return world;
}

symbolic::ContingentProblem problem() {
  return symbolic::loadContingent(example("domain.pddl"), example("problem.pddl"));
}

// The plan file of examples/pick-and-place as the solver writes it: (pickup kr5 block left) at
// nodes[2] with transit, approach, grasp, retreat; (putdown kr5 block right) at nodes[1].
const json& planFile() {
  static const json file = [] {
    Solver solver(world(), problem());
    const SolveResult result = solver.solve();
    EXPECT_EQ(result.status, PlannerStatus::Solved) << result.message;
    return planFileJson(solver, result,
                        {example("domain.pddl"), example("problem.pddl"), example("scene.yaml")});
  }();
  return file;
}

// The node of the plan file whose action is `action`.
json& node(json& file, const std::string& action) {
  for (json& entry : file["nodes"]) {
    if (entry.value("action", "") == action) return entry;
  }
  ADD_FAILURE() << "no node " << action;
  return file;
}

json& pickUpStep(json& file, std::size_t step) {
  return node(file, "(pickup kr5 block left)")["geometry"][0]["steps"][step];
}

PlanCheck verify(const json& file) {
  return verifyPlanFile(world(), problem(), file, "plan.json");
}

std::string inputError(const json& file) {
  try {
    (void)verify(file);
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

}  // namespace

TEST(VerifyPlanFile, TheSolversPlanReadsBackAndIsValid) {
  const PlanCheck check = verify(planFile());
  EXPECT_TRUE(check.passed()) << check.verification.symbolic.message
                              << (check.failures.empty() ? "" : check.failures.front());
  EXPECT_TRUE(check.verification.symbolic.valid);
  EXPECT_EQ(check.verification.paths, 6U);
  EXPECT_EQ(check.verification.checks.size(), 6U);
  EXPECT_EQ(check.verification.collidingPaths, 0U);
  EXPECT_GT(check.verification.samples, 6U);
  EXPECT_GT(check.verification.smallestClearance, 0.0);
  ASSERT_EQ(check.contents.plan.nodes.size(), planFile()["nodes"].size());
  const json& pick = planFile()["nodes"][2];
  ASSERT_EQ(pick["action"], "(pickup kr5 block left)");
  ASSERT_EQ(check.contents.geometry[2].size(), 1U);
  const ActionGeometry& action = check.contents.geometry[2][0];
  EXPECT_EQ(action.procedure, "pickUp");
  EXPECT_EQ(action.arguments, (std::vector<std::string>{"kr5", "block"}));
  ASSERT_EQ(action.steps.size(), 4U);
  EXPECT_EQ(action.steps[2].kind, GeometricStep::Kind::Grasp);
  EXPECT_EQ(action.steps[2].object, world().find("block")->index);
  EXPECT_EQ(action.steps[1].path,
            pick["geometry"][0]["steps"][1]["waypoints"].get<std::vector<std::vector<double>>>());
}

TEST(VerifyPlanFile, AWaypointMovedIntoTheTableIsACollision) {
  json file = planFile();
  json& transit = pickUpStep(file, 0)["waypoints"];
  std::vector<double> down = transit[0];
  down[1] += 0.8;  // shoulder_pitch: the hand dips into the table
  transit.insert(transit.begin() + 1, down);
  const PlanCheck check = verify(file);
  EXPECT_FALSE(check.passed());
  EXPECT_TRUE(check.verification.symbolic.valid);
  EXPECT_TRUE(check.failures.empty()) << check.failures.front();
  EXPECT_EQ(check.verification.collidingPaths, 1U);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "pickUp(kr5, block) step 1 (transit): robot 'kr5'",
                      check.verification.firstCollision);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "collides with object 'table'",
                      check.verification.firstCollision);
  EXPECT_FALSE(check.verification.checks.front().result.collisionFree());
}

TEST(VerifyPlanFile, AMotionMustStartWhereThePreviousStepLeftTheRobot) {
  json file = planFile();
  pickUpStep(file, 1)["waypoints"][0][0] =
      pickUpStep(file, 1)["waypoints"][0][0].get<double>() + 0.01;
  const PlanCheck check = verify(file);
  EXPECT_FALSE(check.passed());
  ASSERT_EQ(check.failures.size(), 1U);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "nodes[2] (pickup kr5 block left): pickUp(kr5, block) step 2 (approach): "
                      "starts 0.01 (joint 'shoulder_yaw') from where robot 'kr5' is",
                      check.failures.front());
}

TEST(VerifyPlanFile, GraspsAndReleasesMustBeWhereTheObjectIs) {
  json file = planFile();
  json& release = node(file, "(putdown kr5 block right)")["geometry"][0]["steps"][2];
  ASSERT_EQ(release["kind"], "release");
  release["object_pose"]["position"][2] =
      release["object_pose"]["position"][2].get<double>() + 0.01;
  json& grasp = pickUpStep(file, 2);
  ASSERT_EQ(grasp["kind"], "grasp");
  grasp["object_in_link"]["position"][0] =
      grasp["object_in_link"]["position"][0].get<double>() + 0.01;
  const PlanCheck check = verify(file);
  EXPECT_FALSE(check.passed());
  ASSERT_EQ(check.failures.size(), 2U);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "step 3 (grasp): robot 'kr5' grasps object 'block' away from where it is",
                      check.failures[0] + check.failures[1]);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "step 3 (release): object 'block' is released away from where robot 'kr5' "
                      "holds it",
                      check.failures[0] + check.failures[1]);
}

TEST(VerifyPlanFile, ABranchThatFailsSymbolicallyMakesThePlanInvalid) {
  json file = planFile();
  file["root"] = node(file, "(putdown kr5 block right)")["id"];  // the pickup skipped
  const PlanCheck check = verify(file);
  EXPECT_FALSE(check.passed());
  EXPECT_FALSE(check.verification.symbolic.valid);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "plan.json: precondition of (putdown kr5 block right) is not known to hold",
                      check.verification.symbolic.message);
  ASSERT_FALSE(check.failures.empty());
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "robot 'kr5' does not hold object 'block'",
                      check.failures.front());
}

TEST(VerifyPlanFileBadInput, OneLineNamesTheFileAndTheKey) {
  json file = planFile();
  node(file, "(pickup kr5 block left)")["action"] = "(pickup kr5 cup left)";
  EXPECT_EQ(inputError(file),
            "plan.json: nodes[2].action: unknown or never applicable action (pickup kr5 cup left)");

  file = planFile();
  node(file, "(pickup kr5 block left)")["sample"] = -1;
  EXPECT_EQ(inputError(file), "plan.json: nodes[2].sample: expected a non-negative integer");
  node(file, "(pickup kr5 block left)")["sample"] = std::uint64_t{1} << 32;
  EXPECT_EQ(inputError(file), "plan.json: nodes[2].sample: expected a sample number below 2^32");

  file = planFile();
  node(file, "(pickup kr5 block left)")["geometry"][0].erase("to_state");
  EXPECT_EQ(inputError(file), "plan.json: nodes[2].geometry[0]: missing key 'to_state'");

  file = planFile();
  pickUpStep(file, 1)["waypoints"][2].erase(5);
  EXPECT_EQ(inputError(file),
            "plan.json: nodes[2].geometry[0].steps[1].waypoints[2]: 5 values, but robots 'kr5' "
            "have 6 joints");

  file = planFile();
  pickUpStep(file, 1)["waypoints"][0][2] = 2.0;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "plan.json: nodes[2].geometry[0].steps[1].waypoints[0][2]: joint "
                      "'elbow_pitch' of robot 'kr5' at 2 is outside its limits",
                      inputError(file));

  file = planFile();
  pickUpStep(file, 0)["robot"] = "wam";
  EXPECT_EQ(inputError(file),
            "plan.json: nodes[2].geometry[0].steps[0].robot: no robot 'wam' in the scene");

  file = planFile();
  pickUpStep(file, 2)["object_in_link"]["quaternion_wxyz"] = {2, 0, 0, 0};
  EXPECT_EQ(inputError(file),
            "plan.json: nodes[2].geometry[0].steps[2].object_in_link: not a finite position and "
            "unit quaternion");

  file = planFile();
  node(file, "(pickup kr5 block left)")["next"] = 7;
  EXPECT_EQ(inputError(file), "plan.json: nodes[2].next: no node 7 (the plan has 3)");

  file = planFile();
  file["nodes"][0] = {
      {"id", 0}, {"kind", "branch"}, {"test", "(holding kr5"}, {"on_true", 0}, {"on_false", 0}};
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "plan.json: nodes[0].test: not an S-expression",
                      inputError(file));
  file["nodes"][0]["test"] = "(flying block)";
  EXPECT_EQ(inputError(file), "plan.json: nodes[0].test: unknown atom (flying block)");

  // A join step names two different movable objects.
  const auto withJoin = [&](const json& objects) {
    json joined = planFile();
    json& steps = node(joined, "(pickup kr5 block left)")["geometry"][0]["steps"];
    steps.insert(steps.begin() + 1,
                 json{{"kind", "join"}, {"robot", "kr5"}, {"tool", ""}, {"objects", objects}});
    return inputError(joined);
  };
  EXPECT_EQ(withJoin({"block"}),
            "plan.json: nodes[2].geometry[0].steps[1].objects: expected the two objects joined");
  EXPECT_EQ(withJoin({"block", "table"}),
            "plan.json: nodes[2].geometry[0].steps[1].objects[1]: expected the name of a movable "
            "object of the scene");
  EXPECT_EQ(withJoin({"block", "block"}),
            "plan.json: nodes[2].geometry[0].steps[1].objects: an object cannot be joined to "
            "itself");

  // A plan made on another layout of the objects (another scene, or --placement-seed).
  file = planFile();
  file["initial_state"]["objects"]["block"]["position"][0] =
      file["initial_state"]["objects"]["block"]["position"][0].get<double>() + 0.02;
  EXPECT_EQ(inputError(file),
            "plan.json: initial_state.objects.block: the scene starts the object elsewhere (20.0 "
            "mm, 0.00° away): the plan was made on another scene or --placement-seed");
  file = planFile();
  file["initial_state"]["objects"]["cup"] = file["initial_state"]["objects"]["block"];
  EXPECT_EQ(inputError(file), "plan.json: initial_state.objects: the scene has no object 'cup'");
  file["initial_state"]["objects"] = 3;
  EXPECT_EQ(inputError(file), "plan.json: initial_state.objects: expected an object");

  EXPECT_EQ(inputError(json::array()), "plan.json: (top level): expected a JSON object");
  file = planFile();
  file["format"] = "kaboum-path";
  EXPECT_EQ(inputError(file), "plan.json: format: expected \"kaboum-plan\"");
}

// A plan made with the block at a random place (place_in) records its placement seed: verify-plan
// loads the scene with it, and another layout is one line naming the moved object.
TEST(VerifyPlanCli, APlanOnARandomLayoutReadsBackWithItsPlacementSeed) {
  test::ScratchDir dir;
  std::string scene = test::slurp(example("scene.yaml"));
  const std::string pose = "    pose: {position: [0.45, 0.25, -0.075]}\n";
  ASSERT_NE(scene.find(pose), std::string::npos);
  scene.replace(scene.find(pose), pose.size(),
                "    place_in: left\n    resting_faces: [[0, 0, -1]]\n");
  const std::string files = "'" + example("domain.pddl") + "' '" + example("problem.pddl") + "' '" +
                            dir.write("scene.yaml", scene) + "' ";
  const std::string plan = dir.file("plan.json");
  const test::CliResult solved =
      test::runCli(dir, "solve " + files + "--quiet --placement-seed 2 --plan-out " + plan +
                            test::sharedCacheOption());
  ASSERT_EQ(solved.exitCode, 0) << solved.err;
  EXPECT_EQ(json::parse(test::slurp(plan))["placement_seed"], 2);
  test::CliResult run =
      test::runCli(dir, "verify-plan " + files + plan + " -q" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "verdict:    valid", run.out);
  run = test::runCli(
      dir, "verify-plan " + files + plan + " --placement-seed 1" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "plan.json: initial_state.objects.block: the scene starts the object "
                      "elsewhere",
                      run.err);
  json negative = json::parse(test::slurp(plan));
  negative["placement_seed"] = -2;
  const std::string badSeed = dir.write("bad-seed.json", negative.dump());
  run = test::runCli(dir, "verify-plan " + files + badSeed + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "bad-seed.json: placement_seed: expected a non-negative integer", run.err);
}

TEST(VerifyPlanCli, ExitCodesZeroValidOneInvalidTwoBadInput) {
  test::ScratchDir dir;
  const std::string files = "'" + example("domain.pddl") + "' '" + example("problem.pddl") + "' '" +
                            example("scene.yaml") + "' ";
  const std::string plan = dir.file("plan.json");
  ASSERT_EQ(
      test::runCli(dir, "solve " + files + "--quiet --plan-out " + plan + test::sharedCacheOption())
          .exitCode,
      0);
  test::CliResult run =
      test::runCli(dir, "verify-plan " + files + plan + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "verdict:    valid", run.out);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "symbolic:   valid (2 action(s)", run.out);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "paths:      6 (", run.out);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "verify-plan: nodes[2] (pickup kr5 block left)",
                      run.err);

  run = test::runCli(dir,
                     "verify-plan " + files + plan + " --json --quiet" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const json report = json::parse(run.out);
  EXPECT_EQ(report["valid"], true);
  EXPECT_EQ(report["paths"].size(), 6U);
  EXPECT_EQ(report["paths"][0]["verification"]["collision_free"], true);
  EXPECT_EQ(report["colliding_paths"], 0);

  json file = json::parse(test::slurp(plan));
  json& transit = pickUpStep(file, 0)["waypoints"];
  std::vector<double> down = transit[0];
  down[1] += 0.8;
  transit.insert(transit.begin() + 1, down);
  const std::string colliding = dir.write("colliding.json", file.dump());
  run = test::runCli(dir, "verify-plan " + files + colliding + " -q" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_PRED_FORMAT2(
      ::testing::IsSubstring,
      "verdict:    INVALID: collision: nodes[2] pickUp(kr5, block) step 1 (transit)", run.out);

  pickUpStep(file, 1)["waypoints"][0].erase(0);
  const std::string bad = dir.write("bad.json", file.dump());
  run = test::runCli(dir, "verify-plan " + files + bad + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "bad.json: nodes[2].geometry[0].steps[1].waypoints[0]: 5 values", run.err);
  run = test::runCli(dir, "verify-plan " + files + dir.write("broken.json", "{\"nodes\": [") +
                              test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "broken.json:1:", run.err);
}

}  // namespace kaboum::tamp
