// The scene file reader on the example scenes (every value as written, defaults, source
// positions) and one test per class of bad input, each a single line naming file, line, column
// and key; truncated and mutated files never give anything but InputError.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <variant>

#include "io_test_support.hpp"
#include "kaboum/io/scene_file.hpp"

namespace kaboum::io {

using namespace kaboum::testing;

namespace {

using test::ScratchDir;
using test::slurp;

constexpr double kDegree = std::numbers::pi / 180;

std::string scenesDir() {
  return exampleFile("scenes");
}

// Parses `text` as "scene.yaml" in examples/scenes/ (so ../robots/two-arm.urdf resolves).
SceneDescription parse(const std::string& text) {
  return parseSceneText(text, "scene.yaml", scenesDir());
}

// The message parse(text) throws as InputError, or "" when it reads the scene.
std::string sceneError(const std::string& text, const std::string& baseDir = scenesDir()) {
  try {
    parseSceneText(text, "scene.yaml", baseDir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// parse(text) fails with one line that starts with `where` ("scene.yaml:3:11: robots[0].urdf")
// followed by ": " and contains `what`.
void expectSceneError(const std::string& text, const std::string& where, const std::string& what,
                      const std::string& baseDir = scenesDir()) {
  const std::string message = sceneError(text, baseDir);
  EXPECT_EQ(message.rfind(where + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// The 1-based number of the first line of `path` that starts with `text`.
long lineStarting(const std::string& path, const std::string& text) {
  std::istringstream in(slurp(path));
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (line.rfind(text, 0) == 0) return number;
  }
  return 0;
}

void expectNear(const Vec3& actual, const Vec3& expected) {
  EXPECT_LT((actual - expected).norm(), 1e-12) << actual.transpose();
}

void expectSamePose(const Pose& actual, const Pose& expected) {
  EXPECT_LT((actual.matrix() - expected.matrix()).norm(), 1e-12) << actual.matrix();
}

const JointSpec& joint(const RobotSpec& robot, const std::string& name) {
  const auto found = std::find_if(robot.joints.begin(), robot.joints.end(),
                                  [&](const JointSpec& spec) { return spec.name == name; });
  EXPECT_NE(found, robot.joints.end()) << name;
  return found == robot.joints.end() ? robot.joints.front() : *found;
}

Pose translation(double x, double y, double z) {
  return Pose(Eigen::Translation3d(x, y, z));
}

// A robot entry on examples/robots/two-arm.urdf with `more` appended (indented four spaces).
std::string twinRobot(const std::string& more = "") {
  return "robots:\n"
         "  - name: twin\n"
         "    urdf: ../robots/two-arm.urdf\n" +
         more;
}

// A twin robot whose left tool has `hand` appended (indented ten spaces under `hand:`).
std::string twinWithHand(const std::string& hand) {
  return twinRobot(
      "    tools:\n"
      "      - name: left\n"
      "        link: left_flange\n"
      "        hand:\n" +
      hand);
}

// One movable sphere named `name` with `more` appended (indented four spaces).
std::string ball(const std::string& more = "", const std::string& name = "ball") {
  return "objects:\n"
         "  - name: " +
         name +
         "\n"
         "    geometry: {sphere: {radius: 0.05}}\n"
         "    movable: true\n" +
         more;
}

TEST(SceneFile, TwoArmsTableHasTheWrittenValues) {
  const std::string path = exampleFile("scenes/two-arms-table.yaml");
  const SceneDescription scene = readSceneFile(path);

  EXPECT_DOUBLE_EQ(scene.settings.epsilon, 0.01);
  EXPECT_TRUE(scene.settings.epsilonRelative);
  EXPECT_DOUBLE_EQ(scene.settings.jointStep, 2 * kDegree);
  EXPECT_DOUBLE_EQ(scene.settings.toolStep, 0.005);
  EXPECT_EQ(scene.settings.seed, 7u);

  ASSERT_EQ(scene.robots.size(), 1u);
  const RobotSpec& twin = scene.robots[0];
  EXPECT_EQ(twin.name, "twin");
  EXPECT_TRUE(std::filesystem::equivalent(twin.urdf, exampleFile("robots/two-arm.urdf")));
  expectSamePose(twin.base, Pose::Identity());
  ASSERT_EQ(twin.joints.size(), 12u);
  EXPECT_EQ(joint(twin, "left_j1").home, 0.0);  // not listed
  EXPECT_EQ(joint(twin, "left_j2").home, 0.3);
  EXPECT_DOUBLE_EQ(joint(twin, "right_j5").home, 60 * kDegree);
  EXPECT_EQ(joint(twin, "left_j1").maxVelocity, 1.5);  // the file's, over the URDF's 2.0
  EXPECT_EQ(joint(twin, "left_j1").maxAcceleration, 3.0);
  EXPECT_EQ(joint(twin, "left_j2").maxVelocity, 2.0);      // the URDF's
  EXPECT_EQ(joint(twin, "left_j2").maxAcceleration, 2.0);  // the default entry's
  ASSERT_EQ(twin.tools.size(), 2u);
  const ToolSpec& left = twin.tools[0];
  EXPECT_EQ(left.name, "left");
  EXPECT_EQ(left.link, "left_flange");
  EXPECT_EQ(left.baseLink, "torso");
  expectSamePose(left.tcp, translation(0, 0, 0.14));
  EXPECT_EQ(left.ik, IkMethod::ClosedForm);
  EXPECT_EQ(twin.tools[1].ik, IkMethod::Auto);
  ASSERT_TRUE(left.hand.has_value());
  EXPECT_EQ(left.hand->links, std::vector<std::string>{"left_flange"});
  ASSERT_EQ(left.hand->shapes.size(), 2u);
  EXPECT_EQ(left.hand->shapes[1].shape.kind, CollisionShape::Kind::Box);
  expectNear(left.hand->shapes[1].shape.size, Vec3(0.02, 0.01, 0.06));
  expectSamePose(left.hand->shapes[1].shape.origin, translation(0, -0.03, 0.13));
  EXPECT_FALSE(left.hand->fingers.has_value());

  ASSERT_EQ(scene.objects.size(), 3u);
  const ObjectSpec& table = scene.objects[0];
  EXPECT_EQ(table.name, "table");
  EXPECT_FALSE(table.movable);
  EXPECT_EQ(table.geometry.shape.kind, CollisionShape::Kind::Box);
  expectNear(table.geometry.shape.size, Vec3(0.5, 1.0, 0.04));
  expectSamePose(table.pose, translation(0.55, 0, 0.70));

  const ObjectSpec& bottle = scene.objects[1];
  EXPECT_TRUE(bottle.movable);
  EXPECT_EQ(bottle.geometry.shape.kind, CollisionShape::Kind::Cylinder);
  EXPECT_EQ(bottle.geometry.shape.radius, 0.035);
  EXPECT_EQ(bottle.geometry.shape.length, 0.22);
  ASSERT_EQ(bottle.grasps.size(), 2u);
  EXPECT_EQ(bottle.grasps[0].name, "side");
  const auto& side = std::get<std::vector<GraspConstraint>>(bottle.grasps[0].definition);
  ASSERT_EQ(side.size(), 3u);
  EXPECT_EQ(side[0].type, ConstraintType::Coincident);
  EXPECT_EQ(side[0].hand.kind, PrimitiveShape::Kind::Point);
  EXPECT_EQ(side[0].object.kind, PrimitiveShape::Kind::Line);
  expectNear(side[0].object.direction, Vec3::UnitZ());
  EXPECT_EQ(side[1].object.kind, PrimitiveShape::Kind::Plane);
  expectNear(side[1].object.point, Vec3(0, 0, 0.03));
  EXPECT_EQ(side[2].type, ConstraintType::Perpendicular);
  expectNear(side[2].hand.direction, Vec3::UnitZ());  // xy-plane: normal z
  const auto& top = std::get<GraspPose>(bottle.grasps[1].definition);
  expectNear(top.tcp.translation(), Vec3(0, 0, 0.10));
  expectNear(top.tcp.linear() * Vec3::UnitZ(), -Vec3::UnitZ());
  ASSERT_EQ(top.free.size(), 1u);
  EXPECT_EQ(top.free[0].kind, FreeMotion::Kind::Rotation);
  EXPECT_EQ(top.free[0].axis, 2);
  EXPECT_DOUBLE_EQ(top.free[0].lower, -std::numbers::pi);
  EXPECT_DOUBLE_EQ(top.free[0].upper, std::numbers::pi);
  EXPECT_FALSE(bottle.restingFaces.automatic);
  ASSERT_EQ(bottle.restingFaces.normals.size(), 1u);
  expectNear(bottle.restingFaces.normals[0], -Vec3::UnitZ());

  const ObjectSpec& crate = scene.objects[2];
  EXPECT_EQ(crate.geometry.shape.kind, CollisionShape::Kind::Mesh);
  EXPECT_TRUE(
      std::filesystem::equivalent(crate.geometry.shape.meshPath, dataFile("meshes/cube.off")));
  expectNear(crate.geometry.shape.size, Vec3::Constant(0.06));
  expectSamePose(crate.geometry.shape.origin, translation(-0.03, -0.03, -0.03));
  expectSamePose(crate.pose, translation(0.45, -0.1, 0.75) *
                                 Pose(Eigen::AngleAxisd(30 * kDegree, Vec3::UnitZ())));
  const auto& crateTop = std::get<GraspPose>(crate.grasps[0].definition);
  ASSERT_EQ(crateTop.free.size(), 2u);
  EXPECT_EQ(crateTop.free[1].kind, FreeMotion::Kind::Translation);
  EXPECT_EQ(crateTop.free[1].lower, -0.01);
  EXPECT_TRUE(crate.restingFaces.automatic);

  ASSERT_EQ(scene.locations.size(), 2u);
  const auto& goal = std::get<BoxRegion>(scene.locations[0].region);
  expectNear(goal.lower, Vec3(0.35, -0.45, 0.72));
  expectNear(goal.upper, Vec3(0.70, -0.15, 0.95));
  EXPECT_FALSE(scene.locations[0].supportSurface);
  const auto& shelf = std::get<BoxRegion>(scene.locations[1].region);
  expectSamePose(shelf.pose, translation(0.3, -0.55, 1.0));
  expectNear(shelf.lower, Vec3(-0.15, -0.15, -0.1));
  EXPECT_TRUE(scene.locations[1].supportSurface);
}

TEST(SceneFile, BimanualCellHasTwoRobotsFingersMeshesAndAHull) {
  const SceneDescription scene = readSceneFile(exampleFile("scenes/bimanual-cell.yaml"));
  EXPECT_EQ(scene.settings.epsilon, 0.005);
  EXPECT_FALSE(scene.settings.epsilonRelative);
  ASSERT_EQ(scene.robots.size(), 2u);
  const RobotSpec& left = scene.robots[0];
  expectSamePose(left.base, translation(0, 0.57, 0));
  ASSERT_EQ(left.joints.size(), 8u);  // six arm joints, two fingers
  EXPECT_EQ(joint(left, "finger0").home, 0.03);
  EXPECT_DOUBLE_EQ(joint(left, "joint2").home, 100 * kDegree);
  EXPECT_EQ(joint(left, "finger0").maxVelocity, 0.5);  // the URDF's
  EXPECT_EQ(joint(left, "finger0").maxAcceleration, 5.0);
  const HandSpec& hand = *left.tools[0].hand;
  EXPECT_EQ(hand.links, (std::vector<std::string>{"body7", "body8"}));
  ASSERT_TRUE(hand.fingers.has_value());
  EXPECT_EQ(hand.fingers->open.at("finger1"), 0.05);
  EXPECT_EQ(hand.fingers->closed.at("finger0"), 0.0);
  EXPECT_EQ(scene.robots[1].tools[0].hand->shapes[0].shape.kind, CollisionShape::Kind::Mesh);

  const auto& rim = std::get<std::vector<GraspConstraint>>(scene.objects[1].grasps[0].definition);
  EXPECT_EQ(rim[1].type, ConstraintType::Distance);
  EXPECT_EQ(rim[1].distance, 0.03);
  const auto& area = std::get<HullRegion>(scene.locations[0].region);
  EXPECT_EQ(area.points.size(), 8u);
}

TEST(SceneFile, EntriesKnowTheirFileLineAndKey) {
  const std::string path = exampleFile("scenes/two-arms-table.yaml");
  const SceneDescription scene = readSceneFile(path);
  const SourceLocation& bottle = scene.objects[1].source;
  EXPECT_EQ(bottle.file, path);
  EXPECT_EQ(bottle.key, "objects[1]");
  EXPECT_EQ(bottle.line, lineStarting(path, "  - name: bottle"));
  EXPECT_EQ(bottle.column, 5);
  EXPECT_EQ(scene.objects[1].poseSource.key, "objects[1].pose");
  EXPECT_EQ(scene.objects[1].poseSource.line, bottle.line + 2);
  EXPECT_EQ(scene.robots[0].homeSource.line, lineStarting(path, "    home:"));
  EXPECT_EQ(scene.robots[0].tools[1].source.key, "robots[0].tools[1]");
  EXPECT_EQ(scene.objects[1].grasps[1].source.key, "objects[1].grasps[1]");
  EXPECT_EQ(scene.locations[1].source.line, lineStarting(path, "  - name: shelf"));
  EXPECT_EQ(bottle.message("starts in collision with 'table'"),
            path + ":" + std::to_string(bottle.line) +
                ":5: objects[1]: starts in collision with 'table'");
}

TEST(SceneFile, UnwrittenValuesTakeTheirDefaults) {
  const SceneDescription scene = parse(twinRobot() + ball());
  EXPECT_EQ(scene.settings.epsilon, 0.01);
  EXPECT_TRUE(scene.settings.epsilonRelative);
  EXPECT_DOUBLE_EQ(scene.settings.jointStep, kDegree);
  EXPECT_EQ(scene.settings.toolStep, 0.005);
  EXPECT_EQ(scene.settings.seed, 1u);
  const RobotSpec& twin = scene.robots[0];
  expectSamePose(twin.base, Pose::Identity());
  for (const JointSpec& joint : twin.joints) {
    EXPECT_EQ(joint.home, 0.0);
    EXPECT_EQ(joint.maxVelocity,
              joint.name.ends_with("4") || joint.name.ends_with("5") || joint.name.ends_with("6")
                  ? 3.0
                  : 2.0);
    EXPECT_FALSE(joint.maxAcceleration.has_value());
  }
  EXPECT_TRUE(twin.tools.empty());
  EXPECT_EQ(twin.homeSource.key, "robots[0]");
  const ObjectSpec& ball = scene.objects[0];
  expectSamePose(ball.pose, Pose::Identity());
  expectSamePose(ball.geometry.shape.origin, Pose::Identity());
  EXPECT_TRUE(ball.grasps.empty());
  EXPECT_TRUE(ball.restingFaces.automatic);
  EXPECT_EQ(ball.poseSource.key, "objects[0]");
  EXPECT_TRUE(parse("robots:\nobjects: []\n").robots.empty());
}

TEST(SceneFile, OrientationsInRadiansDegreesAndQuaternionsAgree) {
  const auto rotationOf = [](const std::string& orientation) {
    return parse(ball("    pose: {orientation: " + orientation + "}\n")).objects[0].pose;
  };
  const Pose expected(Eigen::AngleAxisd(0.3, Vec3::UnitZ()) *
                      Eigen::AngleAxisd(-0.2, Vec3::UnitY()) *
                      Eigen::AngleAxisd(0.1, Vec3::UnitX()));
  expectSamePose(rotationOf("{rpy: [0.1, -0.2, 0.3]}"), expected);
  const Eigen::Quaterniond q(expected.linear());
  // Not unit length: quaternions are normalized.
  expectSamePose(rotationOf(fmt::format("{{quaternion: [{}, {}, {}, {}]}}", 2 * q.w(), 2 * q.x(),
                                        2 * q.y(), 2 * q.z())),
                 expected);
  expectSamePose(rotationOf("{rpy: [90deg, 0, -45 deg]}"),
                 Pose(Eigen::AngleAxisd(-std::numbers::pi / 4, Vec3::UnitZ()) *
                      Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX())));
}

TEST(SceneFile, TheDocumentedExampleIsTheExampleFile) {
  const std::string doc = slurp(sourceFile("docs/scene-format.md"));
  const std::string fence = "```yaml\n";
  const std::size_t start = doc.find(fence, doc.find("## Complete example"));
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + fence.size());
  ASSERT_NE(end, std::string::npos);
  EXPECT_EQ(doc.substr(start + fence.size(), end - start - fence.size()),
            slurp(exampleFile("scenes/two-arms-table.yaml")));
}

TEST(SceneFile, MissingFileIsNamed) {
  try {
    readSceneFile("/nonexistent/scene.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/scene.yaml: cannot open file");
  }
}

TEST(SceneFileError, YamlSyntaxNamesYamlCppsPlace) {
  expectSceneError("objects:\n  - name: a\n    geometry: {sphere: {radius: 1}\n", "scene.yaml:4:1",
                   "invalid YAML: end of map flow not found");
  expectSceneError("settings:\n  seed: 1\n seed: 2\n", "scene.yaml:3:2", "invalid YAML");
}

TEST(SceneFileError, EmptyOrWronglyShapedFile) {
  EXPECT_EQ(sceneError("# nothing\n"),
            "scene.yaml: empty scene: expected a mapping with robots, objects, locations and "
            "settings");
  expectSceneError("- robots\n", "scene.yaml:1:1", "expected a mapping, got a list");
  expectSceneError("version: 2\n", "scene.yaml:1:10",
                   "version: unsupported version '2' (expected 1)");
}

TEST(SceneFileError, MissingOrUnreadableUrdf) {
  expectSceneError(twinRobot().replace(twinRobot().find("two-arm"), 7, "three-arm"),
                   "scene.yaml:3:11: robots[0].urdf", "three-arm.urdf: cannot open file");
  ScratchDir dir;
  dir.write("broken.urdf", "<robot name='x'><link name='a'/>");
  expectSceneError("robots:\n  - {name: r, urdf: broken.urdf}\n", "scene.yaml:2:21: robots[0].urdf",
                   "broken.urdf: invalid URDF", dir.file(""));
}

TEST(SceneFileError, MissingOrUnreadableMesh) {
  ScratchDir dir;
  dir.write("garbage.obj", "this is not a mesh\n");
  dir.write("points.xyz", "0 0 0\n");
  const auto meshObject = [](const std::string& file) {
    return "objects:\n"
           "  - name: part\n"
           "    geometry:\n"
           "      mesh:\n"
           "        file: " +
           file + "\n";
  };
  expectSceneError(meshObject("missing.stl"), "scene.yaml:5:15: objects[0].geometry.mesh.file",
                   "missing.stl: cannot open", dir.file(""));
  expectSceneError(meshObject("garbage.obj"), "scene.yaml:5:15: objects[0].geometry.mesh.file",
                   "garbage.obj", dir.file(""));
  expectSceneError(meshObject("points.xyz"), "scene.yaml:5:15: objects[0].geometry.mesh.file",
                   "points.xyz", dir.file(""));
  expectSceneError(meshObject("''"), "scene.yaml:5:15: objects[0].geometry.mesh.file",
                   "empty file name", dir.file(""));
}

TEST(SceneFileError, UnknownKeysSuggestTheNearestValidKey) {
  expectSceneError(ball("    pose: {postion: [0, 0, 1]}\n"), "scene.yaml:5:12: objects[0].pose",
                   "unknown key 'postion' (did you mean 'position'?)");
  expectSceneError("robot: []\n", "scene.yaml:1:1", "unknown key 'robot' (did you mean 'robots'?)");
  expectSceneError(ball("    colour: red\n"), "scene.yaml:5:5: objects[0]",
                   "unknown key 'colour' (expected one of: name, geometry, pose, place_in, "
                   "movable, grasps, resting_faces)");
  expectSceneError(ball("    pose: {position: [0, 0, 1], position: [1, 0, 0]}\n"),
                   "scene.yaml:5:33: objects[0].pose", "duplicate key 'position'");
  expectSceneError(ball("    geometry: {sphere: {radius: 1}}\n"), "scene.yaml:5:5: objects[0]",
                   "duplicate key 'geometry'");
}

TEST(SceneFileError, MissingKeysAndAmbiguousChoices) {
  expectSceneError("objects:\n  - name: a\n", "scene.yaml:2:5: objects[0]",
                   "missing key 'geometry'");
  expectSceneError(
      "objects:\n  - name: a\n    geometry: {sphere: {radius: 1}, box: {size: [1, 1, 1]}}\n",
      "scene.yaml:3:15: objects[0].geometry",
      "expected exactly one of box, cylinder, sphere, mesh, got box and sphere");
  expectSceneError(
      "locations:\n  - name: l\n    region: {box: {size: [1, 1, 1], min: [0, 0, 0]}}\n",
      "scene.yaml:3:19: locations[0].region.box", "expected size, or min and max");
}

TEST(SceneFileError, UnknownLinksAndJointsSuggestTheNearestUrdfName) {
  expectSceneError(twinRobot("    tools:\n      - {name: left, link: left_flang}\n"),
                   "scene.yaml:5:28: robots[0].tools[0].link",
                   "unknown link 'left_flang' (did you mean 'left_flange'?)");
  expectSceneError(
      twinRobot("    tools:\n      - {name: left, link: left_flange, base_link: tors}\n"),
      "scene.yaml:5:52: robots[0].tools[0].base_link",
      "unknown link 'tors' (did you mean 'torso'?)");
  expectSceneError(twinRobot("    home: {lft_j2: 0.5}\n"), "scene.yaml:4:12: robots[0].home",
                   "unknown joint 'lft_j2' (did you mean 'left_j2'?)");
  expectSceneError(twinRobot("    home: {left_mount: 0}\n"), "scene.yaml:4:12: robots[0].home",
                   "joint 'left_mount' is fixed");
  expectSceneError(twinRobot("    joint_limits: {right_j9: {velocity: 1}}\n"),
                   "scene.yaml:4:20: robots[0].joint_limits",
                   "unknown joint 'right_j9' (did you mean 'right_j1'?)");
  expectSceneError(twinWithHand("          links: [left_flange, left_flage]\n"),
                   "scene.yaml:8:32: robots[0].tools[0].hand.links[1]",
                   "unknown link 'left_flage' (did you mean 'left_flange'?)");
}

TEST(SceneFileError, WrongTypes) {
  expectSceneError(ball("    pose: {position: 3}\n"), "scene.yaml:5:22: objects[0].pose.position",
                   "expected a list, got '3'");
  expectSceneError(ball("    pose: {position: [0, 0]}\n"),
                   "scene.yaml:5:22: objects[0].pose.position", "expected 3 numbers, got 2");
  expectSceneError(ball("    pose: {position: [0, zero, 0]}\n"),
                   "scene.yaml:5:26: objects[0].pose.position[1]", "expected a number, got 'zero'");
  expectSceneError(ball().replace(ball().find("movable: true"), 13, "movable: maybe"),
                   "scene.yaml:4:14: objects[0].movable", "expected true or false, got 'maybe'");
  expectSceneError("objects: {ball: 1}\n", "scene.yaml:1:10: objects",
                   "expected a list, got a mapping");
  expectSceneError(ball("", "[b]"), "scene.yaml:2:11: objects[0].name",
                   "expected a name, got a list");
  expectSceneError(ball("", "3d-ball"), "scene.yaml:2:11: objects[0].name",
                   "name '3d-ball' must start with a letter");
  expectSceneError(ball("    pose:\n"), "scene.yaml:5:5: objects[0].pose",
                   "expected a mapping, got nothing");
  expectSceneError(
      twinRobot("    tools:\n      - {name: left, link: left_flange, ik: clsoed-form}\n"),
      "scene.yaml:5:45: robots[0].tools[0].ik",
      "unknown value 'clsoed-form' (did you mean 'closed-form'?)");
  expectSceneError(twinRobot("    home: {left_j2: 30 degrees}\n"),
                   "scene.yaml:4:21: robots[0].home.left_j2",
                   "expected an angle (radians, or degrees as in 90deg), got '30 degrees'");
  expectSceneError("settings: {seed: -3}\n", "scene.yaml:1:18: settings.seed",
                   "expected a non-negative integer, got '-3'");
}

TEST(SceneFileError, NanAndInfinityAreRejected) {
  expectSceneError(ball("    pose: {position: [0, .nan, 0]}\n"),
                   "scene.yaml:5:26: objects[0].pose.position[1]", "'.nan' is not a finite number");
  expectSceneError(ball().replace(ball().find("0.05"), 4, "-.inf"),
                   "scene.yaml:3:33: objects[0].geometry.sphere.radius",
                   "'-.inf' is not a finite number");
  expectSceneError("settings: {tool_step: .Inf}\n", "scene.yaml:1:23: settings.tool_step",
                   "'.Inf' is not a finite number");
  expectSceneError(ball("    pose: {orientation: {rpy: [0, 0, nan deg]}}\n"),
                   "scene.yaml:5:38: objects[0].pose.orientation.rpy[2]",
                   "'nan deg' is not a finite number");
}

TEST(SceneFileError, ZeroQuaternion) {
  EXPECT_EQ(sceneError(ball("    pose: {orientation: {quaternion: [0, 0, 0, 0]}}\n")),
            "scene.yaml:5:25: objects[0].pose.orientation: zero quaternion");
  expectSceneError(ball("    pose: {orientation: {quaternion: [1, 0, 0]}}\n"),
                   "scene.yaml:5:38: objects[0].pose.orientation.quaternion",
                   "expected 4 numbers [w, x, y, z], got 3");
}

TEST(SceneFileError, NonPositiveSizes) {
  expectSceneError("objects:\n  - name: a\n    geometry: {box: {size: [1, 0, 1]}}\n",
                   "scene.yaml:3:32: objects[0].geometry.box.size[1]", "must be positive, got '0'");
  expectSceneError(ball().replace(ball().find("0.05"), 4, "-0.05"),
                   "scene.yaml:3:33: objects[0].geometry.sphere.radius",
                   "must be positive, got '-0.05'");
  expectSceneError("objects:\n  - name: a\n    geometry: {cylinder: {radius: 1, length: 0}}\n",
                   "scene.yaml:3:46: objects[0].geometry.cylinder.length",
                   "must be positive, got '0'");
  expectSceneError(
      "objects:\n  - name: a\n    geometry: {mesh: {file: ../../data/meshes/cube.off, scale: 0}}\n",
      "scene.yaml:3:64: objects[0].geometry.mesh.scale", "must be positive, got '0'");
  expectSceneError(
      "locations:\n  - name: flat\n    region: {hull: [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, "
      "0]]}\n",
      "scene.yaml:3:20: locations[0].region.hull",
      "the points span no volume (at least four points, not all in one plane)");
  expectSceneError("locations:\n  - name: b\n    region: {box: {min: [0, 0, 0], max: [1, 1, 0]}}\n",
                   "scene.yaml:3:41: locations[0].region.box.max",
                   "must exceed min in every coordinate (0 is not above 0)");
  expectSceneError(ball("    grasps:\n      - name: g\n        constraints:\n"
                        "          - {constraint: coincident, hand: origin, object: {line: "
                        "{point: [0, 0, 0], direction: [0, 0, 0]}}}\n"),
                   "scene.yaml:8:97: objects[0].grasps[0].constraints[0].object.line.direction",
                   "zero vector");
}

TEST(SceneFileError, DuplicateNamesAcrossRobotsToolsObjectsAndLocations) {
  expectSceneError(twinRobot() + ball("", "Twin"), "scene.yaml:5:11: objects[0].name",
                   "duplicate name 'Twin' (also robots[0].name at line 2)");
  expectSceneError(twinRobot("    tools:\n      - {name: twin, link: left_flange}\n"),
                   "scene.yaml:5:16: robots[0].tools[0].name", "duplicate name 'twin'");
  expectSceneError(ball() + "locations:\n  - {name: ball, region: {box: {size: [1, 1, 1]}}}\n",
                   "scene.yaml:6:12: locations[0].name", "duplicate name 'ball'");
  expectSceneError(
      ball("    grasps:\n      - {name: top, pose: {}}\n      - {name: TOP, pose: {}}\n"),
      "scene.yaml:7:9: objects[0].grasps[1]", "duplicate grasp name 'TOP'");
}

TEST(SceneFile, PlaceInNamesALocationAndPlacementSeedIsRead) {
  const SceneDescription scene =
      parse("settings: {placement_seed: 7}\n" + ball("    place_in: Tray\n") +
            "locations:\n  - {name: shelf, region: {box: {size: [1, 1, 1]}}}\n"
            "  - {name: tray, region: {box: {size: [1, 1, 1]}}}\n");
  EXPECT_EQ(scene.settings.placementSeed, 7U);
  EXPECT_EQ(scene.objects[0].placeIn, 1U);
  EXPECT_EQ(scene.objects[0].poseSource.key, "objects[0].place_in");
  EXPECT_FALSE(parse(ball()).objects[0].placeIn);
  EXPECT_EQ(parse(ball()).settings.placementSeed, 1U);
}

TEST(SceneFileError, PlaceInIsAMovableObjectsLocationInsteadOfAPose) {
  const std::string tray = "locations:\n  - {name: tray, region: {box: {size: [1, 1, 1]}}}\n";
  expectSceneError(ball("    place_in: trey\n") + tray, "scene.yaml:5:15: objects[0].place_in",
                   "unknown location 'trey' (did you mean 'tray'?)");
  expectSceneError(ball("    pose: {}\n    place_in: tray\n") + tray,
                   "scene.yaml:6:15: objects[0].place_in",
                   "an object has a pose or place_in, not both");
  expectSceneError(
      "objects:\n  - {name: post, geometry: {sphere: {radius: 1}}, place_in: tray}\n" + tray,
      "scene.yaml:2:61: objects[0].place_in",
      "only a movable object has place_in (set movable: true)");
  expectSceneError("settings: {placement_seed: -2}\n", "scene.yaml:1:28: settings.placement_seed",
                   "expected a non-negative integer, got '-2'");
}

TEST(SceneFileError, HomeOutsideJointLimits) {
  expectSceneError(twinRobot("    home: {left_j2: 2.5}\n"),
                   "scene.yaml:4:21: robots[0].home.left_j2",
                   "2.5 is outside the limits [-2, 2] of joint 'left_j2'");
  expectSceneError(twinRobot("    home: {left_j2: 120deg}\n"),
                   "scene.yaml:4:21: robots[0].home.left_j2",
                   "2.0944 is outside the limits [-2, 2] of joint 'left_j2'");
  ScratchDir dir;
  dir.write("raised.urdf",
            "<robot name='raised'><link name='a'/><link name='b'/>"
            "<joint name='lift' type='prismatic'><parent link='a'/><child link='b'/>"
            "<limit lower='0.5' upper='1' effort='0' velocity='1'/></joint></robot>");
  expectSceneError("robots:\n  - name: r\n    urdf: raised.urdf\n", "scene.yaml:2:5: robots[0]",
                   "joint 'lift' is not listed in home and 0 is outside its limits [0.5, 1]",
                   dir.file(""));
  expectSceneError("robots:\n  - name: r\n    urdf: raised.urdf\n    home: {lift: 30deg}\n",
                   "scene.yaml:4:18: robots[0].home.lift", "expected a number, got '30deg'",
                   dir.file(""));
}

TEST(SceneFileError, EpsilonMustBePositiveAndAtMostAHundredPercent) {
  expectSceneError("settings: {epsilon: 0}\n", "scene.yaml:1:21: settings.epsilon",
                   "must be positive, got '0'");
  expectSceneError("settings: {epsilon: -1%}\n", "scene.yaml:1:21: settings.epsilon",
                   "must be positive, got '-1%'");
  expectSceneError("settings: {epsilon: 150%}\n", "scene.yaml:1:21: settings.epsilon",
                   "a relative epsilon must be at most 100%, got '150%'");
  expectSceneError("settings: {epsilon: 1 cm}\n", "scene.yaml:1:21: settings.epsilon",
                   "expected a distance (0.01) or a percentage (1%), got '1 cm'");
  expectSceneError("settings: {joint_step: 0deg}\n", "scene.yaml:1:24: settings.joint_step",
                   "must be positive, got '0deg'");
  EXPECT_EQ(parse("settings: {epsilon: 100%}\n").settings.epsilon, 1.0);
}

TEST(SceneFileError, ToolsHandsAndFingersMustFitTheUrdf) {
  expectSceneError(
      twinRobot("    tools:\n      - {name: left, link: left_link3, base_link: torso, ik: "
                "closed-form}\n"),
      "scene.yaml:5:62: robots[0].tools[0].ik",
      "the chain to 'left_link3' is not a five- or six-axis arm of Appendix A.3");
  expectSceneError(
      twinRobot("    tools:\n      - {name: left, link: left_flange, base_link: right_link1}\n"),
      "scene.yaml:5:52: robots[0].tools[0].base_link",
      "link 'right_link1' is not an ancestor of the tool link 'left_flange'");
  expectSceneError(twinRobot("    tools:\n      - {name: body, link: torso}\n"),
                   "scene.yaml:5:28: robots[0].tools[0].link",
                   "no movable joint leads to the tool link 'torso'");
  expectSceneError(twinWithHand("          links: [left_link3]\n"),
                   "scene.yaml:8:19: robots[0].tools[0].hand.links[0]",
                   "link 'left_link3' does not move with the tool link 'left_flange'");
  expectSceneError(twinWithHand("          links: [left_flange]\n"
                                "          fingers: {open: {left_j6: 0}, closed: {left_j6: 1}}\n"),
                   "scene.yaml:9:28: robots[0].tools[0].hand.fingers.open",
                   "joint 'left_j6' moves the arm, not a finger");
  expectSceneError(
      twinWithHand("          fingers: {open: {right_j6: 0}, closed: {right_j6: 1}}\n"),
      "scene.yaml:8:11: robots[0].tools[0].hand", "a hand needs links or shapes");
  expectSceneError(
      twinWithHand(
          "          links: [left_flange]\n"
          "          fingers: {open: {right_j6: 0, right_j5: 0}, closed: {right_j6: 1}}\n"),
      "scene.yaml:9:63: robots[0].tools[0].hand.fingers.closed",
      "joint 'right_j5' has no closed value");
  const std::string comau =
      "robots:\n"
      "  - name: comau\n"
      "    urdf: ../../data/robots/comau-left.urdf\n"
      "    tools:\n"
      "      - name: gripper\n"
      "        link: body6\n"
      "        hand:\n"
      "          links: [body7, body8]\n"
      "          fingers: {open: {finger0: 0.05, finger1: 0.05}, closed: {finger0: 0, finger1: "
      "0}}\n";
  EXPECT_EQ(parse(comau).robots[0].tools[0].hand->links.size(), 2u);
  expectSceneError(comau.substr(0, comau.find("          fingers")),
                   "scene.yaml:8:19: robots[0].tools[0].hand.links[0]",
                   "link 'body7' does not move with the tool link 'body6' (only finger joints may "
                   "lie between them)");
  expectSceneError(comau.substr(0, comau.rfind("0}}")) + "0.07}}\n",
                   "scene.yaml:9:89: robots[0].tools[0].hand.fingers.closed.finger1",
                   "0.07 is outside the limits [0, 0.06] of joint 'finger1'");
}

TEST(SceneFileError, GraspsFollowTable51) {
  const auto grasp = [](const std::string& constraint) {
    return ball("    grasps:\n      - name: g\n        constraints:\n          - " + constraint +
                "\n");
  };
  expectSceneError(grasp("{constraint: parallel, hand: origin, object: z-axis}"),
                   "scene.yaml:8:13: objects[0].grasps[0].constraints[0]",
                   "Parallel(Point, Line) is not a defined constraint (Table 5.1)");
  EXPECT_NO_THROW(parse(grasp("{constraint: coincident, hand: z-axis, object: origin}")));
  expectSceneError(grasp("{constraint: distance, hand: origin, object: z-axis}"),
                   "scene.yaml:8:13: objects[0].grasps[0].constraints[0]",
                   "missing key 'value' (the distance in metres)");
  expectSceneError(grasp("{constraint: parallel, hand: z-axis, object: z-axis, value: 1}"),
                   "scene.yaml:8:73: objects[0].grasps[0].constraints[0].value",
                   "only a distance constraint takes a value");
  expectSceneError(grasp("{constraint: coincident, hand: origin, object: z-axsi}"),
                   "scene.yaml:8:60: objects[0].grasps[0].constraints[0].object",
                   "unknown value 'z-axsi' (did you mean 'z-axis'?)");
  expectSceneError(ball("    grasps:\n      - {name: g, pose: {}, free: {rotate_z: [1, -1]}}\n"),
                   "scene.yaml:6:46: objects[0].grasps[0].free.rotate_z",
                   "lower bound above upper bound");
  expectSceneError(ball("    grasps:\n      - {name: g}\n"), "scene.yaml:6:9: objects[0].grasps[0]",
                   "expected exactly one of constraints, pose, got none");
  expectSceneError(
      "objects:\n  - name: wall\n    geometry: {box: {size: [1, 1, 1]}}\n"
      "    grasps: []\n",
      "scene.yaml:4:13: objects[0].grasps", "only a movable object has grasps (set movable: true)");
  expectSceneError(ball("    resting_faces: some\n"), "scene.yaml:5:20: objects[0].resting_faces",
                   "expected auto or a list of face normals, got 'some'");
}

// Every prefix of the example (cut at each line) and seeded random byte changes either read or
// fail with one InputError line; nothing else escapes and nothing hangs.
TEST(SceneFileError, TruncatedAndMutatedFilesOnlyGiveInputErrors) {
  const std::string text = slurp(exampleFile("scenes/two-arms-table.yaml"));
  const auto check = [](const std::string& variant) {
    try {
      parse(variant);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  for (std::size_t end = text.find('\n'); end != std::string::npos;
       end = text.find('\n', end + 1)) {
    check(text.substr(0, end));
  }
  std::mt19937_64 random(11);
  const std::string replacements = "-:[]{},#&*!|>'\"%@` \n\t0a.";
  for (int trial = 0; trial < 400; ++trial) {
    std::string variant = text;
    for (int change = 0; change < 3; ++change) {
      variant[random() % variant.size()] = replacements[random() % replacements.size()];
    }
    check(variant);
  }
}

}  // namespace
}  // namespace kaboum::io
