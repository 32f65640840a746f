// MoveIt problems (MotionBenchMaker) as worlds: each copied problem's start and goal are free, the
// SRDF's allowed pairs reach the robot's collision filter, and an arm reaching through the table
// collides; over the 300 shared problems when /work/shared is there.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/moveit_scene.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::world {

using namespace kaboum::testing;

namespace {

namespace fs = std::filesystem;

MoveItRobot panda() {
  return {dataFile("robots/panda/panda.urdf"),
          dataFile("robots/panda/panda.srdf"),
          "panda_arm",
          {"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4", "panda_joint5",
           "panda_joint6", "panda_joint7"}};
}

MotionProblem tablePick1() {
  const fs::path folder = dataFile("motionbenchmaker/table_pick_panda");
  return readMoveItProblem(folder / "scene0001.yaml", folder / "request0001.yaml", panda());
}

WorldOptions withPieces(MeshPieces pieces) {
  WorldOptions options;
  options.pieces = pieces;
  return options;
}

// The first collision of `world`'s robot at `configuration`, described ("free" if none).
std::string collisionAt(const World& world, const std::vector<double>& configuration) {
  GeometricState state = world.initialState();
  state.robots[0].configuration = configuration;
  const auto collision = world.firstCollision(state);
  return collision ? world.describe(*collision) : "free";
}

// Imports every problem of `folder` into a World with `pieces` and expects its start and goal
// free; prints the mean import and build times.
void expectEveryStartAndGoalFree(const fs::path& folder, MeshPieces pieces) {
  using Clock = std::chrono::steady_clock;
  double readSeconds = 0;
  double buildSeconds = 0;
  const std::vector<MoveItProblemFiles> problems = listMoveItProblems(folder);
  for (const MoveItProblemFiles& files : problems) {
    const Clock::time_point start = Clock::now();
    const MotionProblem problem = readMoveItProblem(files.scene, files.request, panda());
    const Clock::time_point read = Clock::now();
    const World world(problem.scene, withPieces(pieces));
    buildSeconds += std::chrono::duration<double>(Clock::now() - read).count();
    readSeconds += std::chrono::duration<double>(read - start).count();
    EXPECT_EQ(collisionAt(world, problem.start), "free") << problem.name << " start";
    EXPECT_EQ(collisionAt(world, problem.goal), "free") << problem.name << " goal";
  }
  const auto count = static_cast<double>(problems.size());
  std::cout << problems.size() << " problems of " << folder << ": import " << readSeconds / count
            << " s, World " << buildSeconds / count << " s per problem\n";
}

}  // namespace

TEST(MoveItWorld, EveryCopiedProblemStartsAndEndsFree) {
  expectEveryStartAndGoalFree(dataFile("motionbenchmaker"), MeshPieces::Hulls);
}

TEST(MoveItWorld, TablePickStartsAndEndsFreeWithDecomposedLinks) {
  const MotionProblem problem = tablePick1();
  const World world(problem.scene);  // the default: links decomposed at 1% of their diagonal
  EXPECT_EQ(collisionAt(world, problem.start), "free");
  EXPECT_EQ(collisionAt(world, problem.goal), "free");
}

TEST(MoveItWorld, AnArmReachingThroughTheTableCollidesWithAnObject) {
  const MotionProblem problem = tablePick1();
  const World world(problem.scene, withPieces(MeshPieces::Hulls));
  // Turned towards the table's centre (0.441, 1.026), leaning far forward: the flange ends below
  // the table top (z 0.179 to 0.219) inside its outline.
  std::vector<double> reaching = problem.start;
  reaching[0] = std::atan2(1.026, 0.441);
  reaching[1] = 1.6;
  reaching[3] = -0.2;
  const RobotModel& model = world.robots()[0].collision.model();
  std::vector<Pose> poses(model.links().size());
  model.linkPoses(reaching, poses);
  EXPECT_LT(poses[static_cast<std::size_t>(*model.findLink("panda_link8"))].translation().z(),
            0.15);
  GeometricState state = world.initialState();
  state.robots[0].configuration = reaching;
  const auto collision = world.firstCollision(state);
  ASSERT_TRUE(collision);
  EXPECT_EQ(collision->first.kind, Party::Kind::Robot);
  EXPECT_EQ(collision->second.kind, Party::Kind::Object);
}

TEST(MoveItWorld, TheSrdfsPairsReachTheCollisionFilter) {
  const MotionProblem problem = tablePick1();
  SceneDescription withoutPairs = problem.scene;
  withoutPairs.robots[0].allowedCollisions.clear();
  const World world(problem.scene, withPieces(MeshPieces::Hulls));
  const World unfiltered(withoutPairs, withPieces(MeshPieces::Hulls));
  // The hand and link 3 are far apart at the start; only the SRDF exempts them ("Never").
  const auto exempt = [](const World& w, const std::string& a, const std::string& b) {
    const RobotCollisionModel& robot = w.robots()[0].collision;
    const auto partOf = [&](const std::string& link) {
      for (std::size_t part = 0; part < robot.partCount(); ++part) {
        if (robot.part(part).link == robot.model().findLink(link)) return part;
      }
      ADD_FAILURE() << "no part for " << link;
      return std::size_t{0};
    };
    return robot.filter().allowed(partOf(a), partOf(b));
  };
  EXPECT_TRUE(exempt(world, "panda_hand", "panda_link3"));
  EXPECT_FALSE(exempt(unfiltered, "panda_hand", "panda_link3"));
  EXPECT_TRUE(exempt(world, "panda_link0", "panda_link4"));
  EXPECT_FALSE(exempt(world, "panda_link0", "panda_link7"));

  SceneDescription unknownLink = problem.scene;
  unknownLink.robots[0].allowedCollisions.push_back({"panda_link0", "panda_link9"});
  try {
    const World broken(unknownLink, withPieces(MeshPieces::Hulls));
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("unknown link 'panda_link9'"), std::string::npos)
        << error.what();
  }
}

TEST(MoveItWorld, EverySharedMotionBenchMakerProblemStartsAndEndsFree) {
  const auto shared = sharedDir();
  if (!shared || !fs::is_directory(*shared / "motionbenchmaker" / "problems")) {
    GTEST_SKIP() << "no shared MotionBenchMaker problems (EveryCopiedProblemStartsAndEndsFree "
                    "covers the copies)";
  }
  expectEveryStartAndGoalFree(*shared / "motionbenchmaker" / "problems", MeshPieces::Hulls);
}

}  // namespace kaboum::world
