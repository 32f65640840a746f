// MoveIt's formats: the SRDF's allowed pairs (also through the scene file's `srdf` and
// `allowed_collisions` keys), package:// mesh paths, and MotionBenchMaker's planning scenes and
// requests read into scene descriptions (the copies in data/motionbenchmaker/), with one test per
// class of bad input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <string>

#include "io_test_support.hpp"
#include "kaboum/io/moveit_scene.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/io/urdf_loader.hpp"

namespace kaboum::io {

using namespace kaboum::testing;

namespace {

namespace fs = std::filesystem;
using test::ScratchDir;
using test::slurp;

constexpr const char* kScenarios[] = {"table_pick_panda", "bookshelf_small_panda", "box_panda"};

std::string pandaFile(const std::string& name) {
  return dataFile("robots/panda/" + name);
}

MoveItRobot panda() {
  std::vector<std::string> arm;
  for (int joint = 1; joint <= 7; ++joint) arm.push_back(fmt::format("panda_joint{}", joint));
  return {pandaFile("panda.urdf"), pandaFile("panda.srdf"), "panda_arm", arm};
}

fs::path problemFile(const std::string& scenario, const std::string& file) {
  return dataFile("motionbenchmaker/" + scenario + "/" + file);
}

MotionProblem tablePick1() {
  return readMoveItProblem(problemFile("table_pick_panda", "scene0001.yaml"),
                           problemFile("table_pick_panda", "request0001.yaml"), panda());
}

const ObjectSpec& objectNamed(const MotionProblem& problem, const std::string& name) {
  const auto& objects = problem.scene.objects;
  const auto found = std::find_if(objects.begin(), objects.end(),
                                  [&](const ObjectSpec& object) { return object.name == name; });
  EXPECT_NE(found, objects.end()) << name;
  return found == objects.end() ? objects.front() : *found;
}

// The message `read` throws as InputError, or "" when it reads.
template <typename Read>
std::string errorOf(const Read& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A copy of table_pick_panda/0001 in `dir` with `from` replaced by `to` in the scene (or, with
// `inRequest`, the request); reading it must fail with one line that starts with `where` (the
// copied file's name and position) and contains `what`.
void expectProblemError(const std::string& from, const std::string& to, bool inRequest,
                        const std::string& where, const std::string& what) {
  const ScratchDir dir;
  std::string scene = slurp(problemFile("table_pick_panda", "scene0001.yaml"));
  std::string request = slurp(problemFile("table_pick_panda", "request0001.yaml"));
  std::string& edited = inRequest ? request : scene;
  const auto at = edited.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  edited.replace(at, from.size(), to);
  const std::string scenePath = dir.write("scene0001.yaml", scene);
  const std::string requestPath = dir.write("request0001.yaml", request);
  const std::string message = errorOf([&] { readMoveItProblem(scenePath, requestPath, panda()); });
  const std::string file = inRequest ? requestPath : scenePath;
  EXPECT_EQ(message.rfind(file + ":" + where + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

void expectSceneError(const std::string& from, const std::string& to, const std::string& where,
                      const std::string& what) {
  expectProblemError(from, to, false, where, what);
}

void expectRequestError(const std::string& from, const std::string& to, const std::string& where,
                        const std::string& what) {
  expectProblemError(from, to, true, where, what);
}

bool hasPair(const std::vector<AllowedPair>& pairs, const std::string& a, const std::string& b) {
  return std::any_of(pairs.begin(), pairs.end(), [&](const AllowedPair& pair) {
    return (pair.first == a && pair.second == b) || (pair.first == b && pair.second == a);
  });
}

}  // namespace

TEST(Srdf, ReadsThePandasThirtyFourDisabledPairs) {
  const RobotModel model = loadUrdf(pandaFile("panda.urdf"));
  const std::vector<AllowedPair> pairs = readSrdfAllowedPairs(pandaFile("panda.srdf"), model);
  EXPECT_EQ(pairs.size(), 34U);  // 19 arm pairs, 3 in the hand, 12 between hand and arm
  EXPECT_TRUE(hasPair(pairs, "panda_link0", "panda_link1"));
  EXPECT_TRUE(hasPair(pairs, "panda_link7", "panda_rightfinger"));
  EXPECT_FALSE(hasPair(pairs, "panda_link0", "panda_link7"));
}

TEST(SrdfError, UnknownLinksMissingAttributesAndBadXmlNameFileAndLine) {
  const RobotModel model = loadUrdf(pandaFile("panda.urdf"));
  const ScratchDir dir;
  const auto error = [&](const std::string& body) {
    const std::string path = dir.write("bad.srdf", "<robot name=\"panda\">\n" + body + "</robot>");
    return errorOf([&] { readSrdfAllowedPairs(path, model); });
  };
  EXPECT_EQ(error("<disable_collisions link1=\"panda_link0\" link2=\"panda_lnk3\"/>\n"),
            dir.file("bad.srdf") +
                ":2:1: disable_collisions: unknown link 'panda_lnk3' (did you mean "
                "'panda_link3'?)");
  EXPECT_EQ(error("\n<disable_collisions link1=\"panda_link0\"/>\n"),
            dir.file("bad.srdf") + ":3:1: disable_collisions: missing attribute link2");
  EXPECT_NE(error("<disable_collisions").find("bad.srdf:2:20: invalid XML"), std::string::npos);
  EXPECT_EQ(errorOf([&] { readSrdfAllowedPairs(dir.file("none.srdf"), model); }),
            dir.file("none.srdf") + ": cannot open file");
}

TEST(SceneFileAllowedCollisions, PairsFromTheListAndTheSrdfAreMergedOnce) {
  const ScratchDir dir;
  const std::string scene =
      dir.write("scene.yaml", "robots:\n  - name: arm\n    urdf: " + pandaFile("panda.urdf") +
                                  "\n    home: {panda_joint4: -1.5}\n"
                                  "    allowed_collisions: [[panda_link0, panda_link7], "
                                  "[panda_link1, panda_link0]]\n    srdf: " +
                                  pandaFile("panda.srdf") + "\n");
  const SceneDescription description = readSceneFile(scene);
  const std::vector<AllowedPair>& pairs = description.robots[0].allowedCollisions;
  EXPECT_EQ(pairs.size(), 35U);  // the SRDF's 34 and link0–link7; link0–link1 is in both
  EXPECT_TRUE(hasPair(pairs, "panda_link7", "panda_link0"));
  EXPECT_EQ(pairs[0].first, "panda_link0");
  EXPECT_EQ(pairs[0].second, "panda_link7");
  // Without either key, no pairs.
  const std::string plain =
      dir.write("plain.yaml", "robots:\n  - {name: arm, urdf: " + pandaFile("panda.urdf") +
                                  ", home: {panda_joint4: -1.5}}\n");
  EXPECT_TRUE(readSceneFile(plain).robots[0].allowedCollisions.empty());
}

TEST(SceneFileAllowedCollisions, UnknownLinksSuggestTheNearestUrdfName) {
  const ScratchDir dir;
  const auto error = [&](const std::string& key) {
    const std::string scene =
        dir.write("scene.yaml", "robots:\n  - name: arm\n    urdf: " + pandaFile("panda.urdf") +
                                    "\n    home: {panda_joint4: -1.5}\n" + key);
    return errorOf([&] { readSceneFile(scene); });
  };
  const std::string scene = dir.file("scene.yaml");
  EXPECT_EQ(error("    allowed_collisions: [[panda_link0, panda_lnk7]]\n"),
            scene +
                ":5:40: robots[0].allowed_collisions[0][1]: unknown link 'panda_lnk7' (did you "
                "mean 'panda_link7'?)");
  EXPECT_EQ(error("    allowed_collisions: [[panda_link0]]\n"),
            scene + ":5:26: robots[0].allowed_collisions[0]: expected two links [a, b], got 1");
  const std::string srdf = dir.write("bad.srdf",
                                     "<robot name=\"panda\">\n<disable_collisions "
                                     "link1=\"panda_hnd\" link2=\"panda_link7\"/>\n</robot>\n");
  EXPECT_EQ(error("    srdf: bad.srdf\n"),
            scene + ":5:11: robots[0].srdf: " + srdf +
                ":2:1: disable_collisions: unknown link 'panda_hnd' (did you mean "
                "'panda_hand'?)");
}

TEST(UrdfPackagePaths, ThePandasPackageMeshesResolveBesideItsUrdf) {
  const RobotModel model = loadUrdf(pandaFile("panda.urdf"));
  const Link& link0 = model.links()[static_cast<std::size_t>(*model.findLink("panda_link0"))];
  ASSERT_EQ(link0.collisions.size(), 1U);
  EXPECT_EQ(fs::path(link0.collisions[0].meshPath),
            fs::path(pandaFile("meshes/collision/link0.obj")).lexically_normal());
  EXPECT_EQ(readCollisionMeshes(model).size(), 10U);  // link0..7, hand, finger (used twice)
}

TEST(UrdfPackagePaths, APackageFolderAmongTheAncestorsResolvesAndAMissingOneIsNamed) {
  const ScratchDir dir;
  fs::create_directories(dir.file("ws/franka/meshes"));
  fs::copy_file(pandaFile("meshes/collision/hand.obj"), dir.file("ws/franka/meshes/hand.obj"));
  const std::string urdf =
      "<robot name=\"r\"><link name=\"base\"><collision><geometry><mesh "
      "filename=\"package://franka/meshes/hand.obj\"/></geometry></collision></link></robot>";
  // The URDF in ws/franka/robots/: package://franka/... is ws/franka/...
  const std::string inPackage = dir.write("ws/franka/robots/r.urdf", urdf);
  EXPECT_EQ(fs::path(loadUrdf(inPackage).links()[0].collisions[0].meshPath),
            fs::path(dir.file("ws/franka/meshes/hand.obj")));
  const std::string elsewhere = dir.write("other/r.urdf", urdf);
  EXPECT_EQ(errorOf([&] { loadUrdf(elsewhere); }),
            elsewhere + ": link 'base': mesh 'package://franka/meshes/hand.obj' not found");
}

TEST(MoveItScene, TablePickHasTheYamlsObjectsPosesJointsAndAllowedPairs) {
  const MotionProblem problem = tablePick1();
  EXPECT_EQ(problem.name, "table_pick_panda/scene0001");
  EXPECT_EQ(problem.robot, "panda");
  ASSERT_EQ(problem.scene.robots.size(), 1U);
  const RobotSpec& robot = problem.scene.robots[0];
  EXPECT_EQ(robot.name, "panda");
  EXPECT_TRUE(robot.base.isApprox(Pose::Identity()));
  EXPECT_EQ(robot.allowedCollisions.size(), 34U);  // the SRDF's pairs; the matrix adds none
  ASSERT_EQ(problem.scene.objects.size(), 12U);
  EXPECT_EQ(problem.scene.objects[0].name, "Can1");
  EXPECT_EQ(problem.scene.objects[11].name, "table_top");
  for (const ObjectSpec& object : problem.scene.objects) EXPECT_FALSE(object.movable);

  const ObjectSpec& can = objectNamed(problem, "Can1");
  EXPECT_EQ(can.geometry.shape.kind, CollisionShape::Kind::Cylinder);
  EXPECT_EQ(can.geometry.shape.length, 0.12);  // MoveIt's cylinder: [height, radius]
  EXPECT_EQ(can.geometry.shape.radius, 0.03);
  EXPECT_TRUE(can.pose.translation().isApprox(
      Vec3(0.308907161037877, 0.8398608492910964, 0.2984669621486253)));
  // orientation [x, y, z, w] = [0, 0, 0.4967, 0.8679]: a turn about z by 2 atan2(z, w).
  const double turn = 2 * std::atan2(0.4966790222940755, 0.8679342998251661);
  EXPECT_TRUE(
      can.pose.linear().isApprox(Eigen::AngleAxisd(turn, Vec3::UnitZ()).toRotationMatrix(), 1e-12));
  EXPECT_EQ(can.source.line, 33);  // the object's mapping
  EXPECT_EQ(can.poseSource.line, 34);

  const ObjectSpec& table = objectNamed(problem, "table_top");
  EXPECT_EQ(table.geometry.shape.kind, CollisionShape::Kind::Box);
  EXPECT_EQ(table.geometry.shape.size, Vec3(1.2, 2, 0.04));

  const std::vector<double> ready{0, -0.785, 0, -2.356, 0, 1.571, 0.785};
  EXPECT_EQ(problem.start, ready);
  ASSERT_EQ(problem.goal.size(), 7U);
  EXPECT_EQ(problem.goal[0], -1.451140183264752);
  EXPECT_EQ(problem.goal[6], 0.8869533207576928);
  for (std::size_t j = 0; j < 7; ++j) EXPECT_EQ(robot.joints[j].home, ready[j]);
  EXPECT_EQ(robot.joints[0].name, "panda_joint1");
  EXPECT_EQ(robot.joints[0].maxVelocity, 2.3925);
}

TEST(MoveItScene, EveryCopiedProblemHasOneObjectPerPrimitiveWithTheYamlsDimensions) {
  for (const char* scenario : kScenarios) {
    for (const char* number : {"0001", "0002"}) {
      const fs::path scene = problemFile(scenario, std::string("scene") + number + ".yaml");
      const MotionProblem problem = readMoveItProblem(
          scene, problemFile(scenario, std::string("request") + number + ".yaml"), panda());
      const std::string text = slurp(scene.string());
      std::size_t primitives = 0;
      for (auto at = text.find("type: "); at != std::string::npos; at = text.find("type: ", at + 1))
        ++primitives;
      EXPECT_EQ(problem.scene.objects.size(), primitives) << scene;
      for (const ObjectSpec& object : problem.scene.objects) {
        const CollisionShape& shape = object.geometry.shape;
        const std::string dimensions =
            shape.kind == CollisionShape::Kind::Box
                ? fmt::format("[{:g}, {:g}, {:g}]", shape.size.x(), shape.size.y(), shape.size.z())
                : fmt::format("[{:g}, {:g}]", shape.length, shape.radius);
        EXPECT_NE(text.find("dimensions: " + dimensions), std::string::npos)
            << scene << " " << object.name << " " << dimensions;
        EXPECT_NE(text.find("id: " + object.name), std::string::npos) << object.name;
      }
      EXPECT_EQ(problem.start.size(), 7U);
      EXPECT_EQ(problem.goal.size(), 7U);
    }
  }
}

TEST(MoveItScene, ObjectPosesComposeWithPrimitivePosesAndSeveralPrimitivesAreNumbered) {
  const ScratchDir dir;
  const std::string scene = dir.write("scene0001.yaml", R"(robot_model_name: panda
world:
  collision_objects:
    - id: shelf
      header: {frame_id: panda_link0}
      pose: {position: [1, 0, 0], orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]}
      primitives:
        - {type: box, dimensions: [0.1, 0.2, 0.3]}
        - {type: sphere, dimensions: [0.05]}
      primitive_poses:
        - {position: [0.5, 0, 0], orientation: [0, 0, 0, 1]}
        - {position: {x: 0, y: 0, z: 0.25}, orientation: {x: 0, y: 0, z: 0, w: 2}}
)");
  const std::string request =
      dir.write("request0001.yaml", slurp(problemFile("table_pick_panda", "request0001.yaml")));
  const MotionProblem problem = readMoveItProblem(scene, request, panda());
  ASSERT_EQ(problem.scene.objects.size(), 2U);
  const ObjectSpec& box = problem.scene.objects[0];
  EXPECT_EQ(box.name, "shelf/0");
  EXPECT_TRUE(box.pose.translation().isApprox(Vec3(1, 0.5, 0)));  // turned 90° about z, then +x
  EXPECT_TRUE(box.pose.linear().isApprox(
      Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()).toRotationMatrix()));
  const ObjectSpec& ball = problem.scene.objects[1];
  EXPECT_EQ(ball.name, "shelf/1");
  EXPECT_EQ(ball.geometry.shape.kind, CollisionShape::Kind::Sphere);
  EXPECT_EQ(ball.geometry.shape.radius, 0.05);
  EXPECT_TRUE(ball.pose.translation().isApprox(Vec3(1, 0, 0.25)));
  // No allowed_collision_matrix: the SRDF's pairs only.
  EXPECT_EQ(problem.scene.robots[0].allowedCollisions.size(), 34U);
}

TEST(MoveItScene, TheMatrixAddsLinkPairsAndTheGoalKeepsJointsOutsideTheGroup) {
  MoveItRobot robot = panda();
  robot.srdf.clear();
  robot.groupJoints.pop_back();  // the group without panda_joint7: the goal still sets it
  const MotionProblem problem =
      readMoveItProblem(problemFile("box_panda", "scene0001.yaml"),
                        problemFile("box_panda", "request0001.yaml"), robot);
  EXPECT_EQ(problem.scene.robots[0].allowedCollisions.size(), 34U);  // the matrix equals the SRDF
  EXPECT_TRUE(hasPair(problem.scene.robots[0].allowedCollisions, "panda_hand", "panda_link3"));

  const ScratchDir dir;
  std::string text = slurp(problemFile("box_panda", "request0001.yaml").string());
  const auto joint7 = text.find("      - joint_name: panda_joint7");
  const std::string request =
      dir.write("request0001.yaml", text.substr(0, joint7) + text.substr(text.find("planner_id")));
  const MotionProblem withoutJoint7 =
      readMoveItProblem(problemFile("box_panda", "scene0001.yaml"), request, robot);
  EXPECT_EQ(withoutJoint7.goal[6], withoutJoint7.start[6]);
  EXPECT_EQ(withoutJoint7.goal[0], problem.goal[0]);
}

TEST(MoveItScene, ThePandasForwardKinematicsMatchesItsDhParameters) {
  const RobotModel model = loadUrdf(pandaFile("panda.urdf"));
  const int flange = *model.findLink("panda_link8");
  std::vector<Pose> poses(model.links().size());
  // At zero: the flange 0.333 + 0.316 + 0.384 - 0.107 m up, 0.088 m forward, pointing down (the
  // URDF's joint origins added by hand).
  model.linkPoses(std::vector<double>(7, 0.0), poses);
  EXPECT_LT((poses[static_cast<std::size_t>(flange)].translation() - Vec3(0.088, 0, 0.926)).norm(),
            1e-9);
  EXPECT_LT(
      (poses[static_cast<std::size_t>(flange)].linear() * Vec3::UnitZ() + Vec3::UnitZ()).norm(),
      1e-9);
  // At the start state ("ready"): Franka's modified DH parameters (a, d, α per joint, flange
  // d 0.107), multiplied out independently of the URDF, put the flange at (0.30702, 0, 0.59027).
  const MotionProblem problem = tablePick1();
  model.linkPoses(problem.start, poses);
  EXPECT_LT((poses[static_cast<std::size_t>(flange)].translation() -
             Vec3(0.307019570052, 0, 0.590269558277))
                .norm(),
            1e-9);
  const int hand = *model.findLink("panda_hand");
  EXPECT_LT((poses[static_cast<std::size_t>(hand)].translation() -
             poses[static_cast<std::size_t>(flange)].translation())
                .norm(),
            1e-12);
}

TEST(MoveItScene, TheFolderReaderPairsScenesWithRequests) {
  const std::vector<MoveItProblemFiles> problems = listMoveItProblems(dataFile("motionbenchmaker"));
  ASSERT_EQ(problems.size(), 6U);
  EXPECT_EQ(problems[0].scene, problemFile("bookshelf_small_panda", "scene0001.yaml"));
  EXPECT_EQ(problems[0].request, problemFile("bookshelf_small_panda", "request0001.yaml"));
  EXPECT_EQ(problems[5].scene, problemFile("table_pick_panda", "scene0002.yaml"));
  EXPECT_EQ(listMoveItProblems(dataFile("motionbenchmaker/box_panda")).size(), 2U);

  const ScratchDir dir;
  dir.write("set/scene0007.yaml", "");
  EXPECT_EQ(errorOf([&] { listMoveItProblems(dir.file("set")); }),
            dir.file("set/scene0007.yaml") + ": no request0007.yaml beside it");
  dir.write("empty/notes.txt", "");
  EXPECT_EQ(errorOf([&] { listMoveItProblems(dir.file("empty")); }),
            dir.file("empty") + ": no problems (sceneNNNN.yaml with requestNNNN.yaml)");
  EXPECT_EQ(errorOf([&] { listMoveItProblems(dir.file("none")); }),
            dir.file("none") + ": not a folder");
}

TEST(MoveItSceneError, MissingFiles) {
  const fs::path scene = problemFile("box_panda", "scene0001.yaml");
  const fs::path request = problemFile("box_panda", "request0001.yaml");
  EXPECT_EQ(errorOf([&] { readMoveItProblem("nowhere/scene.yaml", request, panda()); }),
            "nowhere/scene.yaml: cannot open file");
  EXPECT_EQ(errorOf([&] { readMoveItProblem(scene, "nowhere/request.yaml", panda()); }),
            "nowhere/request.yaml: cannot open file");
  MoveItRobot robot = panda();
  robot.urdf = "nowhere/panda.urdf";
  EXPECT_EQ(errorOf([&] { readMoveItProblem(scene, request, robot); }),
            "nowhere/panda.urdf: cannot open file");
  robot = panda();
  robot.srdf = "nowhere/panda.srdf";
  EXPECT_EQ(errorOf([&] { readMoveItProblem(scene, request, robot); }),
            "nowhere/panda.srdf: cannot open file");
  robot = panda();
  robot.groupJoints.push_back("panda_jont8");
  EXPECT_EQ(errorOf([&] { readMoveItProblem(scene, request, robot); }),
            robot.urdf.string() +
                ": planning group joint 'panda_jont8' is not a movable joint (did you mean "
                "'panda_joint1'?)");
}

TEST(MoveItSceneError, UnsupportedShapesAndObjectParts) {
  expectSceneError("type: cylinder", "type: cone", "38:17",
                   "world.collision_objects[0].primitives[0].type: unsupported shape 'cone' (box, "
                   "cylinder, sphere)");
  expectSceneError("      id: Can1",
                   "      id: Can1\n      meshes: [{triangles: [], vertices: []}]", "40:15",
                   "world.collision_objects[0].meshes: meshes are not supported");
  expectSceneError("      id: Can1", "      id: Can1\n      operation: 1", "40:18",
                   "world.collision_objects[0].operation: operation '1' is not supported");
  expectSceneError("      id: Can1", "      id: Can1\n      header: {frame_id: panda_hand}",
                   "40:26",
                   "world.collision_objects[0].header.frame_id: frame 'panda_hand' is "
                   "not the robot base frame");
  expectSceneError("id: Cube", "id: can1", "43:11",
                   "world.collision_objects[1].id: id 'can1' is taken by "
                   "world.collision_objects[0].id");
}

TEST(MoveItSceneError, WrongDimensionAndPoseCounts) {
  expectSceneError("dimensions: [0.12, 0.03]", "dimensions: [0.12, 0.03, 0.5]", "37:23",
                   "world.collision_objects[0].primitives[0].dimensions: expected 2 dimensions "
                   "for a cylinder, got 3");
  expectSceneError("dimensions: [0.25, 0.25, 0.25]", "dimensions: [0.25, 0.25]", "41:23",
                   "expected 3 dimensions for a box, got 2");
  expectSceneError("dimensions: [0.12, 0.03]", "dimensions: [0.12, -0.03]", "37:30",
                   "world.collision_objects[0].primitives[0].dimensions[1]: must be positive");
  expectSceneError("orientation: [0, 0, 0.4966790222940755, 0.8679342998251661]\n",
                   "orientation: [0, 0, 0.4966790222940755]\n", "35:24",
                   "world.collision_objects[0].primitive_poses[0].orientation: expected 4 "
                   "numbers, got 3");
  expectSceneError("orientation: [0, 0, 0.4966790222940755, 0.8679342998251661]\n",
                   "orientation: [0, 0, 0, 0]\n", "35:24", "zero quaternion");
}

TEST(MoveItSceneError, NanAndNonNumbers) {
  expectSceneError("dimensions: [0.12, 0.03]", "dimensions: [.nan, 0.03]", "37:24",
                   "world.collision_objects[0].primitives[0].dimensions[0]: '.nan' is not a "
                   "finite number");
  expectSceneError("position: [0.308907161037877,", "position: [.inf,", "34:22",
                   "primitive_poses[0].position[0]: '.inf' is not a finite number");
  expectRequestError("position: -1.451140183264752", "position: .NaN", "7:19",
                     "goal_constraints[0].joint_constraints[0].position: '.NaN' is not a finite "
                     "number");
  expectRequestError("position: [0, -0.785,", "position: [zero, -0.785,", "25:16",
                     "start_state.joint_state.position[0]: expected a number");
}

TEST(MoveItSceneError, RequestJointsMustBeTheUrdfsAndWithinLimits) {
  expectRequestError("joint_name: panda_joint1", "joint_name: panda_joint9", "6:21",
                     "goal_constraints[0].joint_constraints[0].joint_name: joint 'panda_joint9' "
                     "is not in the URDF (did you mean 'panda_joint1'?)");
  expectRequestError("name: [panda_joint1,", "name: [panda_jiont1,", "24:12",
                     "start_state.joint_state.name[0]: joint 'panda_jiont1' is not in the URDF "
                     "(did you mean 'panda_joint1'?)");
  expectRequestError("position: -1.451140183264752", "position: 3.5", "7:19",
                     "3.5 is outside the limits [-2.9671, 2.9671] of joint 'panda_joint1'");
  expectRequestError("      - joint_name: panda_joint1\n        position: -1.451140183264752\n", "",
                     "6:7",
                     "goal_constraints[0].joint_constraints: no position for group "
                     "joint 'panda_joint1'");
  expectRequestError("position: [0, -0.785, 0, -2.356, 0, 1.571, 0.785, 0.065, 0.065]",
                     "position: [0, -0.785, 0, -2.356, 0, 1.571, 0.785, 0.065]", "25:15",
                     "start_state.joint_state.position: expected 9 positions (one per name), got "
                     "8");
  expectRequestError("group_name: panda_arm", "group_name: hand", "31:13",
                     "group_name: planning group 'hand' is not 'panda_arm'");
}

TEST(MoveItSceneError, MatrixNamesFramesAndGoalsOutsideTheSupportedSubset) {
  expectSceneError("entry_names: [panda_hand,", "entry_names: [panda_hnd,", "16:17",
                   "allowed_collision_matrix.entry_names[0]: unknown link or object 'panda_hnd' "
                   "(did you mean 'panda_hand'?)");
  expectSceneError("entry_names: [panda_hand,", "entry_names: [Cube,", "18:15",
                   "allowed_collision_matrix.entry_values[0][1]: allowing link 'panda_leftfinger' "
                   "to touch object 'Cube' is not supported");
  expectSceneError("robot_model_name: panda", "robot_model_name: fetch", "30:19",
                   "robot_model_name: robot 'fetch' is not the URDF's robot 'panda'");
  expectRequestError("transforms: [{translation: [0, 0, 0],",
                     "transforms: [{translation: [0, 1, 0],", "29:18",
                     "start_state.multi_dof_joint_state.transforms[0]: the virtual joint must be "
                     "the identity");
  expectRequestError("goal_constraints:\n", "goal_constraints:\n  - position_constraints: [{}]\n",
                     "5:3", "goal_constraints: expected 1 goal, got 2");
}

}  // namespace kaboum::io
