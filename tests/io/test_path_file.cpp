// The path file (docs/path-format.md): a written path reads back exactly, its JSON has the
// documented keys, and each class of bad input gives one line naming the file and the key.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "io_test_support.hpp"
#include "kaboum/io/path_file.hpp"

namespace kaboum::io {

namespace {

using test::ScratchDir;
using test::slurp;

PathFile twoRobotPath() {
  PathFile path;
  path.scene = "examples/scenes/two-arms-table.yaml";
  path.robots = {"twin", "kr5"};
  path.waypoints = {{0.1, -0.2, 0.3, 1e-17, -0.0, 2.0 / 3.0}, {0.5, 0.25, -1.5, 0, 0, 3.125}};
  Pose grasp(Eigen::AngleAxisd(0.3, Vec3(0, 1, 1).normalized()));
  grasp.translation() = Vec3(0, 0.01, 0.14);
  path.held = {{"twin", "bottle", "left_flange", grasp}};
  return path;
}

// The message readPathFile throws for a file with `contents`, or "" when it reads.
std::string readError(const ScratchDir& dir, const std::string& contents) {
  try {
    readPathFile(dir.write("path.json", contents));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A file with `contents` must fail with one line: the file, then `where` (key, or line:column),
// then containing `what`.
void expectError(const std::string& contents, const std::string& where, const std::string& what) {
  const ScratchDir dir;
  const std::string message = readError(dir, contents);
  const std::string prefix = dir.file("path.json") + ":" + where;
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

const std::string kHeader = R"("format": "kaboum-path", "version": 1, )";

TEST(PathFile, WritesAndReadsBackEveryValueExactly) {
  const ScratchDir dir;
  const PathFile written = twoRobotPath();
  writePathFile(dir.file("path.json"), written);
  const PathFile read = readPathFile(dir.file("path.json"));
  EXPECT_EQ(read.scene, written.scene);
  EXPECT_EQ(read.robots, written.robots);
  EXPECT_EQ(read.waypoints, written.waypoints);
  ASSERT_EQ(read.held.size(), 1u);
  EXPECT_EQ(read.held[0].robot, "twin");
  EXPECT_EQ(read.held[0].object, "bottle");
  EXPECT_EQ(read.held[0].link, "left_flange");
  EXPECT_TRUE(read.held[0].objectInLink.isApprox(written.held[0].objectInLink, 1e-15));
  // One waypoint per line.
  EXPECT_NE(slurp(dir.file("path.json")).find("\n    [0.5,0.25,-1.5,0.0,0.0,3.125]"),
            std::string::npos)
      << slurp(dir.file("path.json"));
}

TEST(PathFile, JsonHasTheDocumentedKeys) {
  const nlohmann::json json = toJson(twoRobotPath());
  EXPECT_EQ(json.at("format"), "kaboum-path");
  EXPECT_EQ(json.at("version"), 1);
  EXPECT_EQ(json.at("scene"), "examples/scenes/two-arms-table.yaml");
  EXPECT_EQ(json.at("robots"), nlohmann::json({"twin", "kr5"}));
  EXPECT_EQ(json.at("waypoints").size(), 2u);
  EXPECT_EQ(json.size(), 6u);
  const nlohmann::json& held = json.at("held").at(0);
  EXPECT_EQ(held.at("link"), "left_flange");
  EXPECT_EQ(held.at("pose").at("position"), nlohmann::json({0.0, 0.01, 0.14}));
  EXPECT_EQ(held.at("pose").at("quaternion_wxyz").size(), 4u);
}

TEST(PathFile, OptionalKeysTakeTheirDefaults) {
  const ScratchDir dir;
  const PathFile path =
      readPathFile(dir.write("path.json", "{" + kHeader +
                                              R"("robots": ["a"], "waypoints": [[1, 2]],
                          "held": [{"robot": "a", "object": "o", "link": "l"}]})"));
  EXPECT_EQ(path.scene, "");
  EXPECT_EQ(path.waypoints, (std::vector<std::vector<double>>{{1, 2}}));
  EXPECT_TRUE(path.held.at(0).objectInLink.isApprox(Pose::Identity()));
}

TEST(PathFile, NotJsonNamesLineAndColumn) {
  expectError("{\"format\": \"kaboum-path\",\n  \"version\": 1,\n  \"robots\": [NaN]}",
              "3:14: ", "invalid JSON");
  expectError("", "1:1: ", "invalid JSON");
}

TEST(PathFile, WrongFormatOrVersion) {
  expectError(R"({"format": "kaboum-plan", "version": 1, "robots": ["a"], "waypoints": [[0]]})",
              " format: ", "expected \"kaboum-path\", got \"kaboum-plan\"");
  expectError(R"({"format": "kaboum-path", "version": 2, "robots": ["a"], "waypoints": [[0]]})",
              " version: ", "expected 1, got 2");
  expectError(R"([1, 2])", " expected an object", "got [1,2]");
}

TEST(PathFile, WaypointOfTheWrongLength) {
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": [[0, 1, 2], [0, 1], [0, 1, 2]]})",
              " waypoints[1]: ", "2 values, waypoints[0] has 3");
}

TEST(PathFile, NonNumbersAndNonFiniteNumbers) {
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": [[0, 1], [0, "1"]]})",
              " waypoints[1][1]: ", "expected a number, got \"1\"");
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": [[0, 1e999]]})",
              " invalid JSON: ", "number overflow");
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": [[0, null]]})",
              " waypoints[0][1]: ", "expected a number, got null");
}

TEST(PathFile, MissingAndUnknownKeys) {
  expectError(R"({"format": "kaboum-path", "robots": ["a"], "waypoints": [[0]]})",
              " version: ", "missing");
  expectError("{" + kHeader + R"("waypoints": [[0]]})", " robots: ", "missing");
  expectError("{" + kHeader + R"("robots": ["a"]})", " waypoints: ", "missing");
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": [[0]], "speed": 1})",
              " speed: ", "unknown key");
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": [[0]], "held": [{"robot": "a"}]})",
              " held[0].object: ", "missing");
  expectError("{" + kHeader +
                  R"("robots": ["a"], "waypoints": [[0]], "held": [{"robot": "a", "object": "o",
                     "link": "l", "pose": {"quaternion_wxyz": [0, 0, 0, 0]}}]})",
              " held[0].pose.quaternion_wxyz: ", "zero quaternion");
}

TEST(PathFile, EmptyAndRepeatedRobots) {
  expectError("{" + kHeader + R"("robots": [], "waypoints": [[0]]})", " robots: ", "no robot");
  expectError("{" + kHeader + R"("robots": ["a", "a"], "waypoints": [[0]]})",
              " robots[1]: ", "already robots[0]");
  expectError("{" + kHeader + R"("robots": ["a"], "waypoints": []})",
              " waypoints: ", "no waypoint");
}

TEST(PathFile, MissingFile) {
  const ScratchDir dir;
  try {
    readPathFile(dir.file("absent.json"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("absent.json") + ": cannot open file");
  }
}

}  // namespace

}  // namespace kaboum::io
