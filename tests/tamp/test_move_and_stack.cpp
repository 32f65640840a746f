// Seed 003's MOVE AND STACK scenario with geometry (examples/move-and-stack): stacking that arises
// from placement — the tray holds two objects side by side, so the third goes on the can — every
// path certified and verified; an object with another one standing on it is not picked up.
#include <gtest/gtest.h>

#include <numeric>

#include "../support/test_support.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/tamp/solver.hpp"

namespace kaboum::tamp {

using namespace kaboum::testing;

namespace {

std::string example(const std::string& file) {
  return exampleFile("move-and-stack/" + file);
}

const World& moveAndStack() {
  static const World world(readSceneFile(example("scene.yaml")), {MeshPieces::Hulls, std::nullopt});
  return world;
}

std::size_t id(const std::string& name) {
  return moveAndStack().find(name).value().index;
}

// The geometric state the plan ends in (its last action's).
const GeometricState& lastState(const Solver& solver, const SolveResult& result) {
  std::size_t last = 0;
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) last = std::max(last, action.to);
  }
  return solver.attachments().map().state(last);
}

}  // namespace

// Table I's MOVE AND STACK goal: the blue bottle, the turquoise bottle and the can in the tray. The
// green bottle leaves the tray, the turquoise bottle and the can stand in it side by side, and the
// blue bottle ends on the can: no action of the domain says so.
TEST(MoveAndStack, TheBlueBottleIsStackedOnTheCanInTheTray) {
  SolveOptions options;
  options.search.mode = "astar";
  options.search.limits.seconds = 120;
  Solver solver(moveAndStack(),
                symbolic::loadContingent(example("domain.pddl"), example("problem-full.pddl")),
                options);
  const SolveResult result = solver.solve();
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.verification.passed()) << result.message;
  EXPECT_EQ(result.verification.collidingPaths, 0U);
  EXPECT_EQ(symbolic::measure(result.plan).actions, 8.0) << "four objects moved once each";
  const GeometricState& end = lastState(solver, result);
  const PlacementGeometry placements(moveAndStack());
  QueryScratch scratch = moveAndStack().scratch();
  for (const char* object : {"bluebottle", "turquoisebottle", "can"}) {
    EXPECT_TRUE(placements.isInside(end, id(object), id("tray"))) << object;
  }
  EXPECT_FALSE(placements.isInside(end, id("greenbottle"), id("tray")));
  const Support table{Support::Kind::Object, id("table")};
  EXPECT_EQ(placements.isOnSupportSurface(end, id("can"), scratch), table);
  EXPECT_EQ(placements.isOnSupportSurface(end, id("turquoisebottle"), scratch), table);
  EXPECT_EQ(placements.isOnSupportSurface(end, id("bluebottle"), scratch),
            (Support{Support::Kind::Object, id("can")}));
  EXPECT_EQ(placements.objectOnTop(end, id("can")), id("bluebottle"));
  EXPECT_FALSE(moveAndStack().firstCollision(end).has_value());
}

// The object below is not picked while another stands on it: pickUp fails at once, naming the
// object on top; the one on top is picked up.
TEST(MoveAndStack, AnObjectUnderAnotherIsNotPickedUp) {
  const World& world = moveAndStack();
  // The green bottle in the depot, the can in its place in the tray, the blue bottle on the can.
  GeometricState stacked = world.initialState();
  const auto pose = [&](const std::string& object) -> Pose& {
    return stacked.placements[world.scene().slot(id(object))].pose;
  };
  pose("can").translation() = pose("greenbottle").translation() + Vec3(0, 0, 0.005);
  pose("greenbottle").translation() += Vec3(0.095, -0.105, 0);
  pose("bluebottle").translation() = pose("can").translation() + Vec3(0, 0, 0.05 + 0.045 + 0.0016);
  ASSERT_FALSE(world.firstCollision(stacked).has_value());
  GeometricAttachments attachments(world);
  const std::size_t state = attachments.intern(stacked);
  symbolic::ProcedureRegistry registry;
  attachments.registerProcedures(registry);
  const auto pickUp = [&](const std::string& object) {
    const std::vector<std::string> names{"kr5", object};
    const std::vector<symbolic::ObjectId> ids{0, 1};
    const std::vector<double> reads{static_cast<double>(state)};
    std::vector<double> writes(1);
    return (*registry.applicator("pickUp"))({ids, &names, reads}, writes);
  };
  EXPECT_FALSE(pickUp("can"));
  ASSERT_FALSE(attachments.statistics().recentFailures.empty());
  EXPECT_EQ(attachments.statistics().recentFailures.back(),
            "pickUp(kr5, can): 'bluebottle' stands on the object");
  EXPECT_EQ(attachments.statistics().ikCalls, 0U) << "fails before sampling a grasp";
  EXPECT_TRUE(pickUp("bluebottle")) << attachments.statistics().recentFailures.back();
}

}  // namespace kaboum::tamp
