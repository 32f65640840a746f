// Certified motion: the state checker and swept-volume motion validator on worlds of real robots
// (KUKA KR5 from dart-doc, the two-arm example, the Comau pair, a mobile manipulator), straight
// and OMPL-planned paths, transfer paths holding objects, Cartesian motions, honest failures,
// determinism, and no allocation per check.
#include <gtest/gtest.h>

#include <atomic>
#include <random>

#include "../support/allocation_counter.hpp"
#include "../support/test_support.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/motion/cartesian_motion.hpp"
#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/motion/world_checkers.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/path_verifier.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::motion {

using namespace kaboum::testing;

namespace {

// Link meshes as convex hulls: the worlds build in milliseconds, and certification holds for any
// bounding geometry.
const WorldOptions kHulls{MeshPieces::Hulls, std::nullopt};

const World& kr5World() {
  static const World world(readSceneFile(exampleFile("scenes/kr5-cell.yaml")), kHulls);
  return world;
}

const World& twoArmsWorld() {
  static const World world(readSceneFile(exampleFile("scenes/two-arms-table.yaml")), kHulls);
  return world;
}

const World& comauWorld() {
  static const World world(readSceneFile(exampleFile("scenes/bimanual-cell.yaml")), kHulls);
  return world;
}

std::size_t robotIndex(const World& world, const std::string& name) {
  return world.find(name).value().index;
}

MotionGroup groupOf(const World& world, const std::vector<std::string>& robots) {
  std::vector<std::size_t> indices;
  for (const std::string& name : robots) indices.push_back(robotIndex(world, name));
  return {world, world.initialState(), indices};
}

// `q` with coordinate `i` set to `value`.
std::vector<double> with(std::vector<double> q, std::size_t i, double value) {
  q[i] = value;
  return q;
}

constexpr double kDegree = std::numbers::pi / 180;

// Every configuration of every segment at joint steps of at most `step` is free for the state
// checker (a discrete check much finer than the planner's steps, on the same bounded geometry).
void expectDenselyFree(const MotionGroup& group, const Waypoints& path,
                       double step = 0.25 * kDegree) {
  WorldStateChecker states(group, 0.0);
  for (std::size_t s = 0; s + 1 < path.size(); ++s) {
    double largest = 0;
    for (std::size_t i = 0; i < path[s].size(); ++i) {
      largest = std::max(largest, std::abs(path[s + 1][i] - path[s][i]));
    }
    const int samples = std::max(1, static_cast<int>(std::ceil(largest / step)));
    std::vector<double> q(path[s].size());
    for (int k = 0; k <= samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      for (std::size_t i = 0; i < q.size(); ++i)
        q[i] = path[s][i] + t * (path[s + 1][i] - path[s][i]);
      const auto collision = states.firstCollision(q);
      ASSERT_FALSE(collision) << "segment " << s << " at t=" << t << ": "
                              << group.world().describe(*collision);
    }
  }
}

// Each segment of a solved query's path certified again by a fresh validator at the query's ε.
void expectCertified(const MotionGroup& group, const MotionResult& result) {
  ASSERT_GT(result.statistics.sweepEpsilon, 0.0);
  SweptMotionValidator motions(group, result.statistics.sweepEpsilon);
  for (std::size_t s = 0; s + 1 < result.path.size(); ++s) {
    EXPECT_TRUE(motions.isValid(result.path[s], result.path[s + 1])) << "segment " << s;
  }
}

TEST(MotionPlanner, TakesTheStraightSegmentWhenItsSweptVolumeIsFree) {
  const MotionGroup group = groupOf(twoArmsWorld(), {"twin"});
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(with(start, 0, 60 * kDegree), 1, -60 * kDegree);
  const MotionResult result = planMotion(group, start, goal);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_TRUE(result.statistics.straight);
  ASSERT_EQ(result.path.size(), 2u);
  EXPECT_EQ(result.path.front(), start);
  EXPECT_EQ(result.path.back(), goal);
  EXPECT_EQ(result.statistics.checks.motionChecks, 1u);
  EXPECT_EQ(result.statistics.planningSeconds, 0.0);
}

TEST(MotionPlanner, PlansAroundThePoleWithCertifiedSegmentsThatAreDenselyFree) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(start, 0, -60 * kDegree);
  SweptMotionValidator motions(group, 0.005);
  ASSERT_FALSE(motions.isValid(start, goal)) << "the straight motion should sweep through the pole";
  const MotionResult result = planMotion(group, start, goal);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_FALSE(result.statistics.straight);
  EXPECT_EQ(result.path.front(), start);
  EXPECT_EQ(result.path.back(), goal);
  EXPECT_GE(result.path.size(), 3u);
  EXPECT_LE(result.statistics.length, result.statistics.plannedLength + 1e-12);
  EXPECT_NEAR(result.statistics.length, pathLength(result.path), 1e-12);
  EXPECT_GT(result.statistics.checks.motionChecks, 0u);
  expectCertified(group, result);
  expectDenselyFree(group, result.path);
}

// A joint held still keeps its value along a planned path, through the planner's samples too.
TEST(MotionPlanner, AJointHeldStillKeepsItsValueAlongThePath) {
  MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> start = group.configuration(group.context());
  group.holdStill(0, 5);
  EXPECT_EQ(group.lower()[5], start[5]);
  EXPECT_EQ(group.upper()[5], start[5]);
  const MotionResult result = planMotion(group, start, with(start, 0, -60 * kDegree));
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  ASSERT_GE(result.path.size(), 3u) << "planned around the pole, not straight";
  for (const std::vector<double>& q : result.path) EXPECT_EQ(q[5], start[5]);
  const MotionResult moved = planMotion(group, start, with(start, 5, start[5] + 0.5));
  EXPECT_EQ(moved.status, PlannerStatus::InvalidGoal) << "the goal moves the held joint";
  EXPECT_THROW(group.holdStill(0, 6), std::out_of_range);
  EXPECT_THROW(group.holdStill(1, 0), std::out_of_range);
}

TEST(MotionPlanner, TheSameSeedGivesTheSamePath) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(start, 0, -60 * kDegree);
  MotionOptions options;
  options.seed = 11;
  const MotionResult first = planMotion(group, start, goal, options);
  const MotionResult second = planMotion(group, start, goal, options);
  ASSERT_EQ(first.status, PlannerStatus::Solved);
  EXPECT_EQ(first.path, second.path);
  options.seed = 12;
  const MotionResult other = planMotion(group, start, goal, options);
  ASSERT_EQ(other.status, PlannerStatus::Solved);
  EXPECT_NE(first.path, other.path);
}

TEST(MotionPlanner, EveryPlannerByNameReturnsACertifiedPath) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(start, 0, -60 * kDegree);
  for (const std::string& name : motionPlannerNames()) {
    MotionOptions options;
    options.planner = name;
    options.timeLimit = 2;  // the optimizing RRT* refines its path until the limit
    const MotionResult result = planMotion(group, start, goal, options);
    ASSERT_EQ(result.status, PlannerStatus::Solved) << name << ": " << result.message;
    expectCertified(group, result);
  }
  MotionOptions unknown;
  unknown.planner = "teleport";
  EXPECT_THROW((void)planMotion(group, start, goal, unknown), std::invalid_argument);
}

TEST(MotionPlanner, AStartOrGoalInCollisionIsNamed) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> home = group.configuration(group.context());
  const std::vector<double> intoPole = with(home, 0, 0.0);  // the arm stretched through the pole
  const MotionResult badStart = planMotion(group, intoPole, home);
  EXPECT_EQ(badStart.status, PlannerStatus::InvalidStart);
  EXPECT_EQ(badStart.message, "start: robot 'kr5' link 'forearm' collides with object 'pole'");
  EXPECT_TRUE(badStart.path.empty());
  const MotionResult badGoal = planMotion(group, home, intoPole);
  EXPECT_EQ(badGoal.status, PlannerStatus::InvalidGoal);
  EXPECT_EQ(badGoal.message, "goal: robot 'kr5' link 'forearm' collides with object 'pole'");
}

TEST(MotionPlanner, AGoalCloserThanTheSweepEpsilonIsReachedAtASmallerOne) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> home = group.configuration(group.context());
  // Turn towards the pole until the arm is free but within the 5 mm sweep ε of it.
  std::vector<double> goal = home;
  while (!configurationProblem(group, goal, 0.005)) goal[0] -= 0.001;
  ASSERT_FALSE(configurationProblem(group, goal, 0.0));
  const MotionResult result = planMotion(group, home, goal);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_LT(result.statistics.sweepEpsilon, 0.005);
  EXPECT_GE(result.statistics.sweepEpsilon, 0.005 / 16);
  expectCertified(group, result);
}

TEST(MotionPlanner, AJointOutsideItsLimitsIsNamed) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> home = group.configuration(group.context());
  const MotionResult result = planMotion(group, home, with(home, 1, 3.0));
  EXPECT_EQ(result.status, PlannerStatus::InvalidGoal);
  EXPECT_EQ(result.message,
            "goal: shoulder_pitch of robot 'kr5' is 3, outside its limits [-1.74533, 2.35619]");
  EXPECT_THROW((void)planMotion(group, home, std::vector<double>(5, 0.0)), std::invalid_argument);
}

TEST(MotionPlanner, StopsAtTheTimeLimitAndTheCancelFlag) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(start, 0, -60 * kDegree);
  MotionOptions options;
  options.timeLimit = 1e-9;
  const MotionResult late = planMotion(group, start, goal, options);
  EXPECT_EQ(late.status, PlannerStatus::TimeLimit);
  EXPECT_TRUE(late.path.empty());
  const std::atomic<bool> cancel{true};
  options.timeLimit = 10;
  options.cancel = &cancel;
  EXPECT_EQ(planMotion(group, start, goal, options).status, PlannerStatus::Cancelled);
}

ObjectSpec boxObject(const std::string& name, const Vec3& size, const Vec3& position,
                     bool movable) {
  ObjectSpec object;
  object.name = name;
  object.movable = movable;
  object.geometry.shape.kind = CollisionShape::Kind::Box;
  object.geometry.shape.size = size;
  object.pose = Pose::Identity();
  object.pose.translation() = position;
  return object;
}

TEST(MotionPlanner, AHeldObjectIsCarriedAndCertifiedWithTheArm) {
  // A bar held upright above the KR5's palm sweeps a post that the arm alone passes under.
  SceneDescription scene = readSceneFile(exampleFile("scenes/kr5-cell.yaml"));
  scene.objects.push_back(boxObject("bar", {0.04, 0.04, 0.3}, {-0.5, 0.5, 0.2}, true));
  Pose grasp = Pose::Identity();
  grasp.translation() = Vec3(0, 0, 0.25);  // in the palm frame, whose z axis points up here
  const World plain(scene, kHulls);
  const RobotCollisionModel& robot = plain.robots()[0].collision;
  const int palm = robot.model().findLink("palm").value();
  std::vector<double> start = plain.robots()[0].home;  // shoulder_yaw 60°
  const std::vector<double> goal = with(start, 0, 20 * kDegree);
  std::vector<Pose> poses(robot.model().links().size());
  robot.model().linkPoses(with(start, 0, 40 * kDegree), poses);
  const Vec3 barMiddle =
      robot.basePose() * poses[static_cast<std::size_t>(palm)] * grasp.translation();
  scene.objects.push_back(boxObject("post", {0.04, 0.04, 0.04}, barMiddle, false));
  const World world(std::move(scene), kHulls);
  const MotionGroup armAlone(world, world.initialState(), {0});
  GeometricState context = world.initialState();
  world.hold(context, 0, palm, world.find("bar").value().index, grasp);
  const MotionGroup holding(world, context, {0});

  SweptMotionValidator withoutBar(armAlone, 0.005), withBar(holding, 0.005);
  EXPECT_TRUE(withoutBar.isValid(start, goal));
  EXPECT_FALSE(withBar.isValid(start, goal));
  const MotionResult result = planMotion(holding, start, goal);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_FALSE(result.statistics.straight);
  expectCertified(holding, result);
  expectDenselyFree(holding, result.path);
}

TEST(MotionPlanner, TwoArmsMoveTogetherWithoutMeetingEachOther) {
  const MotionGroup group = groupOf(comauWorld(), {"comau-left", "comau-right"});
  ASSERT_EQ(group.dimension(), 14u);  // 6 joints and 2 fingers, 6 joints
  const std::vector<double> start = group.configuration(group.context());
  // Both arms swing towards the middle of the table, where the straight motion makes them meet.
  std::vector<double> goal = start;
  goal[0] = -40 * kDegree;
  goal[8] = 60 * kDegree;
  const MotionResult result = planMotion(group, start, goal);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  expectCertified(group, result);
  expectDenselyFree(group, result.path, 0.5 * kDegree);
}

// The benchmark's Comau pair (examples/scenes/comau-pair.yaml: the URDFs with the link meshes of
// data/robots/comau):
// both arms move at once between random free configurations drawn with the scene's seed, each goal
// within 0.4 rad per joint of its start (so that the verifier's dense replay on the original
// meshes stays short); every path is certified and free for the verifier.
TEST(MotionPlanner, TheComauPairMovesBothArmsBetweenRandomFreeConfigurations) {
  const World world(readSceneFile(exampleFile("scenes/comau-pair.yaml")), kHulls);
  ASSERT_EQ(world.robots().size(), 2u);
  for (const WorldRobot& robot : world.robots()) EXPECT_GE(robot.collision.partCount(), 7u);
  ASSERT_FALSE(world.firstCollision(world.initialState()));
  const MotionGroup group = groupOf(world, {"comau-left", "comau-right"});
  const verify::ReferenceGeometry reference(world);
  const double clearance = world.description().settings.sweepEpsilon;
  std::mt19937_64 rng(world.description().settings.seed);
  for (int query = 0; query < 3; ++query) {
    const std::optional<std::vector<double>> start = randomFreeConfiguration(group, clearance, rng);
    ASSERT_TRUE(start);
    std::optional<std::vector<double>> goal;
    while (!goal) {
      std::vector<double> q = *start;
      for (std::size_t i = 0; i < q.size(); ++i) {
        q[i] = std::clamp(q[i] + 0.8 * (kinematics::uniformUnit(rng) - 0.5), group.lower()[i],
                          group.upper()[i]);
      }
      if (!configurationProblem(group, q, clearance)) goal = std::move(q);
    }
    const MotionResult result = planMotion(group, *start, *goal);
    ASSERT_EQ(result.status, PlannerStatus::Solved) << "query " << query << ": " << result.message;
    expectCertified(group, result);
    EXPECT_TRUE(
        verify::verifyPath(reference, {{0, 1}, result.path, {}, std::nullopt}).collisionFree())
        << "query " << query;
  }
}

TEST(MotionPlanner, AMobileBaseDrivesAroundAnObstacle) {
  const test::ScratchDir dir;
  const std::string scene = R"(robots:
  - name: rover
    urdf: )" + exampleFile("robots/mobile-5axis.urdf") +
                            R"(
    home: {drive/x: -1.0, shoulder: 0.3, elbow: 1.2}
objects:
  - name: wall
    geometry: {box: {size: [0.2, 1.0, 0.6]}}
    pose: {position: [0, 0, 0.3]}
)";
  const World world(readSceneFile(dir.write("rover.yaml", scene)), kHulls);
  const MotionGroup group(world, world.initialState(), {0});
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(start, 0, 1.0);  // drive_x from -1 to 1 through the wall
  const MotionResult result = planMotion(group, start, goal);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_FALSE(result.statistics.straight);
  expectCertified(group, result);
  expectDenselyFree(group, result.path, 0.005);
}

// The 7-DOF Barrett WAM (dart-doc), whose arm no closed form fits: planning around a post, and a
// Cartesian line by numeric IK.
TEST(MotionPlanner, TheSevenAxisWamPlansAroundAPostAndFollowsALine) {
  const test::ScratchDir dir;
  const std::string scene = R"(robots:
  - name: wam
    urdf: )" + wamUrdf() + R"(
    home: {/j1: 1.2, /j2: 1.0, /j4: 1.0}
    tools:
      - {name: hand, link: /wam7, tcp: {position: [0, 0, 0.1]}}
objects:
  - name: post
    geometry: {box: {size: [0.06, 0.06, 0.6]}}
    pose: {position: [0.95, 0.14, 0.3]}
)";
  const World world(readSceneFile(dir.write("wam.yaml", scene)), kHulls);
  const MotionGroup group(world, world.initialState(), {0});
  const std::vector<double> start = group.configuration(group.context());
  const MotionResult result = planMotion(group, start, with(start, 0, -1.2));
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_FALSE(result.statistics.straight);
  expectCertified(group, result);
  const verify::ReferenceGeometry reference(world);
  EXPECT_TRUE(verify::verifyPath(reference, {{0}, result.path, {}, std::nullopt}).collisionFree());

  ToolKinematics tool(world, 0, 0);
  std::vector<double> q = start;
  Pose target = tool.tcpPose(q);
  target.translation().z() -= 0.05;
  const MotionResult line = planCartesian(group, tool, start, target);
  ASSERT_EQ(line.status, PlannerStatus::Solved) << line.message;
  EXPECT_TRUE(target.isApprox(tool.tcpPose(q = line.path.back()), 1e-5));
}

// Random start and goal configurations among the KR5 cell's obstacles: every solved path is
// certified, densely free, and free for the independent verifier (FCL on the original meshes);
// every failure is an invalid start or goal, named, or the time limit.
TEST(MotionPlanner, RandomQueriesGiveCertifiedPathsOrNamedFailures) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  const RobotModel& model = kr5World().robots()[0].collision.model();
  const verify::ReferenceGeometry reference(kr5World());
  std::mt19937_64 rng(3);
  int solved = 0;
  for (int query = 0; query < 12; ++query) {
    const std::vector<double> start = randomConfiguration(model, rng);
    const std::vector<double> goal = randomConfiguration(model, rng);
    MotionOptions options;
    options.seed = static_cast<std::uint64_t>(query);
    options.timeLimit = 2;
    const MotionResult result = planMotion(group, start, goal, options);
    switch (result.status) {
      case PlannerStatus::Solved:
        ++solved;
        expectCertified(group, result);
        expectDenselyFree(group, result.path, 1 * kDegree);
        EXPECT_TRUE(
            verify::verifyPath(reference, {{0}, result.path, {}, std::nullopt}).collisionFree())
            << "query " << query;
        break;
      case PlannerStatus::InvalidStart:
      case PlannerStatus::InvalidGoal:
        EXPECT_TRUE(result.message.find("collides") != std::string::npos ||
                    result.message.find("closer than") != std::string::npos)
            << result.message;
        break;
      default:
        EXPECT_EQ(result.status, PlannerStatus::TimeLimit) << result.message;
    }
  }
  EXPECT_GE(solved, 3);
}

TEST(MotionChecks, AllocateNothingPerCheck) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  WorldStateChecker states(group, 0.005);
  SweptMotionValidator motions(group, 0.005);
  const std::vector<double> start = group.configuration(group.context());
  const std::vector<double> goal = with(start, 0, -60 * kDegree);
  const std::vector<double> near = with(start, 0, 50 * kDegree);
  // The first checks grow the buffers (to the longest motion seen); later ones allocate nothing.
  EXPECT_TRUE(states.isValid(goal));
  EXPECT_FALSE(motions.isValid(start, goal));
  EXPECT_TRUE(motions.isValid(start, near));
  bool valid = false;
  EXPECT_EQ(test::allocationsDuring([&] {
              for (int i = 0; i < 10; ++i) {
                valid = states.isValid(goal) != valid;
                valid = motions.isValid(start, goal) != valid;
                valid = motions.isValid(start, near) != valid;
              }
            }),
            0);
}

TEST(MotionChecks, TheVerdictOnASegmentDoesNotDependOnItsDirection) {
  const MotionGroup group = groupOf(kr5World(), {"kr5"});
  SweptMotionValidator motions(group, 0.005);
  const RobotModel& model = kr5World().robots()[0].collision.model();
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20; ++i) {
    const std::vector<double> a = randomConfiguration(model, rng);
    const std::vector<double> b = randomConfiguration(model, rng);
    EXPECT_EQ(motions.isValid(a, b), motions.isValid(b, a));
  }
}

TEST(CartesianMotion, FollowsTheToolLineWithinTheDeviation) {
  const World& world = kr5World();
  const MotionGroup group = groupOf(world, {"kr5"});
  ToolKinematics tool(world, 0, 0);
  const std::vector<double> start = group.configuration(group.context());
  std::vector<double> q = start;
  const Pose from = tool.tcpPose(q);
  Pose target = from;
  target.translation() += 0.08 * from.linear().col(2);  // 8 cm along the tool's approach axis
  const CartesianOptions cartesian;
  const MotionResult result = planCartesian(group, tool, start, target, {}, cartesian);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << result.message;
  EXPECT_GE(result.path.size(), 17u);  // 5 mm steps
  EXPECT_TRUE(target.isApprox(tool.tcpPose(q = result.path.back()), 1e-6));
  const Vec3 axis = (target.translation() - from.translation()).normalized();
  const auto offLine = [&](const std::vector<double>& config) {
    std::vector<double> copy = config;
    const Vec3 p = tool.tcpPose(copy).translation() - from.translation();
    return (p - p.dot(axis) * axis).norm();
  };
  for (std::size_t s = 0; s + 1 < result.path.size(); ++s) {
    EXPECT_LT(offLine(result.path[s]), 1e-6);
    std::vector<double> middle(result.path[s].size());
    for (std::size_t i = 0; i < middle.size(); ++i) {
      middle[i] = 0.5 * (result.path[s][i] + result.path[s + 1][i]);
    }
    EXPECT_LE(offLine(middle), cartesian.maxDeviation);
  }
  expectCertified(group, result);
}

// A pose reached by numeric IK from two different starts gives the same configuration, to the
// bit: the closed form's solution replaces the numeric one, so that equal geometric states of the
// planner compare equal whatever led to them.
TEST(ToolKinematics, SolveNearGivesTheClosedFormsSolutionFromAnyStart) {
  const World& world = kr5World();
  ToolKinematics tool(world, 0, 0);
  std::vector<double> home = world.initialState().robots[0].configuration;
  home[2] = -0.4;  // away from the wrist singularity of home (its wrist pitch 0)
  home[4] = 0.7;
  const Pose target = tool.tcpPose(home);
  std::vector<double> first = home, second = home;
  first[1] += 0.02;
  second[3] -= 0.03;
  second[5] += 0.02;
  const std::optional<std::vector<double>> a = tool.solveNear(target, first);
  const std::optional<std::vector<double>> b = tool.solveNear(target, second);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(*a, *b);
  const std::vector<std::vector<double>> exact = tool.solutions(target, home);
  EXPECT_NE(std::find(exact.begin(), exact.end(), *a), exact.end())
      << "one of the closed form's solutions";
}

TEST(CartesianMotion, ALineThroughAnObstacleIsRejectedNamingIt) {
  const World& world = kr5World();
  const MotionGroup group = groupOf(world, {"kr5"});
  ToolKinematics tool(world, 0, 0);
  // Start next to the pole, the wrist bent (away from its singularity), then move the tool
  // straight through the pole.
  std::vector<double> start = group.configuration(group.context());
  start[0] = 12 * kDegree;
  start[4] = 35 * kDegree;
  ASSERT_FALSE(configurationProblem(group, start, 0.005));
  Pose target = tool.tcpPose(start);
  std::vector<double> across = with(start, 0, -12 * kDegree);
  target.translation() = tool.tcpPose(across).translation();
  const MotionResult result = planCartesian(group, tool, start, target);
  EXPECT_EQ(result.status, PlannerStatus::Unsolvable);
  EXPECT_NE(result.message.find("pole"), std::string::npos) << result.message;
}

TEST(CartesianMotion, AnUnreachableLineIsAnInvalidGoal) {
  const World& world = kr5World();
  const MotionGroup group = groupOf(world, {"kr5"});
  ToolKinematics tool(world, 0, 0);
  std::vector<double> start = group.configuration(group.context());
  start[4] = 35 * kDegree;
  Pose target = tool.tcpPose(start);
  target.translation() += Vec3(3, 0, 0);  // far out of reach
  const MotionResult result = planCartesian(group, tool, start, target);
  EXPECT_EQ(result.status, PlannerStatus::InvalidGoal);
  EXPECT_NE(result.message.find("% of the line"), std::string::npos) << result.message;
}

}  // namespace
}  // namespace kaboum::motion
