// `kaboum verify-path SCENE PATH`: exit code 0 for a free path, 1 for a colliding one, 2 for bad
// input with one line naming the file and key; --json, --quiet and the step options.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "../support/test_support.hpp"
#include "kaboum/io/path_file.hpp"

namespace kaboum::test {

namespace {

std::string twoArmsTable() {
  return "'" + exampleFile("scenes/two-arms-table.yaml") + "'";
}

// The twin robot's waypoint: home with left_j2 (variable 2) and left_j5 (variable 8) set.
std::vector<double> twin(double leftJ2, double leftJ5) {
  return {0, 0, leftJ2, 0.3, 1.2, 1.2, 0, 0, leftJ5, 1.0471975511965976, 0, 0};
}

std::string writePath(const ScratchDir& dir, const std::vector<std::vector<double>>& waypoints) {
  io::PathFile path;
  path.scene = "examples/scenes/two-arms-table.yaml";
  path.robots = {"twin"};
  path.waypoints = waypoints;
  io::writePathFile(dir.file("path.json"), path);
  return "'" + dir.file("path.json") + "'";
}

CliResult verifyPath(const ScratchDir& dir, const std::string& path, const std::string& options) {
  return runCli(dir, "verify-path " + twoArmsTable() + " " + path + " --no-cache " + options);
}

TEST(VerifyPathCli, FreePathExitsZeroWithItsClearance) {
  const ScratchDir dir;
  const CliResult result = verifyPath(
      dir, writePath(dir, {twin(0.3, 1.0471975511965976), twin(0.8, 1.0471975511965976)}), "");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("clearance:"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("verdict:    collision-free\n"), std::string::npos) << result.out;
  EXPECT_EQ(result.err, "");
}

TEST(VerifyPathCli, CollidingPathExitsOneNamingBothParties) {
  const ScratchDir dir;
  const std::string path = writePath(dir, {twin(1.25, -2), twin(1.25, 2)});
  const CliResult result = verifyPath(dir, path, "");
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_NE(result.out.find("collision:  robot 'twin' link 'left_flange' with object 'table', "
                            "segment 0 at 0."),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("verdict:    1 collision(s)\n"), std::string::npos) << result.out;

  const CliResult quiet = verifyPath(dir, path, "--quiet");
  EXPECT_EQ(quiet.exitCode, 1);
  EXPECT_EQ(quiet.out, "verdict:    1 collision(s)\n");
}

TEST(VerifyPathCli, JsonReportsSamplesClearanceAndCollisions) {
  const ScratchDir dir;
  const CliResult result = verifyPath(dir, writePath(dir, {twin(1.25, -2), twin(1.25, 2)}),
                                      "--json --joint-step 1 --tool-step 2");
  ASSERT_EQ(result.exitCode, 1) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  EXPECT_FALSE(json.at("collision_free").get<bool>());
  EXPECT_GT(json.at("samples").get<int>(), 100);
  EXPECT_GT(json.at("pairs").get<int>(), 0);
  EXPECT_DOUBLE_EQ(json.at("tool_step").get<double>(), 0.002);
  EXPECT_DOUBLE_EQ(json.at("joint_step").get<double>(), std::numbers::pi / 180);
  EXPECT_EQ(json.at("clearance").at("distance").get<double>(), 0.0);
  const nlohmann::json& collision = json.at("collisions").at(0);
  EXPECT_EQ(collision.at("first").at("link"), "left_flange");
  EXPECT_EQ(collision.at("first").at("robot"), "twin");
  EXPECT_TRUE(collision.at("first").at("object").is_null());
  EXPECT_EQ(collision.at("second").at("object"), "table");
  EXPECT_EQ(collision.at("second").at("description"), "object 'table'");
  EXPECT_EQ(collision.at("from").at("segment"), 0);
  EXPECT_GT(collision.at("samples").get<int>(), 0);
}

// verify-path with a path file of `contents` exits with 2 and one line starting with the file.
void expectBadPath(const std::string& contents, const std::string& what) {
  const ScratchDir dir;
  const std::string file = dir.write("path.json", contents);
  const CliResult result = verifyPath(dir, "'" + file + "'", "");
  EXPECT_EQ(result.exitCode, 2) << result.out;
  EXPECT_EQ(result.err.rfind("kaboum: error: " + file + ":", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(what), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << result.err;
  EXPECT_EQ(result.out, "");
}

const std::string kHeader = R"({"format": "kaboum-path", "version": 1, )";

TEST(VerifyPathCli, BadPathFilesExitTwoWithOneLine) {
  expectBadPath(kHeader + R"("robots": ["kr5"], "waypoints": [[0]]})",
                "robots[0]: no robot 'kr5' in the scene");
  expectBadPath(kHeader + R"("robots": ["twin"], "waypoints": [[0, 0, 0]]})",
                "waypoints[0]: 3 values, but robots 'twin' have 12 joints");
  expectBadPath(
      kHeader + R"("robots": ["twin"], "waypoints": [[3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]]})",
      "waypoints[0][0]: joint 'left_j1' of robot 'twin' at 3 is outside its limits");
  expectBadPath("{\"format\": \"kaboum-path\",\n \"version\": 1,,}",
                ":2:15: invalid JSON: syntax error");
  expectBadPath(kHeader + R"("robots": ["twin"], "waypoints": [[0], [0, 1]]})",
                "waypoints[1]: 2 values, waypoints[0] has 1");
}

TEST(VerifyPathCli, BadStepsExitTwo) {
  const ScratchDir dir;
  const std::string path = writePath(dir, {twin(0.3, 1.0)});
  EXPECT_EQ(verifyPath(dir, path, "--joint-step 0").err,
            "kaboum: error: --joint-step: must be a positive number of degrees\n");
  EXPECT_EQ(verifyPath(dir, path, "--tool-step -1").exitCode, 2);
}

}  // namespace

}  // namespace kaboum::test
