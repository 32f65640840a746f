// The independent path verifier (docs/verify.md) on real scenes: free paths are free with a
// positive clearance; paths through the table, a thin plate, a held object's obstacle and the
// robot itself are caught with both parties named, also where only the interior of a segment
// collides (the planner's check at the waypoints says free); densification keeps its step bounds;
// bad paths are refused with one line naming the file and key.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/path_verifier.hpp"

namespace kaboum::verify {

using namespace kaboum::testing;

namespace {

constexpr double kDegree = std::numbers::pi / 180;

// One convex hull per mesh: fast to build; the reference does not use the planner's pieces.
WorldOptions hullPieces() {
  WorldOptions options;
  options.pieces = MeshPieces::Hulls;
  return options;
}

const World& twoArmsWorld() {
  static const World world(readSceneFile(exampleFile("scenes/two-arms-table.yaml")), hullPieces());
  return world;
}

const World& bimanualWorld() {
  static const World world(readSceneFile(exampleFile("scenes/bimanual-cell.yaml")), hullPieces());
  return world;
}

// The KR5 of dart-doc (its root frame has y up) at shoulder_yaw 0.5 beside a 2 mm thick plate
// (data/meshes/cube.off scaled) in the plane z = 0, which the arm crosses when the shoulder turns.
const World& kr5PlateWorld() {
  static const World world(
      parseSceneText("robots:\n"
                     "  - name: kr5\n"
                     "    urdf: \"" +
                         kr5Urdf() +
                         "\"\n"
                         "    home: {shoulder_yaw: 0.5}\n"
                         "objects:\n"
                         "  - name: plate\n"
                         "    geometry:\n"
                         "      mesh: {file: meshes/cube.off, scale: [0.35, 0.3, 0.002]}\n"
                         "      pose: {position: [-0.175, -0.15, -0.001]}\n"
                         "    pose: {position: [0.425, 0.2, 0]}\n",
                     "kr5-plate.yaml", dataFile("")),
      hullPieces());
  return world;
}

const ReferenceGeometry& referenceOf(const World& world) {
  static std::map<const World*, std::unique_ptr<ReferenceGeometry>> geometries;
  auto& geometry = geometries[&world];
  if (!geometry) geometry = std::make_unique<ReferenceGeometry>(world);
  return *geometry;
}

// Robot `robot`'s home configuration with the named joints set.
std::vector<double> configuration(const World& world, const std::string& robot,
                                  const std::map<std::string, double>& joints) {
  const WorldRobot& model = world.robots()[world.find(robot).value().index];
  std::vector<double> q = model.home;
  for (const auto& [name, value] : joints) {
    bool found = false;
    for (int v = 0; v < model.collision.model().dof(); ++v) {
      if (model.collision.model().variableJoint(v).name == name) {
        q[static_cast<std::size_t>(v)] = value;
        found = true;
      }
    }
    EXPECT_TRUE(found) << name;
  }
  return q;
}

io::PathFile pathOf(const std::string& robot, std::vector<std::vector<double>> waypoints) {
  io::PathFile path;
  path.robots = {robot};
  path.waypoints = std::move(waypoints);
  return path;
}

PathVerification verified(const World& world, const io::PathFile& file,
                          const VerifyOptions& options = {}) {
  return verifyPath(referenceOf(world), resolvePath(world, file, "path.json"), options);
}

// Whether some collision of `result` is between the parties described `first` and `second`.
bool collides(const PathVerification& result, const std::string& first, const std::string& second) {
  for (const PathCollision& collision : result.collisions) {
    const std::string a = describe(collision.first), b = describe(collision.second);
    if ((a == first && b == second) || (a == second && b == first)) return true;
  }
  return false;
}

std::string summary(const PathVerification& result) {
  std::string text = std::to_string(result.samples) + " samples";
  if (result.clearance) text += ", clearance " + std::to_string(result.clearance->distance);
  for (const PathCollision& collision : result.collisions) {
    text += "; " + describe(collision.first) + " / " + describe(collision.second);
  }
  return text;
}

// The state of `world` with robot 0 at `q`.
GeometricState stateAt(const World& world, const std::vector<double>& q) {
  GeometricState state = world.initialState();
  state.robots[0].configuration = q;
  return state;
}

TEST(PathVerifier, TwoArmsFreePathIsFreeWithAPositiveClearance) {
  const World& world = twoArmsWorld();
  const PathVerification result =
      verified(world, pathOf("twin", {configuration(world, "twin", {}),
                                      configuration(world, "twin", {{"left_j1", 0.5}})}));
  EXPECT_TRUE(result.collisionFree()) << summary(result);
  ASSERT_TRUE(result.clearance);
  EXPECT_GT(result.clearance->distance, 0.005);
  EXPECT_LT(result.clearance->distance, 0.2);
  EXPECT_GT(result.samples, 100u);
  EXPECT_GT(result.pairs, 0u);
}

TEST(PathVerifier, FindsTheTableBetweenTwoFreeWaypointsThatTheirCheckMisses) {
  const World& world = twoArmsWorld();
  const std::vector<double> from =
      configuration(world, "twin", {{"left_j2", 1.25}, {"left_j5", -2}});
  const std::vector<double> to = configuration(world, "twin", {{"left_j2", 1.25}, {"left_j5", 2}});
  // The planner's world and the reference both find each waypoint free.
  EXPECT_FALSE(world.firstCollision(stateAt(world, from)));
  EXPECT_FALSE(world.firstCollision(stateAt(world, to)));
  EXPECT_TRUE(verified(world, pathOf("twin", {from})).collisionFree());
  EXPECT_TRUE(verified(world, pathOf("twin", {to})).collisionFree());

  const PathVerification result = verified(world, pathOf("twin", {from, to}));
  ASSERT_EQ(result.collisions.size(), 1u) << summary(result);
  const PathCollision& collision = result.collisions[0];
  EXPECT_EQ(describe(collision.first), "robot 'twin' link 'left_flange'");
  EXPECT_EQ(describe(collision.second), "object 'table'");
  EXPECT_EQ(collision.from.segment, 0u);
  EXPECT_GT(collision.from.fraction, 0.5);
  EXPECT_LT(collision.to.fraction, 0.9);
  EXPECT_GT(collision.samples, 10u);
  ASSERT_TRUE(result.clearance);
  EXPECT_EQ(result.clearance->distance, 0.0);
}

TEST(PathVerifier, FindsAThinPlateCrossedByTheKr5OnItsOriginalMeshes) {
  const World& world = kr5PlateWorld();
  const PathVerification result =
      verified(world, pathOf("kr5", {configuration(world, "kr5", {{"shoulder_yaw", 0.5}}),
                                     configuration(world, "kr5", {{"shoulder_yaw", -0.5}})}));
  EXPECT_TRUE(collides(result, "robot 'kr5' link 'forearm'", "object 'plate'")) << summary(result);
  EXPECT_TRUE(collides(result, "robot 'kr5' link 'palm'", "object 'plate'")) << summary(result);
  // Turning away from the plate is free.
  const PathVerification away =
      verified(world, pathOf("kr5", {configuration(world, "kr5", {{"shoulder_yaw", 0.5}}),
                                     configuration(world, "kr5", {{"shoulder_yaw", 1.0}})}));
  EXPECT_TRUE(away.collisionFree()) << summary(away);
  ASSERT_TRUE(away.clearance);
  EXPECT_GT(away.clearance->distance, 0.0);
}

TEST(PathVerifier, FindsAHeldObjectHittingTheTable) {
  const World& world = twoArmsWorld();
  io::PathFile path = pathOf(
      "twin", {configuration(world, "twin", {}), configuration(world, "twin", {{"left_j2", 1.2}})});
  EXPECT_TRUE(verified(world, path).collisionFree());
  // The bottle centred on the tool centre point, 14 cm out of the flange: it reaches 11 cm further.
  Pose grasp = Pose::Identity();
  grasp.translation() = Vec3(0, 0, 0.14);
  path.held = {{"twin", "bottle", "left_flange", grasp}};
  const PathVerification result = verified(world, path);
  EXPECT_TRUE(collides(result, "object 'bottle' held by robot 'twin'", "object 'table'"))
      << summary(result);
  // The bottle overlaps the hand's fingers on the flange: that pair is not checked.
  for (const PathCollision& collision : result.collisions) {
    EXPECT_NE(describe(collision.first) + describe(collision.second),
              "robot 'twin' link 'left_flange'object 'bottle' held by robot 'twin'");
  }
}

TEST(PathVerifier, FindsTheRobotHittingItself) {
  const World& world = twoArmsWorld();
  const PathVerification result =
      verified(world, pathOf("twin", {configuration(world, "twin", {}),
                                      configuration(world, "twin", {{"left_j1", -2.0}})}));
  ASSERT_FALSE(result.collisionFree());
  const PathCollision& collision = result.collisions[0];
  EXPECT_EQ(collision.first.robot, "twin");
  EXPECT_EQ(collision.second.robot, "twin");
  EXPECT_TRUE(collision.first.object.empty() && collision.second.object.empty());
  EXPECT_TRUE(
      collides(result, "robot 'twin' link 'right_link2'", "robot 'twin' link 'left_flange'"))
      << summary(result);
}

TEST(PathVerifier, BimanualCellFreeAndThroughTheTabletopMesh) {
  const World& world = bimanualWorld();
  const PathVerification free = verified(
      world,
      pathOf("comau-left", {configuration(world, "comau-left", {}),
                            configuration(world, "comau-left", {{"joint0", 30 * kDegree}})}));
  EXPECT_TRUE(free.collisionFree()) << summary(free);
  ASSERT_TRUE(free.clearance);
  EXPECT_GT(free.clearance->distance, 0.0);

  const PathVerification down = verified(
      world,
      pathOf("comau-left", {configuration(world, "comau-left", {}),
                            configuration(world, "comau-left", {{"joint1", 60 * kDegree}})}));
  ASSERT_FALSE(down.collisionFree()) << summary(down);
  EXPECT_EQ(down.collisions[0].second.object, "tabletop") << summary(down);
  EXPECT_EQ(down.collisions[0].first.robot, "comau-left");
}

TEST(PathVerifier, DensificationKeepsItsStepBounds) {
  const World& world = twoArmsWorld();
  const std::vector<double> from = configuration(world, "twin", {});
  const std::vector<double> to = configuration(world, "twin", {{"left_j1", 0.5}});
  const ScenePath path = resolvePath(world, pathOf("twin", {from, to}), "path.json");

  // Joint steps alone: 0.5 rad in steps of at most 0.5°, i.e. 58 intervals.
  VerifyOptions jointsOnly;
  jointsOnly.toolStep = 10;
  EXPECT_EQ(densify(world, path, jointsOnly).size(), 59u);

  // With the 1 mm tool step: every link origin and tool centre point moves at most 1 mm.
  const VerifyOptions options;
  const std::vector<PathPlace> samples = densify(world, path, options);
  const RobotModel& model = world.robots()[0].collision.model();
  std::vector<std::pair<std::size_t, Vec3>> points;
  for (std::size_t link = 0; link < model.links().size(); ++link)
    points.emplace_back(link, Vec3::Zero());
  for (const ToolSpec& tool : world.description().robots[0].tools) {
    points.emplace_back(static_cast<std::size_t>(*model.findLink(tool.link)),
                        tool.tcp.translation());
  }
  const auto positions = [&](double fraction) {
    std::vector<double> q(from.size());
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = std::lerp(from[j], to[j], fraction);
    std::vector<Pose> poses(model.links().size());
    model.linkPoses(q, poses);
    std::vector<Vec3> result;
    for (const auto& [link, point] : points) result.push_back(poses[link] * point);
    return result;
  };
  double largestStep = 0, reach = 0;
  for (std::size_t s = 0; s + 1 < samples.size(); ++s) {
    EXPECT_LE((samples[s + 1].fraction - samples[s].fraction) * 0.5, options.jointStep + 1e-12);
    const std::vector<Vec3> a = positions(samples[s].fraction),
                            b = positions(samples[s + 1].fraction);
    for (std::size_t i = 0; i < a.size(); ++i)
      largestStep = std::max(largestStep, (b[i] - a[i]).norm());
  }
  const std::vector<Vec3> start = positions(0), end = positions(1);
  for (std::size_t i = 0; i < start.size(); ++i)
    reach = std::max(reach, (end[i] - start[i]).norm());
  EXPECT_LE(largestStep, options.toolStep);
  // Not much more than the fewest samples that could keep the bound (the chord of the farthest
  // point over the tool step).
  EXPECT_GE(samples.size(), static_cast<std::size_t>(reach / options.toolStep));
  EXPECT_LE(samples.size(), static_cast<std::size_t>(1.25 * reach / options.toolStep) + 2);
  EXPECT_EQ(samples.front().fraction, 0.0);
  EXPECT_EQ(samples.back().fraction, 1.0);
}

// resolvePath(world, path) fails with one line "path.json: KEY: ..." containing `what`.
void expectResolveError(const World& world, const io::PathFile& path, const std::string& key,
                        const std::string& what) {
  try {
    (void)resolvePath(world, path, "path.json");
    ADD_FAILURE() << "no error for " << key;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("path.json: " + key + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(PathVerifier, RefusesPathsThatDoNotFitTheScene) {
  const World& world = twoArmsWorld();
  const std::vector<double> home = configuration(world, "twin", {});
  expectResolveError(world, pathOf("kr5", {home}), "robots[0]", "no robot 'kr5' in the scene");
  expectResolveError(world, pathOf("table", {home}), "robots[0]", "no robot 'table'");
  expectResolveError(world, pathOf("twin", {home, {0, 1}}), "waypoints[1]",
                     "2 values, but robots 'twin' have 12 joints");
  expectResolveError(
      world, pathOf("twin", {home, configuration(world, "twin", {{"left_j2", 2.5}})}),
      "waypoints[1][2]", "joint 'left_j2' of robot 'twin' at 2.5 is outside its limits [-2, 2]");
  io::PathFile held = pathOf("twin", {home});
  held.held = {{"twin", "table", "left_flange", Pose::Identity()}};
  expectResolveError(world, held, "held[0].object", "object 'table' is not movable");
  held.held = {{"twin", "bottle", "left_hand", Pose::Identity()}};
  expectResolveError(world, held, "held[0].link", "robot 'twin' has no link 'left_hand'");
  held.held = {{"twin", "bottle", "left_flange", Pose::Identity()},
               {"twin", "bottle", "right_flange", Pose::Identity()}};
  expectResolveError(world, held, "held[1].object", "object 'bottle' is already held (held[0])");
}

}  // namespace

}  // namespace kaboum::verify
