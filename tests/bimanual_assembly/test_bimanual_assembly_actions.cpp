// The assembly actions of the Bimanual Assembly scenario (thesis §6.2.3, Table 6.6, Figure 6.8;
// src/kaboum/tamp/assembly_attachments.hpp) on the scene of examples/bimanual-assembly, each
// called as the planner calls it: the gearbox assembled step by step (eight actions), each part
// where its fit puts it, the part inserted carried with the one it is in; the cases each action
// refuses (one arm for two, a part not held) and a bearing pushed through the pipe, which
// collides and is rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "../support/test_support.hpp"
#include "../tamp/attachment_calls.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/assembly_attachments.hpp"
#include "kaboum/tamp/solver.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/exact_predicates.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

// The World of the scene through the decomposition cache the CLI tests share (as the scene tests
// build it).
const World& bimanualWorld() {
  WorldOptions options;
  options.cacheDirectory =
      std::filesystem::path(KABOUM_CLI).parent_path() / "test-decomposition-cache";
  static const World world(readSceneFile(exampleFile("bimanual-assembly/scene.yaml")), options);
  return world;
}

std::size_t id(const std::string& name) {
  return bimanualWorld().find(name)->index;
}

// Effect `procedure` in state `from`; fails the test with the last failure's reason when it does
// not apply.
std::size_t applied(GeometricAttachments& attachments, const std::string& procedure,
                    const std::vector<std::string>& arguments, std::size_t from) {
  const std::optional<std::size_t> to = calls::apply(attachments, procedure, arguments, from);
  if (!to) {
    ADD_FAILURE() << procedure << ": " << attachments.statistics().recentFailures.back();
    return from;
  }
  return *to;
}

// The states of a sequence of effects applied one after the other from the initial state.
struct Assembly {
  GeometricAttachments attachments{bimanualWorld()};
  std::vector<std::size_t> states{0};

  void step(const std::string& procedure, const std::vector<std::string>& arguments) {
    states.push_back(applied(attachments, procedure, arguments, states.back()));
  }
};

// The assembly step by step: the right arm takes bearing1 and moves out of the way; the left arm
// slides bearing2 onto the tree and takes the pipe; the right arm pushes bearing1 into the pipe
// the left arm holds; the right arm moves away and the left arm lowers the pipe over the tree.
void assembleGearbox(Assembly& assembly) {
  assembly.step("pickUp", {"comau-right", "bearing1"});
  assembly.step("move", {"comau-right"});
  assembly.step("pickUp", {"comau-left", "bearing2"});
  assembly.step("assembleBearingTree", {"comau-left", "bearing2", "tree"});
  assembly.step("pickUp", {"comau-left", "pipe"});
  assembly.step("assemblePipeBearing", {"comau-left", "pipe", "comau-right", "bearing1"});
  assembly.step("move", {"comau-right"});
  assembly.step("assemblePipeTree", {"comau-left", "pipe", "tree"});
}

// Where `part` is in the frame of `base` in `state`.
Pose relativePose(const GeometricState& state, const std::string& base, const std::string& part) {
  const World& world = bimanualWorld();
  return objectPose(world, state, id(base)).inverse() * objectPose(world, state, id(part));
}

void expectOnAxis(const Pose& relative, const AssemblyFit& fit) {
  EXPECT_NEAR(relative.translation().head<2>().norm(), 0, 1e-6);
  EXPECT_NEAR(relative.translation().z(), fit.seatHeight, 1e-6);
  EXPECT_NEAR(relative.linear().col(2).z(), fit.flipped ? -1 : 1, 1e-6);
}

}  // namespace

TEST(BimanualAssemblyActions, TheGearboxIsAssembledOnTheTableStepByStep) {
  Assembly assembly;
  assembleGearbox(assembly);
  ASSERT_EQ(assembly.states.size(), 9u);
  const std::vector<std::size_t>& states = assembly.states;
  const GeometricStateMap& map = assembly.attachments.map();
  const AssemblyFits fits;
  // assembleBearingTree: bearing2 rests on the tree, the left hand is empty.
  const GeometricState& bearingOnTree = map.state(states[4]);
  EXPECT_TRUE(bearingOnTree.robots[0].heldObjects.empty());
  expectOnAxis(relativePose(bearingOnTree, "tree", "bearing2"), fits.bearingOnTree);
  // assemblePipeBearing: the left arm holds the pipe with bearing1 in it, the right hand is empty.
  const GeometricState& bearingInPipe = map.state(states[6]);
  EXPECT_EQ(bearingInPipe.robots[0].heldObjects,
            (std::vector<std::size_t>{id("pipe"), id("bearing1")}));
  EXPECT_TRUE(bearingInPipe.robots[1].heldObjects.empty());
  expectOnAxis(relativePose(bearingInPipe, "pipe", "bearing1"), fits.bearingInPipe);
  // assemblePipeTree: the gearbox stands on the table, nothing is held.
  const GeometricState& done = map.state(states[8]);
  EXPECT_TRUE(done.robots[0].heldObjects.empty());
  EXPECT_TRUE(done.robots[1].heldObjects.empty());
  expectOnAxis(relativePose(done, "tree", "pipe"), fits.pipeOnTree);
  expectOnAxis(relativePose(done, "pipe", "bearing1"), fits.bearingInPipe);
  expectOnAxis(relativePose(done, "tree", "bearing2"), fits.bearingOnTree);
  EXPECT_EQ(relativePose(done, "tree", "tree").translation().norm(), 0);
  // The parts that touch where they fit are joined: each bearing's bore on the tree's shaft, the
  // two bearings one on the other, the bearing pushed into the pipe past its bounds; the pipe and
  // the tree, the pipe and the tree's bearing are not.
  EXPECT_TRUE(done.areJoined(id("bearing2"), id("tree")));
  EXPECT_TRUE(done.areJoined(id("bearing1"), id("tree")));
  EXPECT_TRUE(done.areJoined(id("bearing1"), id("bearing2")));
  EXPECT_TRUE(done.areJoined(id("bearing1"), id("pipe")));
  EXPECT_FALSE(done.areJoined(id("pipe"), id("tree")));
  EXPECT_FALSE(done.areJoined(id("pipe"), id("bearing2")));
  // The gearbox is free of collisions only because its joined parts are not checked against
  // each other.
  EXPECT_FALSE(bimanualWorld().firstCollision(done));
  GeometricState unjoined = done;
  unjoined.joined.clear();
  EXPECT_TRUE(bimanualWorld().firstCollision(unjoined));
  // Each assembly's geometry: a transfer, the parts joined, the Cartesian insertion, the hand-over
  // of the parts and the retreat; assemblePipeBearing starts with the holder's transfer to the
  // meeting.
  const ActionGeometry* insertion = assembly.attachments.transition(states[5], states[6]);
  ASSERT_NE(insertion, nullptr);
  std::vector<GeometricStep::Kind> kinds;
  for (const GeometricStep& step : insertion->steps) kinds.push_back(step.kind);
  using Kind = GeometricStep::Kind;
  EXPECT_EQ(kinds, (std::vector<Kind>{Kind::Transfer, Kind::Transfer, Kind::Join, Kind::Approach,
                                      Kind::Grasp, Kind::Release, Kind::Retreat}));
}

// The verifier on the original meshes finds the insertion of the pipe over the tree (its joins and
// its approach, the transfer before left out) free with the contacts it joins and collides
// without them: the bearing's bore slides down the tree's shaft of the same radius.
TEST(BimanualAssemblyActions, TheVerifierAllowsTheJoinedContactsAndNoOthers) {
  Assembly assembly;
  assembleGearbox(assembly);
  ASSERT_EQ(assembly.states.size(), 9u);
  const ActionGeometry* lowered =
      assembly.attachments.transition(assembly.states[7], assembly.states[8]);
  ASSERT_NE(lowered, nullptr);
  ActionGeometry insertion = *lowered;
  const auto approach = std::find_if(
      insertion.steps.begin(), insertion.steps.end(),
      [](const GeometricStep& step) { return step.kind == GeometricStep::Kind::Approach; });
  ASSERT_NE(approach, insertion.steps.end());
  insertion.steps.erase(approach + 1, insertion.steps.end());
  insertion.steps.erase(insertion.steps.begin());  // the transfer
  const GeometricState& before = assembly.attachments.map().state(assembly.states[7]);
  const verify::ReferenceGeometry reference(bimanualWorld());
  verify::VerifyOptions options;
  options.jointStep = 1.0 * std::numbers::pi / 180;
  options.toolStep = 0.002;
  const auto verification = [&](const ActionGeometry& action) {
    PlanVerification result;
    verifyActionPaths(reference, 0, action, statesAlong(bimanualWorld(), before, action), options,
                      result);
    return result;
  };
  const PlanVerification joined = verification(insertion);
  EXPECT_EQ(joined.paths, 1u);
  EXPECT_EQ(joined.collidingPaths, 0u) << joined.firstCollision;
  ActionGeometry unjoined = insertion;
  std::erase_if(unjoined.steps,
                [](const GeometricStep& step) { return step.kind == GeometricStep::Kind::Join; });
  ASSERT_LT(unjoined.steps.size(), insertion.steps.size());
  const PlanVerification touching = verification(unjoined);
  EXPECT_EQ(touching.collidingPaths, 1u);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "assemblePipeTree(comau-left, pipe, tree) step",
                      touching.firstCollision);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "(approach)", touching.firstCollision);
  EXPECT_PRED_FORMAT2(::testing::IsSubstring, "object 'tree'", touching.firstCollision);
}

// Each action refuses what Table 6.6's preconditions exclude, whatever the symbolic state says:
// parts not held, or held by the wrong arm.
TEST(BimanualAssemblyActions, EachActionFailsWithoutItsPartsInHand) {
  GeometricAttachments attachments(bimanualWorld());
  const std::size_t initial = 0;
  EXPECT_FALSE(calls::apply(attachments, "assemblePipeBearing",
                            {"comau-left", "pipe", "comau-right", "bearing1"}, initial));
  EXPECT_FALSE(calls::apply(attachments, "assembleBearingTree", {"comau-left", "bearing2", "tree"},
                            initial));
  EXPECT_FALSE(
      calls::apply(attachments, "assemblePipeTree", {"comau-left", "pipe", "tree"}, initial));
  const std::size_t pipeHeld = applied(attachments, "pickUp", {"comau-left", "pipe"}, initial);
  EXPECT_FALSE(calls::apply(attachments, "assemblePipeBearing",
                            {"comau-left", "pipe", "comau-left", "bearing1"}, pipeHeld));
  EXPECT_FALSE(
      calls::apply(attachments, "assembleBearingTree", {"comau-right", "pipe", "tree"}, pipeHeld));
  const std::vector<std::string>& failures = attachments.statistics().recentFailures;
  ASSERT_GE(failures.size(), 2u);
  EXPECT_NE(failures[failures.size() - 2].find("the two arms are one robot"), std::string::npos);
  EXPECT_NE(failures.back().find("does not hold the part"), std::string::npos);
}

// The contacts allowed are only those between the parts moved and the parts they go into: pushed
// 12 cm further from the same start, through the pipe, the right arm's fingers and gripper meet
// the pipe and the left arm's hand, and the insertion is rejected. Both fits are tried with as
// many samples as the standard one needs, so that the last sample of each starts alike.
TEST(BimanualAssemblyActions, AnInsertionPushedThroughThePipeIsRejected) {
  AssemblyFits tooDeep;
  tooDeep.bearingInPipe.seatHeight += 0.12;
  tooDeep.bearingInPipe.approach -= 0.12;
  const std::vector<std::string> arguments{"comau-left", "pipe", "comau-right", "bearing1"};
  // The reason of the last sample of assemblePipeBearing with `samples` samples and `fits`; empty
  // when it works.
  const auto lastReason = [&](int samples, const AssemblyFits& fits) {
    TampOptions options;
    options.handoverSamples = samples;
    GeometricAttachments attachments(bimanualWorld(), options);
    AssemblyAttachments assembly(attachments, fits);
    symbolic::ProcedureRegistry registry;
    assembly.registerProcedures(registry);
    std::size_t state = applied(attachments, "pickUp", {"comau-right", "bearing1"}, 0);
    state = applied(attachments, "move", {"comau-right"}, state);
    state = applied(attachments, "pickUp", {"comau-left", "pipe"}, state);
    const calls::AttachmentCall call(arguments, state);
    double reached = -1;
    if ((*registry.applicator("assemblePipeBearing"))({call.ids, &arguments, call.reads},
                                                      std::span(&reached, 1))) {
      return std::string();
    }
    return attachments.statistics().recentFailures.back();
  };
  const int kSamples = TampOptions{}.handoverSamples;
  int samples = 1;
  while (samples <= kSamples && !lastReason(samples, AssemblyFits{}).empty()) ++samples;
  ASSERT_LE(samples, kSamples);
  const std::string reason = lastReason(samples, tooDeep);
  EXPECT_NE(reason.find("insertion: "), std::string::npos) << reason;
  EXPECT_NE(reason.find("collides"), std::string::npos) << reason;
}

namespace {

// A search (depth-first by default) over Table 6.6's actions in `world` assembles the gearbox
// (Table 6.5's goal, checked by the symbolic validator); the plan ends with the parts where they
// fit and their contacts joined, both hands empty, nothing colliding. Its paths are certified by
// the planner; the verifier on the original meshes takes minutes here
// (TheVerifierAllowsTheJoinedContacts- AndNoOthers checks an insertion, the README's main job the
// whole plan).
void expectTheGearboxAssembled(const World& world, const std::string& search = "dfs") {
  SCOPED_TRACE("--search " + search);
  SolveOptions options;
  options.search.mode = search;
  options.search.limits.seconds = 300;
  options.verify = false;
  Solver solver(world,
                symbolic::loadContingent(exampleFile("bimanual-assembly/domain.pddl"),
                                         exampleFile("bimanual-assembly/problem.pddl")),
                options);
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.symbolic.valid) << result.verification.symbolic.message;
  std::vector<std::string> procedures;
  const ActionGeometry* last = nullptr;
  for (const std::vector<ActionGeometry>& node : result.geometry) {
    for (const ActionGeometry& action : node) {
      procedures.push_back(action.procedure);
      if (action.procedure == "assemblePipeTree") last = &action;
    }
  }
  for (const char* assembly : {"assembleBearingTree", "assemblePipeBearing", "assemblePipeTree"}) {
    EXPECT_EQ(std::count(procedures.begin(), procedures.end(), assembly), 1) << assembly;
  }
  ASSERT_NE(last, nullptr);
  const GeometricState& done = solver.attachments().map().state(last->to);
  EXPECT_TRUE(done.robots[0].heldObjects.empty());
  EXPECT_TRUE(done.robots[1].heldObjects.empty());
  EXPECT_EQ(done.joined.size(), 4u);
  const auto part = [&](const char* name) { return world.find(name)->index; };
  EXPECT_FALSE(done.areJoined(part("pipe"), part("tree")));
  EXPECT_FALSE(world.firstCollision(done));
}

}  // namespace

// The whole scenario at CI size, at the thesis's placements.
TEST(BimanualAssemblySolve, DepthFirstSearchAssemblesTheGearbox) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "a minute of swept-volume checks; the release build runs it";
#endif
  expectTheGearboxAssembled(bimanualWorld());
}

// The benchmark's extended criteria (examples/bimanual-assembly/scene-random.yaml): the parts at
// random places on the table, a crate and a post beside them. Two layouts of placement_seed; on
// the second, every search mode, and depth-first search with exact predicates on the original
// meshes.
TEST(BimanualAssemblySolve, PartsAtRandomPlacesAmongExtraObstaclesAreAssembled) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "seconds of swept-volume checks; the release build runs it";
#endif
  io::SceneDescription scene = readSceneFile(exampleFile("bimanual-assembly/scene-random.yaml"));
  WorldOptions options;
  options.cacheDirectory =
      std::filesystem::path(KABOUM_CLI).parent_path() / "test-decomposition-cache";
  const GeometricState written = bimanualWorld().initialState();
  for (const std::uint64_t seed : {2, 4}) {
    SCOPED_TRACE("placement seed " + std::to_string(seed));
    scene.settings.placementSeed = seed;
    World world(scene, options);
    for (const char* part : {"bearing1", "bearing2", "pipe", "tree"}) {
      const Vec3 at = world.scene().pose(id(part), world.initialState().placements).translation();
      EXPECT_GT(
          (at - bimanualWorld().scene().pose(id(part), written.placements).translation()).norm(),
          0.01)
          << part << " where scene.yaml has it";
    }
    ASSERT_TRUE(world.find("crate") && world.find("post"));
    if (seed == 2) {
      expectTheGearboxAssembled(world);
      continue;
    }
    for (const char* search : {"dfs", "bfs", "ids", "gbfs"})
      expectTheGearboxAssembled(world, search);
    const verify::ExactPredicates exact(world);
    world.usePredicates(&exact);
    expectTheGearboxAssembled(world);
  }
}

// The example's domain is accepted as it is; an assembly module with an argument fewer is one
// line naming the domain file, its line and the arity.
TEST(BimanualAssemblyActions, TheDomainDeclaresEachAssemblyEffectWithItsArguments) {
  const std::string domain = test::slurp(exampleFile("bimanual-assembly/domain.pddl"));
  const std::string problem = test::slurp(exampleFile("bimanual-assembly/problem.pddl"));
  const auto solverError = [&](const std::string& text) {
    try {
      const Solver solver(bimanualWorld(),
                          symbolic::parseContingent(text, "domain.pddl", problem, "problem.pddl"));
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(solverError(domain), "no error");
  std::string shortened = domain;
  const std::string module = "(pipebearing ?r - robot ?o - part ?r2 - robot ?o2 - part";
  shortened.replace(shortened.find(module), module.size(),
                    "(pipebearing ?r - robot ?o - part ?r2 - robot");
  const std::string call = "[pipebearing ?r ?o ?r2 ?o2]";
  shortened.replace(shortened.find(call), call.size(), "[pipebearing ?r ?o ?r2]");
  EXPECT_PRED_FORMAT2(::testing::IsSubstring,
                      "domain.pddl:20:5: module 'pipebearing': 'assemblePipeBearing' takes 4 "
                      "argument(s), not 3",
                      solverError(shortened));
}

}  // namespace kaboum::tamp
