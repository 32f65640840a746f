// The handover attachment (thesis §6.1.2; the handoverBearing action of §6.2.3) in the two-arm
// cell of examples/circular-rearrange (the Bartender's two KR5 arms, 1 m apart): one arm hands the
// bottle it holds to the other in the air, every motion certified and free on the original
// meshes; too far apart there is no handover, with the reason; a plan with a handover reads back
// from its plan file and verifies.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "attachment_calls.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string example(const std::string& file) {
  return exampleFile("circular-rearrange/" + file);
}

const World& cell() {
  static const World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  return world;
}

using calls::apply;

std::vector<std::pair<GeometricStep::Kind, std::size_t>> kindsAndRobots(
    const ActionGeometry& action) {
  std::vector<std::pair<GeometricStep::Kind, std::size_t>> steps;
  for (const GeometricStep& step : action.steps) steps.emplace_back(step.kind, step.robot);
  return steps;
}

// In examples/circular-rearrange, robot2 is to hold o1, which stands at loc1 where robot1 alone
// reaches it; there is no other location to put it down.
symbolic::ContingentProblem robot2HoldsO1() {
  return symbolic::parseContingent(test::slurp(example("domain-handover.pddl")),
                                   example("domain-handover.pddl"), R"((define (problem give-o1)
  (:domain circular-rearrange)
  (:objects o1 - bottle robot1 robot2 - robot loc1 - location)
  (:init (ishandempty robot1) (ishandempty robot2) (isatlocation o1 loc1) (= (geometry) 0))
  (:goal (isrobotgrasps robot2 o1))))",
                                   "problem.pddl");
}

}  // namespace

TEST(Handover, TheGiverHandsTheBottleOverInTheAirOnCertifiedPaths) {
  const World& world = cell();
  const std::size_t o1 = world.find("o1")->index;
  GeometricAttachments attachments(world);
  const std::optional<std::size_t> picked = apply(attachments, "pickUp", {"robot1", "o1"}, 0);
  ASSERT_TRUE(picked.has_value()) << attachments.statistics().recentFailures.back();
  const std::optional<std::size_t> handed =
      apply(attachments, "handover", {"robot1", "o1", "robot2"}, *picked);
  ASSERT_TRUE(handed.has_value()) << attachments.statistics().recentFailures.back();

  const GeometricState& after = attachments.map().state(*handed);
  EXPECT_TRUE(after.robots[0].heldObjects.empty());
  EXPECT_EQ(after.robots[1].heldObjects, std::vector<std::size_t>{o1});
  EXPECT_FALSE(after.placements[world.scene().slot(o1)].present) << "the bottle is in the air";
  EXPECT_FALSE(world.firstCollision(after).has_value());

  const ActionGeometry* action = attachments.transition(*picked, *handed);
  ASSERT_NE(action, nullptr);
  EXPECT_EQ(action->procedure, "handover");
  EXPECT_EQ(action->arguments, (std::vector<std::string>{"robot1", "o1", "robot2"}));
  using Kind = GeometricStep::Kind;
  EXPECT_EQ(kindsAndRobots(*action),
            (std::vector<std::pair<Kind, std::size_t>>{{Kind::Transfer, 0},
                                                       {Kind::Transit, 1},
                                                       {Kind::Approach, 1},
                                                       {Kind::Grasp, 1},
                                                       {Kind::Release, 0},
                                                       {Kind::Retreat, 0}}));
  // Replayed, the receiver's grasp takes the bottle from the giver where the giver holds it, and
  // the giver's release leaves it with the receiver: the state the attachment reached.
  const std::vector<GeometricState> states =
      statesAlong(world, attachments.map().state(*picked), *action);
  EXPECT_EQ(attachments.map().find(states.back()), handed);
  EXPECT_EQ(holderOf(states[3], o1), std::optional<std::size_t>(0));
  EXPECT_EQ(holderOf(states[4], o1), std::optional<std::size_t>(1));
  EXPECT_TRUE(objectPose(world, states[3], o1).isApprox(action->steps[4].pose, 1e-6));
  EXPECT_TRUE(objectPose(world, states.back(), o1).isApprox(action->steps[4].pose, 1e-6));

  PlanVerification verification;
  verification.smallestClearance = std::numeric_limits<double>::infinity();
  verifyActionPaths(verify::ReferenceGeometry(world), 0, *action, states, {}, verification);
  EXPECT_EQ(verification.paths, 4U);
  EXPECT_EQ(verification.collidingPaths, 0U) << verification.firstCollision;
  EXPECT_GT(verification.smallestClearance, 0.0);
}

TEST(Handover, ArmsTooFarApartHaveNoHandoverAndSayWhy) {
  std::string scene = test::slurp(example("scene.yaml"));
  const std::string robot2Base = "position: [1.0, 0, 0.5]";
  scene.replace(scene.find(robot2Base), robot2Base.size(), "position: [2.5, 0, 0.5]");
  const World world(parseSceneText(scene, "scene.yaml", exampleFile("circular-rearrange")),
                    {MeshPieces::Hulls, std::nullopt});
  GeometricAttachments attachments(world);
  const std::optional<std::size_t> picked = apply(attachments, "pickUp", {"robot1", "o1"}, 0);
  ASSERT_TRUE(picked.has_value()) << attachments.statistics().recentFailures.back();
  EXPECT_FALSE(apply(attachments, "handover", {"robot1", "o1", "robot2"}, *picked).has_value());
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "handover(robot1, o1, robot2): ",
                      attachments.statistics().recentFailures.back());
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "no IK solution",
                      attachments.statistics().recentFailures.back());
}

TEST(Handover, TheGiverHoldsTheObjectAndTheReceiverIsAnotherRobotWithAnEmptyHand) {
  GeometricAttachments attachments(cell());
  const auto failure = [&] { return attachments.statistics().recentFailures.back(); };
  EXPECT_FALSE(apply(attachments, "handover", {"robot1", "o1", "robot2"}, 0).has_value());
  EXPECT_EQ(failure(), "handover(robot1, o1, robot2): the giver does not hold the object");
  const std::optional<std::size_t> picked = apply(attachments, "pickUp", {"robot1", "o1"}, 0);
  ASSERT_TRUE(picked.has_value()) << failure();
  EXPECT_FALSE(apply(attachments, "handover", {"robot1", "o1", "gripper1"}, *picked).has_value());
  EXPECT_EQ(failure(), "handover(robot1, o1, gripper1): the giver and the receiver are one robot");
  EXPECT_FALSE(apply(attachments, "handover", {"robot1", "table", "robot2"}, *picked).has_value());
  EXPECT_EQ(failure(), "handover(robot1, table, robot2): not a movable object of the scene");
  const std::optional<std::size_t> both = apply(attachments, "pickUp", {"robot2", "o2"}, *picked);
  ASSERT_TRUE(both.has_value()) << failure();
  EXPECT_FALSE(apply(attachments, "handover", {"robot1", "o1", "robot2"}, *both).has_value());
  EXPECT_EQ(failure(), "handover(robot1, o1, robot2): the receiver holds an object");
}

TEST(Handover, APlanWithAHandoverReadsBackFromItsPlanFileAndVerifies) {
  SolveOptions options;
  options.search.mode = "gbfs";
  Solver solver(cell(), robot2HoldsO1(), options);
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  nlohmann::json file = planFileJson(
      solver, result, {example("domain-handover.pddl"), "problem.pddl", example("scene.yaml")});
  nlohmann::json* handover = nullptr;
  for (nlohmann::json& node : file["nodes"]) {
    if (node.value("action", "") == "(handover robot1 o1 robot2)") handover = &node;
  }
  ASSERT_NE(handover, nullptr) << file["nodes"].dump();
  const nlohmann::json& steps = (*handover)["geometry"][0]["steps"];
  EXPECT_EQ(steps[3]["kind"], "grasp");
  EXPECT_EQ(steps[3]["robot"], "robot2");
  EXPECT_EQ(steps[4]["kind"], "release");
  EXPECT_EQ(steps[4]["robot"], "robot1");

  const PlanCheck check = verifyPlanFile(cell(), robot2HoldsO1(), file, "plan.json");
  EXPECT_TRUE(check.passed()) << check.verification.symbolic.message
                              << (check.failures.empty() ? "" : check.failures.front());
  EXPECT_EQ(check.verification.collidingPaths, 0U);

  // The receiver's grasp 5 cm away from where the giver holds the bottle.
  (*handover)["geometry"][0]["steps"][3]["object_in_link"]["position"][0] =
      steps[3]["object_in_link"]["position"][0].get<double>() + 0.05;
  const PlanCheck moved = verifyPlanFile(cell(), robot2HoldsO1(), file, "plan.json");
  EXPECT_FALSE(moved.passed());
  ASSERT_FALSE(moved.failures.empty());
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "handover(robot1, o1, robot2) step 4 (grasp): robot 'robot2' grasps object "
                      "'o1' away from where it is",
                      moved.failures.front());
}

}  // namespace kaboum::tamp
