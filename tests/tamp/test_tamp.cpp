// The integrated planner: the symbolic–geometric map, the geometric attachments, solving a domain
// in a scene, and the plan with its verified geometry.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "attachment_calls.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"
#include "kaboum/tamp/solver.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string pickAndPlaceScene() {
  return exampleFile("pick-and-place/scene.yaml");
}

const World& pickAndPlaceWorld() {
  static const World world(readSceneFile(pickAndPlaceScene()), {MeshPieces::Hulls, std::nullopt});
  return world;
}

// A domain with the geometric attachments move and pickUp over the fluent (geometry).
const char* const kPickDomain = R"((define (domain pick)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents)
  (:types robot item)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - item))
  (:functions (geometry))
  (:modules
    (transit ?r - robot (geometry) effect move :reads ((geometry)))
    (grasp ?r - robot ?o - item (geometry) effect pickUp :reads ((geometry))))
  (:action moveto :parameters (?r - robot) :effect [transit ?r])
  (:action pickup
    :parameters (?r - robot ?o - item)
    :precondition (handempty ?r)
    :effect (and (not (handempty ?r)) (holding ?r ?o) [grasp ?r ?o]))))";

std::string pickProblem(const std::string& objects = "kr5 - robot block - item",
                        const std::string& init = "(handempty kr5) (= (geometry) 0)") {
  return "(define (problem p) (:domain pick) (:objects " + objects + ") (:init " + init +
         ") (:goal (holding kr5 block)))";
}

symbolic::ContingentProblem parse(const std::string& domain, const std::string& problem) {
  return symbolic::parseContingent(domain, "domain.pddl", problem, "problem.pddl");
}

std::string solverError(const std::string& domain, const std::string& problem) {
  try {
    Solver solver(pickAndPlaceWorld(), parse(domain, problem));
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

}  // namespace

TEST(GeometricStateMap, EqualStatesShareAnIdentifierAndTheInverseGivesTheState) {
  const World& world = pickAndPlaceWorld();
  GeometricStateMap map(1e-9);
  const GeometricState initial = world.initialState();
  EXPECT_EQ(map.intern(initial), 0U);
  EXPECT_EQ(map.intern(GeometricState(initial)), 0U);
  GeometricState nudged = initial;
  nudged.robots[0].configuration[0] += 1e-12;  // below the tolerance
  EXPECT_EQ(map.intern(nudged), 0U);
  GeometricState moved = initial;
  moved.robots[0].configuration[0] += 1e-6;
  EXPECT_EQ(map.intern(moved), 1U);
  EXPECT_EQ(map.find(moved), std::optional<std::size_t>(1));
  EXPECT_EQ(map.size(), 2U);
  EXPECT_EQ(map.state(1), moved);
  EXPECT_EQ(map.state(0), initial);
  GeometricState held = initial;
  world.hold(held, 0, 6, world.find("block")->index, Pose::Identity());
  EXPECT_EQ(map.intern(held), 2U) << "holding an object is another state";
  EXPECT_FALSE(map.find(GeometricState{}).has_value());
  EXPECT_THROW((void)map.state(3), std::out_of_range);
}

TEST(GeometricStateMap, PosesAreMappedPerObject) {
  GeometricStateMap map;
  Pose a = Pose::Identity();
  Pose b = a;
  b.translation().x() = 0.1;
  EXPECT_EQ(map.internPose(2, a), 0U);
  EXPECT_EQ(map.internPose(2, b), 1U);
  EXPECT_EQ(map.internPose(2, a), 0U);
  EXPECT_EQ(map.internPose(0, b), 0U) << "each object has its own identifiers";
  EXPECT_TRUE(map.pose(2, 1).isApprox(b));
  EXPECT_THROW(GeometricStateMap(0.0), std::invalid_argument);
}

TEST(Solver, PicksUpTheBlockWithVerifiedCertifiedPaths) {
  const World& world = pickAndPlaceWorld();
  Solver solver(world, parse(kPickDomain, pickProblem()));
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_TRUE(result.verification.symbolic.valid);
  EXPECT_GE(result.verification.paths, 3U);
  EXPECT_EQ(result.verification.collidingPaths, 0U);
  // The pickup carries transit, approach, grasp and lift, and ends holding the block.
  const ActionGeometry* pick = nullptr;
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) {
      if (action.procedure == "pickUp") pick = &action;
    }
  }
  ASSERT_NE(pick, nullptr);
  std::vector<GeometricStep::Kind> kinds;
  for (const GeometricStep& step : pick->steps) kinds.push_back(step.kind);
  EXPECT_EQ(kinds, (std::vector<GeometricStep::Kind>{
                       GeometricStep::Kind::Transit, GeometricStep::Kind::Approach,
                       GeometricStep::Kind::Grasp, GeometricStep::Kind::Retreat}));
  const std::vector<GeometricState> states =
      statesAlong(world, solver.attachments().map().state(pick->from), *pick);
  EXPECT_EQ(states.back(), solver.attachments().map().state(pick->to));
  const std::size_t block = world.find("block")->index;
  EXPECT_EQ(states.back().robots[0].heldObjects, std::vector<std::size_t>{block});
  EXPECT_FALSE(states.back().placements[world.scene().slot(block)].present);
  // Each motion starts where the previous one ended.
  for (std::size_t s = 0; s < pick->steps.size(); ++s) {
    if (pick->steps[s].path.empty()) continue;
    EXPECT_EQ(pick->steps[s].path.front(), states[s].robots[0].configuration) << "step " << s;
  }
}

TEST(Solver, TheSameSeedGivesTheSamePlanAndAnotherSeedAnotherGrasp) {
  const auto firstPath = [](std::uint64_t seed) {
    SolveOptions options;
    options.verify = false;
    options.geometry.seed = seed;
    Solver solver(pickAndPlaceWorld(), parse(kPickDomain, pickProblem()), options);
    const SolveResult result = solver.solve();
    EXPECT_EQ(result.status, PlannerStatus::Solved);
    for (const auto& node : result.geometry) {
      if (!node.empty()) return node.front().steps.at(1).path.back();
    }
    return std::vector<double>{};
  };
  EXPECT_EQ(firstPath(1), firstPath(1));
  EXPECT_NE(firstPath(1), firstPath(2));
}

namespace {

// kPickDomain without its move action: a finite search space (each move leads to a new state).
std::string withoutMove() {
  std::string domain = kPickDomain;
  const std::string move = "(:action moveto :parameters (?r - robot) :effect [transit ?r])";
  domain.erase(domain.find(move), move.size());
  return domain;
}

}  // namespace

TEST(SolverBadInput, NamesWithoutASceneEntityNameBothFiles) {
  const std::string error = solverError(kPickDomain, pickProblem("kr5 - robot block cup - item"));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "problem.pddl: 'cup' (argument 2 of module 'grasp', attachment 'pickUp') "
                      "names no robot, tool, object or location of ",
                      error);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "pick-and-place/scene.yaml", error);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "'arm' (argument 1 of module 'transit', attachment 'move') names no robot",
                      solverError(kPickDomain, pickProblem("kr5 arm - robot block - item")));
}

TEST(Solver, AnArgumentOfTheWrongKindMakesTheCallFail) {
  // PDDL's root type lets `table` (a fixed object) be picked symbolically; the geometry says no.
  Solver solver(pickAndPlaceWorld(),
                parse(withoutMove(),
                      "(define (problem p) (:domain pick) (:objects kr5 - robot "
                      "table - item) (:init (handempty kr5) (= (geometry) 0)) "
                      "(:goal (holding kr5 table)))"));
  const SolveResult result = solver.solve();
  EXPECT_EQ(result.status, PlannerStatus::Unsolvable);
  EXPECT_EQ(result.geometric.recentFailures,
            std::vector<std::string>{"pickUp(kr5, table): not a movable object of the scene"});
}

TEST(SolverBadInput, TheGeometricFluentMustStartAtTheInitialState) {
  EXPECT_PRED_FORMAT2(
      ::testing::IsSubstring,
      "problem.pddl: the geometric state fluent (geometry) must start at the "
      "scene's initial state: add (= (geometry) 0) to :init",
      solverError(kPickDomain, pickProblem("kr5 - robot block - item", "(handempty kr5)")));
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "must start at the scene's initial state",
                      solverError(kPickDomain, pickProblem("kr5 - robot block - item",
                                                           "(handempty kr5) (= (geometry) 3)")));
}

namespace {

// kPickDomain with its `transit` module and `moveto` action replaced.
std::string withTransit(const std::string& module, const std::string& action) {
  std::string domain = kPickDomain;
  const std::string oldModule = "(transit ?r - robot (geometry) effect move :reads ((geometry)))";
  domain.replace(domain.find(oldModule), oldModule.size(), module);
  const std::string oldAction = "(:action moveto :parameters (?r - robot) :effect [transit ?r])";
  domain.replace(domain.find(oldAction), oldAction.size(), action);
  return domain;
}

}  // namespace

TEST(SolverBadInput, ModulesMustUseTheAttachmentsAsTheyAreDefined) {
  EXPECT_PRED_FORMAT2(
      ::testing::IsSubstring, "domain.pddl:7:5: module 'transit': 'move' is an effect",
      solverError(withTransit("(transit ?r - robot conditionchecker move :reads ((geometry)))",
                              "(:action moveto :parameters (?r - robot) :precondition "
                              "[transit ?r])"),
                  pickProblem()));
  EXPECT_PRED_FORMAT2(
      ::testing::IsSubstring,
      "module 'transit': the geometric attachment 'move' reads the geometric state's fluent "
      "first and writes it (one fluent)",
      solverError(withTransit("(transit ?r - robot (geometry) effect move)",
                              "(:action moveto :parameters (?r - robot) :effect [transit ?r])"),
                  pickProblem()));
  EXPECT_PRED_FORMAT2(
      ::testing::IsSubstring, "module 'transit': 'move' takes 1 argument(s), not 2",
      solverError(withTransit("(transit ?r - robot ?o - item (geometry) effect move :reads "
                              "((geometry)))",
                              "(:action moveto :parameters (?r - robot ?o - item) :effect "
                              "[transit ?r ?o])"),
                  pickProblem()));
}

TEST(Solver, AnUnreachableObjectIsNoPlanWithTheGeometricReason) {
  std::string scene = test::slurp(pickAndPlaceScene());
  // The block out of the arm's reach.
  scene.replace(scene.find("[0.45, 0.25, -0.075]"), 20, "[0.45, 1.40, -0.075]");
  scene.replace(scene.find("[0.4, 0.9, 0.04]"), 16, "[0.4, 3.0, 0.04]");
  const World world(parseSceneText(scene, "scene.yaml", exampleFile("pick-and-place")),
                    {MeshPieces::Hulls, std::nullopt});
  Solver solver(world, parse(withoutMove(), pickProblem()));
  const SolveResult result = solver.solve();
  EXPECT_EQ(result.status, PlannerStatus::Unsolvable);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "search space is exhausted", result.message);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "pickUp(kr5, block): no IK solution",
                      result.geometric.recentFailures.back());
}

}  // namespace kaboum::tamp

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string example(const std::string& file) {
  return exampleFile("pick-and-place/" + file);
}

// The steps' kinds of the first action with `procedure` in the plan.
std::vector<GeometricStep::Kind> stepKinds(const SolveResult& result,
                                           const std::string& procedure) {
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) {
      if (action.procedure != procedure) continue;
      std::vector<GeometricStep::Kind> kinds;
      for (const GeometricStep& step : action.steps) kinds.push_back(step.kind);
      return kinds;
    }
  }
  return {};
}

using calls::check;

}  // namespace

TEST(Solver, MovesTheBlockFromTheLeftRegionToTheRightOne) {
  const World& world = pickAndPlaceWorld();
  Solver solver(world, symbolic::loadContingent(example("domain.pddl"), example("problem.pddl")));
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(result.verification.paths, 6U);
  EXPECT_EQ(stepKinds(result, "putDown"),
            (std::vector<GeometricStep::Kind>{
                GeometricStep::Kind::Transfer, GeometricStep::Kind::Approach,
                GeometricStep::Kind::Release, GeometricStep::Kind::Retreat}));
  // Where the plan ends: the block inside the right region, on the table, the hand empty.
  std::size_t last = 0;
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) last = std::max(last, action.to);
  }
  const GeometricState& end = solver.attachments().map().state(last);
  const std::size_t block = world.find("block")->index;
  EXPECT_TRUE(end.robots[0].heldObjects.empty());
  PlacementGeometry placements(world);
  QueryScratch scratch = world.scratch();
  EXPECT_TRUE(placements.isInside(end, block, world.find("right")->index));
  EXPECT_FALSE(placements.isInside(end, block, world.find("left")->index));
  const std::optional<Support> support = placements.isOnSupportSurface(end, block, scratch);
  ASSERT_TRUE(support.has_value());
  EXPECT_EQ(support->index, world.find("table")->index);
  EXPECT_FALSE(world.firstCollision(end).has_value());
}

TEST(GeometricAttachments, PlacementCheckersSeeTheInitialState) {
  GeometricAttachments attachments(pickAndPlaceWorld());
  EXPECT_TRUE(check(attachments, "isInside", {"block", "left"}, 0));
  EXPECT_FALSE(check(attachments, "isInside", {"block", "right"}, 0));
  EXPECT_FALSE(check(attachments, "isInside", {"kr5", "left"}, 0)) << "a robot is no object";
  EXPECT_TRUE(check(attachments, "isOnSupportSurface", {"block"}, 0));
  EXPECT_TRUE(check(attachments, "freeSpaceFound", {"block", "right"}, 0));
  EXPECT_FALSE(check(attachments, "isColliding", {}, 0));
  EXPECT_TRUE(check(attachments, "isReachable", {"kr5", "block"}, 0));
  EXPECT_THROW(check(attachments, "isInside", {"block", "left"}, 5), InputError)
      << "identifier 5 is no geometric state yet";
}

namespace {

// The pick-and-place scene with a location `corner`, a quarter of the right region.
const World& cornerWorld() {
  static const World world = [] {
    const test::ScratchDir dir;
    const std::string scene = dir.write(
        "scene.yaml", test::slurp(pickAndPlaceScene()) +
                          "  - name: corner\n"
                          "    region: {box: {min: [0.3, -0.25, -0.1], max: [0.45, -0.1, 0.1]}}\n");
    return World(readSceneFile(scene), {MeshPieces::Hulls, std::nullopt});
  }();
  return world;
}

// Pick the block up once and put it down once in the right region (a random placement there); the
// goal asks that it stands in the corner.
const char* const kCornerDomain = R"((define (domain corner)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents)
  (:types robot item location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - item) (moved)
               (dropzone ?l - location) (done ?l - location))
  (:functions (geometry))
  (:modules
    (grasp ?r - robot ?o - item (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - item ?l - location (geometry) effect putDown :reads ((geometry)))
    (inside ?o - item ?l - location conditionchecker isInside :reads ((geometry))))
  (:action pickup :parameters (?r - robot ?o - item)
    :precondition (and (handempty ?r) (not (moved)))
    :effect (and (not (handempty ?r)) (holding ?r ?o) [grasp ?r ?o]))
  (:action putdown :parameters (?r - robot ?o - item ?l - location)
    :precondition (and (holding ?r ?o) (dropzone ?l))
    :effect (and (handempty ?r) (not (holding ?r ?o)) (moved) [place ?r ?o ?l]))
  (:action confirm :parameters (?o - item ?l - location)
    :precondition (and (moved) [inside ?o ?l]) :effect (done ?l))))";

const char* const kCornerProblem = R"((define (problem p) (:domain corner)
  (:objects kr5 - robot block - item right corner - location)
  (:init (handempty kr5) (dropzone right) (= (geometry) 0))
  (:goal (and (done corner) (handempty kr5)))))";

// Breadth-first search with `samples` geometric samples per call and geometric seed `seed`.
SolveOptions cornerOptions(std::uint32_t samples, std::uint64_t seed) {
  SolveOptions options;
  options.search.mode = "bfs";
  options.search.samples = samples;
  options.geometry.seed = seed;
  return options;
}

}  // namespace

TEST(Solver, SeveralSamplesPerCallFindAPlacementThatOneSampleMisses) {
  // With seed 2 the first placement in the right region falls outside the corner (the domain
  // allows one putdown), so the thesis's one sample per call finds no plan; 16 do, and the plan
  // names the sample, which its plan file keeps and verify-plan replays.
  constexpr std::uint64_t kSeed = 2;
  Solver one(cornerWorld(), parse(kCornerDomain, kCornerProblem), cornerOptions(1, kSeed));
  EXPECT_EQ(one.solve().status, PlannerStatus::Unsolvable);
  Solver solver(cornerWorld(), parse(kCornerDomain, kCornerProblem), cornerOptions(16, kSeed));
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed());
  int sampled = -1;
  for (const symbolic::PlanTree::Node& node : result.plan.nodes) {
    if (node.kind == symbolic::PlanTree::Node::Kind::Action && node.sample > 0) {
      sampled = static_cast<int>(&node - result.plan.nodes.data());
    }
  }
  ASSERT_GE(sampled, 0) << symbolic::formatPlanTree(solver.task(), result.plan);
  const nlohmann::json file =
      planFileJson(solver, result, {"domain.pddl", "problem.pddl", "scene.yaml"});
  EXPECT_EQ(file["nodes"][static_cast<std::size_t>(sampled)]["sample"],
            result.plan.nodes[static_cast<std::size_t>(sampled)].sample);
  const PlanCheck check =
      verifyPlanFile(cornerWorld(), parse(kCornerDomain, kCornerProblem), file, "plan.json");
  EXPECT_TRUE(check.passed()) << check.verification.symbolic.message;
}

TEST(SolveCli, PrintsThePlanAndWritesThePlanFile) {
  test::ScratchDir dir;
  const std::string files = "'" + example("domain.pddl") + "' '" + example("problem.pddl") + "' '" +
                            example("scene.yaml") + "'" + test::sharedCacheOption();
  const test::CliResult run =
      test::runCli(dir, "solve " + files + " --plan-out " + dir.file("plan.json"));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "(pickup kr5 block left)", run.out);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "kaboum solve: solved, 2 action(s)", run.err);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "0 colliding", run.err);
  const nlohmann::json plan = nlohmann::json::parse(test::slurp(dir.file("plan.json")));
  EXPECT_EQ(plan["format"], "kaboum-plan");
  EXPECT_EQ(plan["verification"]["passed"], true);
  EXPECT_EQ(plan["initial_state"]["robots"]["kr5"].size(), 6U);
  int motions = 0;
  for (const auto& node : plan["nodes"]) {
    if (node["kind"] != "action") continue;
    for (const auto& effect : node["geometry"]) {
      for (const auto& step : effect["steps"]) {
        if (step.contains("waypoints")) {
          ++motions;
          EXPECT_GE(step["waypoints"].size(), 2U);
          EXPECT_EQ(step["waypoints"][0].size(), 6U);
        }
      }
    }
  }
  EXPECT_EQ(motions, 6);
  const test::CliResult json = test::runCli(dir, "solve " + files + " --json --quiet");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["statistics"]["plan_actions"], 2);
  EXPECT_TRUE(json.err.empty()) << json.err;
}

TEST(SolveCli, BadInputGivesOneLineAndExitCodeTwoAndNoPlanExitCodeOne) {
  test::ScratchDir dir;
  const std::string domain = "'" + example("domain.pddl") + "'";
  const std::string scene = "'" + example("scene.yaml") + "'";
  const std::string unknown = dir.write(
      "unknown.pddl",
      "(define (problem p) (:domain pick-and-place) (:objects kr5 - robot cup - object left - "
      "location) (:init (handempty kr5) (at cup left) (= (geometry) 0)) (:goal (holding kr5 "
      "cup)))");
  test::CliResult run = test::runCli(dir, "solve " + domain + " " + unknown + " " + scene);
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "unknown.pddl: 'cup' (argument 2 of module 'grasp'",
                      run.err);
  run = test::runCli(dir, "solve " + domain + " missing.pddl " + scene);
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
  run = test::runCli(dir, "solve " + domain + " '" + example("problem.pddl") + "' missing.yaml");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "missing.yaml", run.err);
  for (const std::string option : {"--memory-limit 0", "--search beam", "--samples 0"}) {
    run = test::runCli(
        dir, "solve " + domain + " '" + example("problem.pddl") + "' " + scene + " " + option);
    EXPECT_EQ(run.exitCode, 2) << option;
    EXPECT_EQ(test::lineCount(run.err), 1U) << run.err;
    EXPECT_PRED_FORMAT2(::testing::IsSubstring, option.substr(0, option.find(' ')), run.err);
  }
  // A goal the geometry cannot reach: the block into a region of the air. Picking the block up and
  // putting it back elsewhere leads to ever new geometric states, so the time limit ends it.
  const std::string air = dir.write(
      "air.yaml", test::slurp(example("scene.yaml")) +
                      "  - name: air\n    region: {box: {min: [0.3, -0.2, 0.5], max: [0.4, "
                      "-0.1, 0.6]}}\n");
  const std::string intoAir = dir.write(
      "air.pddl",
      "(define (problem p) (:domain pick-and-place) (:objects kr5 - robot block - object left "
      "air - location) (:init (handempty kr5) (at block left) (= (geometry) 0)) (:goal (at block "
      "air)))");
  run = test::runCli(dir, "solve " + domain + " " + intoAir + " '" + air + "' --time-limit 2" +
                              test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "no plan: time-limit", run.err);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "putDown(kr5, block, air): no free placement",
                      run.err);
  run = test::runCli(dir, "solve " + domain + " " + intoAir + " '" + air +
                              "' --memory-limit 0.002" + test::sharedCacheOption());
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "no plan: memory-limit", run.err);
}

}  // namespace kaboum::tamp
