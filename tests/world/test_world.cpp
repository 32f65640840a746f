// The world of the integrated planner: scene files turned into collision geometry, the geometric
// state, its collision queries and load-time validation, and the `kaboum scene` verb.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <unordered_set>

#include "../support/allocation_counter.hpp"
#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/world/placement.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::world {

using namespace kaboum::testing;

namespace {

std::string twoArmsTable() {
  return exampleFile("scenes/two-arms-table.yaml");
}

const World& twoArmsWorld() {
  static const World world(readSceneFile(twoArmsTable()));
  return world;
}

std::size_t objectId(const World& world, const std::string& name) {
  return world.find(name).value().index;
}

Party object(const World& world, const std::string& name) {
  return {Party::Kind::Object, objectId(world, name)};
}

// The world pose of `link` of robot 0 in `state`.
Pose linkPose(const World& world, const GeometricState& state, int link) {
  const RobotCollisionModel& robot = world.robots()[0].collision;
  std::vector<Pose> poses(robot.model().links().size());
  robot.model().linkPoses(state.robots[0].configuration, poses);
  return robot.basePose() * poses[static_cast<std::size_t>(link)];
}

// The two-arms-table scene with `objects` replacing its objects section.
SceneDescription twoArmsWith(const std::string& objects) {
  std::string text = test::slurp(twoArmsTable());
  text = text.substr(0, text.find("objects:")) + "objects:\n" + objects;
  return parseSceneText(text, "scene.yaml", exampleFile("scenes"));
}

std::string loadError(const SceneDescription& scene) {
  try {
    const World world(scene, {MeshPieces::Hulls, std::nullopt});
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

TEST(World, BuildsTheTwoArmsTableFreeAtItsInitialState) {
  const World& world = twoArmsWorld();
  ASSERT_EQ(world.robots().size(), 1U);
  EXPECT_EQ(world.robots()[0].collision.model().dof(), 12);
  EXPECT_EQ(world.scene().size(), 3U);
  EXPECT_EQ(world.scene().movableCount(), 2U);
  EXPECT_EQ(world.find("TWIN")->kind, NamedEntity::Kind::Robot);
  EXPECT_EQ(world.find("crate")->kind, NamedEntity::Kind::Object);
  EXPECT_EQ(world.find("shelf")->kind, NamedEntity::Kind::Location);
  EXPECT_FALSE(world.find("nothing"));
  const auto collision = world.firstCollision(world.initialState());
  EXPECT_FALSE(collision) << world.describe(*collision);
  // The bottle and crate stand on the table in the file: raised off it by at most the bound.
  for (const char* name : {"bottle", "crate"}) {
    const double lift = world.restingLift()[objectId(world, name)];
    EXPECT_GT(lift, 0) << name;
    EXPECT_LE(lift, 0.02) << name;
  }
  EXPECT_EQ(world.restingLift()[objectId(world, "table")], 0);
  EXPECT_GT(world.preprocessingSeconds(), 0);
}

TEST(World, HandShapesArePartsOfTheToolLink) {
  const World& world = twoArmsWorld();
  const RobotCollisionModel& robot = world.robots()[0].collision;
  const int flange = robot.model().findLink("left_flange").value();
  for (std::size_t i = 0; i < robot.partCount(); ++i) {
    if (robot.part(i).link != flange) continue;
    // The flange box (z 0.02..0.10) and the two fingers (z 0.10..0.16) in the link frame.
    EXPECT_EQ(robot.part(i).body->pieceCount(), 3U);
    EXPECT_NEAR(robot.part(i).body->bounds().box.hi.z(), 0.16, 1e-9);
    return;
  }
  FAIL() << "no part on the left flange";
}

TEST(World, BuildsTheBimanualCellFreeAtItsInitialState) {
  const World world(readSceneFile(exampleFile("scenes/bimanual-cell.yaml")));
  ASSERT_EQ(world.robots().size(), 2U);
  EXPECT_EQ(world.scene().movableCount(), 2U);
  const auto collision = world.firstCollision(world.initialState());
  EXPECT_FALSE(collision) << world.describe(*collision);
  std::cout << "bimanual-cell: " << world.preprocessingSeconds() << " s\n";
}

TEST(World, AnObjectMovedIntoTheTableCollidesNamingBoth) {
  const World& world = twoArmsWorld();
  GeometricState state = world.initialState();
  state.placements[world.scene().slot(objectId(world, "bottle"))].pose.translation() =
      Vec3(0.55, 0.1, 0.70);
  const auto collision = world.firstCollision(state);
  ASSERT_TRUE(collision);
  EXPECT_EQ(collision->first, object(world, "bottle"));
  EXPECT_EQ(collision->second, object(world, "table"));
  EXPECT_EQ(world.describe(*collision), "object 'bottle' collides with object 'table'");
}

TEST(World, AHeldObjectMovesWithItsLink) {
  const World& world = twoArmsWorld();
  const int flange = world.robots()[0].collision.model().findLink("left_flange").value();
  const std::size_t bottle = objectId(world, "bottle");
  const Pose atTcp(Eigen::Translation3d(0, 0, 0.14));

  // Held at the tool centre point it overlaps the hand, which is not checked against it...
  GeometricState holding = world.initialState();
  world.hold(holding, 0, flange, bottle, atTcp);
  EXPECT_FALSE(holding.placements[world.scene().slot(bottle)].present);
  auto collision = world.firstCollision(holding);
  EXPECT_FALSE(collision) << world.describe(*collision);
  // ...but placed there in the scene, it collides with the robot.
  GeometricState placed = world.initialState();
  placed.placements[world.scene().slot(bottle)].pose = linkPose(world, placed, flange) * atTcp;
  collision = world.firstCollision(placed);
  ASSERT_TRUE(collision);
  EXPECT_EQ(collision->first.kind, Party::Kind::Robot);
  EXPECT_EQ(collision->first.index, 0u);
  EXPECT_EQ(collision->first.link, flange);
  EXPECT_EQ(collision->second, object(world, "bottle"));

  // Held where the table is at home, it collides with the table; turning the arm takes it away.
  const Pose table = world.scene().pose(objectId(world, "table"), holding.placements);
  GeometricState inTable = world.initialState();
  world.hold(inTable, 0, flange, bottle, inFrameOf(linkPose(world, inTable, flange), table));
  collision = world.firstCollision(inTable);
  ASSERT_TRUE(collision);
  EXPECT_EQ(collision->first, object(world, "bottle"));
  EXPECT_EQ(collision->second, object(world, "table"));
  GeometricState turned = inTable;
  turned.robots[0].configuration[0] += 1.5;  // left_j1
  collision = world.firstCollision(turned);
  EXPECT_FALSE(collision && collision->second == object(world, "table"))
      << world.describe(*collision);

  EXPECT_THROW(world.hold(inTable, 0, flange, bottle, atTcp), std::invalid_argument);
  EXPECT_THROW(world.hold(inTable, 0, flange, objectId(world, "table"), atTcp),
               std::invalid_argument);
}

TEST(World, StatesCompareAndHashByValue) {
  const World& world = twoArmsWorld();
  const GeometricState initial = world.initialState();
  const GeometricState copy = initial;
  EXPECT_EQ(copy, initial);
  EXPECT_EQ(std::hash<GeometricState>{}(copy), std::hash<GeometricState>{}(initial));

  GeometricState moved = initial;
  moved.robots[0].configuration[3] += 0.1;
  GeometricState displaced = initial;
  displaced.placements[0].pose.translation().x() += 0.01;
  GeometricState holding = initial;
  world.hold(holding, 0, world.robots()[0].collision.model().findLink("right_flange").value(),
             objectId(world, "crate"), Pose::Identity());
  for (const GeometricState* changed : {&moved, &displaced, &holding}) {
    EXPECT_FALSE(*changed == initial);
  }
  const std::unordered_set<GeometricState> states{initial, copy, moved, displaced, holding};
  EXPECT_EQ(states.size(), 4U);
}

TEST(World, QueriesAllocateNothing) {
  const World& world = twoArmsWorld();
  GeometricState state = world.initialState();
  world.hold(state, 0, world.robots()[0].collision.model().findLink("left_flange").value(),
             objectId(world, "bottle"), Pose(Eigen::Translation3d(0, 0, 0.14)));
  QueryScratch scratch = world.scratch();
  const long allocations = test::allocationsDuring([&] {
    for (int i = 0; i < 100; ++i) {
      state.robots[0].configuration[0] = 0.01 * i;
      (void)world.firstCollision(state, scratch);
    }
  });
  EXPECT_EQ(allocations, 0);
}

// The placement predicates on the example scene allocate nothing per call (placement.hpp).
TEST(World, PlacementPredicatesAllocateNothing) {
  const World& world = twoArmsWorld();
  const PlacementGeometry placements(world);
  const GeometricState state = world.initialState();
  QueryScratch scratch = world.scratch();
  const std::size_t crate = objectId(world, "crate");
  const std::size_t goal = world.find("goal").value().index;
  FreeSpaceOptions options;
  std::optional<Support> support;
  FreeSpace found;
  bool inside = false;
  const long allocations = test::allocationsDuring([&] {
    for (const SearchStrategy strategy :
         {SearchStrategy::Linear, SearchStrategy::Quadtree, SearchStrategy::Random}) {
      options.strategy = strategy;
      found = placements.freeSpaceFound(state, crate, goal, options, scratch);
    }
    support = placements.isOnSupportSurface(state, crate, scratch);
    inside = placements.isInside(state, crate, goal);
  });
  EXPECT_EQ(allocations, 0);
  ASSERT_TRUE(found.pose);
  EXPECT_TRUE(placements.isInside(crate, *found.pose, goal));
  EXPECT_EQ(support, (Support{Support::Kind::Object, objectId(world, "table")}));
  EXPECT_FALSE(inside) << "the crate starts beside the goal region (y -0.1; it ends at -0.15)";
}

TEST(World, RejectsAStateOfTheWrongShape) {
  const World& world = twoArmsWorld();
  GeometricState state = world.initialState();
  state.robots[0].configuration.pop_back();
  EXPECT_THROW((void)world.firstCollision(state), std::invalid_argument);
  state = world.initialState();
  state.placements.pop_back();
  EXPECT_THROW((void)world.firstCollision(state), std::invalid_argument);
}

TEST(World, TwoObjectsStartingInCollisionAreNamed) {
  const std::string error =
      loadError(twoArmsWith("  - name: table\n"
                            "    geometry: {box: {size: [0.5, 1.0, 0.04]}}\n"
                            "    pose: {position: [0.55, 0, 0.70]}\n"
                            "  - name: brick\n"
                            "    geometry: {box: {size: [0.1, 0.1, 0.1]}}\n"
                            "    pose: {position: [0.55, 0, 0.72]}\n"
                            "    movable: true\n"));
  EXPECT_NE(error.find("scene.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("objects[1].pose"), std::string::npos) << error;
  EXPECT_NE(error.find("object 'brick' starts in collision with object 'table'"), std::string::npos)
      << error;
  // The brick's bottom is 50 mm below the table's top.
  const std::size_t depth = error.find(" mm deep: raised by that much it would be free)");
  ASSERT_NE(depth, std::string::npos) << error;
  const double millimetres = std::stod(error.substr(error.rfind('(', depth) + 1));
  EXPECT_NEAR(millimetres, 50.0, 0.15) << error;
}

// A stack written touching (each block's bottom on the top below) loads: the lowest block is
// raised off the table first, then each one off the block under it, every one left resting on it.
TEST(World, AStackWrittenTouchingRisesAsAWhole) {
  std::string objects =
      "  - name: table\n"
      "    geometry: {box: {size: [0.5, 1.0, 0.04]}}\n"
      "    pose: {position: [0.55, 0, 0.70]}\n";
  // Listed top first, so that the order of the file is not the order of the stack.
  for (int level = 2; level >= 0; --level) {
    objects += "  - name: block" + std::to_string(level) +
               "\n"
               "    geometry: {box: {size: [0.06, 0.06, 0.04]}}\n"
               "    pose: {position: [0.55, 0, " +
               std::to_string(0.74 + 0.04 * level) +
               "]}\n"
               "    movable: true\n";
  }
  const World world(twoArmsWith(objects), {MeshPieces::Hulls, std::nullopt});
  const PlacementGeometry placements(world);
  QueryScratch scratch = world.scratch();
  const GeometricState state = world.initialState();
  EXPECT_FALSE(world.firstCollision(state));
  const std::vector<std::string> below{"table", "block0", "block1"};
  for (int level = 0; level < 3; ++level) {
    const std::size_t block = objectId(world, "block" + std::to_string(level));
    EXPECT_GT(world.restingLift()[block], 0) << level;
    const std::optional<Support> support = placements.isOnSupportSurface(state, block, scratch);
    ASSERT_TRUE(support) << level;
    EXPECT_EQ(support->index, objectId(world, below[static_cast<std::size_t>(level)])) << level;
  }
}

TEST(World, ARobotCollidingAtHomeIsNamed) {
  const std::string error =
      loadError(twoArmsWith("  - name: pillar\n"
                            "    geometry: {box: {size: [0.1, 0.1, 2.0]}}\n"
                            "    pose: {position: [0, 0, 1.0]}\n"));
  EXPECT_NE(error.find("scene.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("robot 'twin' link 'torso' at home collides with object 'pillar'"),
            std::string::npos)
      << error;
}

TEST(SceneCli, PrintsTheWorldOfAScene) {
  const test::ScratchDir dir;
  const test::CliResult result = test::runCli(dir, "scene --no-cache '" + twoArmsTable() + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  for (const char* line : {"twin: 12 DOF", "table: static, 1 piece(s), 8 vertices",
                           "bottle: movable", "shelf: box, support surface",
                           "epsilon:       1% of each body", "initial state: collision-free"}) {
    EXPECT_NE(result.out.find(line), std::string::npos) << line << "\n" << result.out;
  }
  const test::CliResult quiet =
      test::runCli(dir, "scene --no-cache --quiet '" + twoArmsTable() + "'");
  EXPECT_EQ(quiet.out, "initial state: collision-free\n");
}

TEST(SceneCli, PrintsJson) {
  const test::ScratchDir dir;
  const test::CliResult result =
      test::runCli(dir, "scene --no-cache --json '" + twoArmsTable() + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  EXPECT_EQ(report["robots"][0]["name"], "twin");
  EXPECT_EQ(report["robots"][0]["dof"], 12);
  EXPECT_EQ(report["objects"].size(), 3U);
  EXPECT_EQ(report["objects"][1]["movable"], true);
  EXPECT_EQ(report["locations"][1]["support_surface"], true);
  EXPECT_EQ(report["epsilon_relative"], true);
  EXPECT_EQ(report["initial_state_collision_free"], true);
}

TEST(SceneCli, BadScenesExitWithTwo) {
  const test::ScratchDir dir;
  test::CliResult result = test::runCli(dir, "scene --no-cache '" + dir.file("missing.yaml") + "'");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_NE(result.err.find("missing.yaml"), std::string::npos) << result.err;

  std::string text = test::slurp(twoArmsTable());
  text.replace(text.find("../robots/two-arm.urdf"), 22, exampleFile("robots/two-arm.urdf"));
  text.replace(text.find("../../data/meshes/cube.off"), 26, dataFile("meshes/cube.off"));
  text.replace(text.find("locations:"), 0,
               "  - name: pillar\n    geometry: {box: {size: [0.1, 0.1, 2.0]}}\n\n");
  const std::string path = dir.write("colliding.yaml", text);
  result = test::runCli(dir, "scene --no-cache '" + path + "'");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_NE(result.err.find("robot 'twin' link 'torso' at home collides with object 'pillar'"),
            std::string::npos)
      << result.err;
}

}  // namespace

}  // namespace kaboum::world
