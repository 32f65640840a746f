// `kaboum motion`: plans on the KR5 cell, its path file checked by `kaboum verify-path` (FCL on
// the original meshes), JSON output, tool-pose and Cartesian goals, and bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::motion {

using namespace kaboum::testing;

namespace {

std::string kr5Motion(const std::string& arguments) {
  return "motion '" + exampleFile("scenes/kr5-cell.yaml") + "' --robot kr5" +
         test::sharedCacheOption() + " " + arguments;
}

TEST(MotionCli, PlansAroundThePoleAndTheIndependentVerifierFindsThePathFree) {
  const test::ScratchDir dir;
  const std::string path = dir.file("path.json");
  const test::CliResult planned =
      test::runCli(dir, kr5Motion("--to shoulder_yaw=-60deg -o '" + path + "'"));
  ASSERT_EQ(planned.exitCode, 0) << planned.err;
  EXPECT_NE(planned.out.find("status:    solved"), std::string::npos) << planned.out;
  EXPECT_NE(planned.out.find("planner:   rrtconnect"), std::string::npos) << planned.out;
  const io::PathFile file = io::readPathFile(path);
  EXPECT_EQ(file.robots, std::vector<std::string>{"kr5"});
  EXPECT_GE(file.waypoints.size(), 3u);
  const test::CliResult verified =
      test::runCli(dir, "verify-path '" + exampleFile("scenes/kr5-cell.yaml") + "' '" + path + "'" +
                            test::sharedCacheOption() + " --quiet");
  EXPECT_EQ(verified.exitCode, 0) << verified.out << verified.err;
}

TEST(MotionCli, JsonGivesStatusPathAndStatistics) {
  const test::ScratchDir dir;
  const test::CliResult result = test::runCli(dir, kr5Motion("--to shoulder_yaw=-60deg --json"));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["status"], "solved");
  EXPECT_EQ(json["planner"], "rrtconnect");
  EXPECT_EQ(json["path"]["format"], "kaboum-path");
  EXPECT_EQ(json["path"]["waypoints"][0][0], 60 * std::numbers::pi / 180);
  EXPECT_GT(json["statistics"]["motion_checks"].get<int>(), 0);
  EXPECT_LE(json["statistics"]["length"].get<double>(),
            json["statistics"]["planned_length"].get<double>());
}

TEST(MotionCli, ReachesAToolPoseDirectlyAndAlongALine) {
  const test::ScratchDir dir;
  const std::string from = "--from shoulder_yaw=12deg,wrist_pitch=35deg ";
  EXPECT_EQ(test::runCli(dir, kr5Motion(from + "--to-pose 0.3,0.1,0.3 -q")).out, "solved\n");
  EXPECT_EQ(test::runCli(dir, kr5Motion(from + "--to-pose 0.38,0.15,0.25 --cartesian -q")).out,
            "solved\n");
}

TEST(MotionCli, TheTimeLimitIsAnHonestFailure) {
  const test::ScratchDir dir;
  const test::CliResult result =
      test::runCli(dir, kr5Motion("--to shoulder_yaw=-60deg --time-limit 1e-9"));
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.out.find("status:    time-limit"), std::string::npos) << result.out;
}

TEST(MotionCli, BadInputGivesOneLineAndExitCodeTwo) {
  const test::ScratchDir dir;
  const std::string scene = exampleFile("scenes/kr5-cell.yaml");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--to home --robot nobody", "--robot: no robot named 'nobody' in the scene"},
      {"--to 1,2,3",
       "--to: 3 values for 6 joints (write 'home', all values, or JOINT=VALUE "
       "pairs)"},
      {"--to elbow=1", "--to: no joint named 'elbow' in the moving robots"},
      {"--to shoulder_yaw=abc", "--to: 'abc' is not a number"},
      {"--to home --to-pose 0,0,1", "give exactly one of --to and --to-pose"},
      {"--to home --cartesian", "--cartesian needs --to-pose"},
      {"--to-pose 0,0", "--to-pose: '0,0' is not x,y,z or x,y,z,roll,pitch,yaw"},
      {"--to-pose 0.3,0.1,0.3 --tool gripper", "--tool: robot 'kr5' has no tool 'gripper'"},
      {"--to-pose 3,0,0.3", "--to-pose: no IK solution reaches the pose"},
      {"--to home --planner teleport",
       "--planner: teleport not in {biest,est,prm,rrt,rrtconnect,rrtstar} (see --help)"},
      {"--from shoulder_yaw=0 --to home",
       scene + ": start: robot 'kr5' link 'wrist' collides with object 'pole'"},
      {"--to shoulder_pitch=3", scene + ": goal: shoulder_pitch of robot 'kr5' is 3, outside its "
                                        "limits [-1.74533, 2.35619]"},
  };
  for (const auto& [arguments, message] : cases) {
    const test::CliResult result = test::runCli(dir, kr5Motion(arguments));
    EXPECT_EQ(result.exitCode, 2) << arguments;
    EXPECT_EQ(result.err, "kaboum: error: " + message + "\n") << arguments;
    EXPECT_EQ(result.out, "") << arguments;
  }
}

TEST(MotionCli, HelpNamesEveryOption) {
  const test::ScratchDir dir;
  const test::CliResult result = test::runCli(dir, "motion --help");
  EXPECT_EQ(result.exitCode, 0);
  for (const char* option :
       {"--robot", "--from", "--to", "--to-pose", "--tool", "--cartesian", "--planner",
        "--time-limit", "--seed", "--sweep-epsilon", "--range", "--shortcuts", "--output", "--json",
        "--quiet", "--no-cache", "--cache-dir"}) {
    EXPECT_NE(result.out.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace kaboum::motion
