// `kaboum execute` (docs/execution.md): the plan files of tests/exec/data run from the command
// line — files per robot, the JSON-lines stream, sensing from a hidden state or the terminal, a
// failed precondition (exit 1) — and every kind of bad input as one line with exit code 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "exec_fixtures.hpp"

namespace kaboum::exec {

namespace {

std::string quoted(const std::string& path) {
  return "'" + path + "' ";
}

std::string exampleFiles(const std::string& folder, const std::string& problem) {
  return quoted(testing::exampleFile(folder + "/domain.pddl")) +
         quoted(testing::exampleFile(folder + "/" + problem)) +
         quoted(testing::exampleFile(folder + "/scene.yaml"));
}

std::string pickAndPlaceRun() {
  return "execute " + exampleFiles("pick-and-place", "problem.pddl") +
         quoted(execData("pick-and-place.plan.json"));
}

std::string bartenderRun() {
  return "execute " + exampleFiles("bartender", "problem-1.pddl") +
         quoted(execData("bartender-1.plan.json"));
}

test::CliResult run(const test::ScratchDir& dir, const std::string& arguments) {
  return test::runCli(dir, arguments + test::sharedCacheOption());
}

// Exit code 2 and one line on stderr containing `message`.
void expectBadInput(const test::CliResult& result, const std::string& message) {
  EXPECT_EQ(result.exitCode, 2) << result.out << result.err;
  EXPECT_EQ(test::lineCount(result.err), 1U) << result.err;
  EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
}

}  // namespace

TEST(ExecuteCli, WritesEachRobotsTrajectoryAsCsvAndJsonAndTheExecution) {
  test::ScratchDir dir;
  const test::CliResult result =
      run(dir, pickAndPlaceRun() + "--rate 200 --out-dir " + quoted(dir.file("out")));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("action:       0.000 s  (pickup kr5 block left)"), std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("execution: goal reached after 2 action(s)"), std::string::npos);
  const nlohmann::json execution =
      nlohmann::json::parse(test::slurp(dir.file("out/execution.json")));
  EXPECT_EQ(execution["reached_goal"], true);
  const double seconds = execution["seconds"];
  const nlohmann::json robot = nlohmann::json::parse(test::slurp(dir.file("out/kr5.json")));
  EXPECT_EQ(robot["format"], "kaboum-trajectory");
  EXPECT_EQ(robot["joints"].size(), 6U);
  const std::size_t samples = robot["time"].size();
  EXPECT_EQ(samples, static_cast<std::size_t>(std::floor(seconds * 200)) + 2);
  EXPECT_EQ(robot["q"].size(), samples);
  const std::string csv = test::slurp(dir.file("out/kr5.csv"));
  EXPECT_EQ(test::lineCount(csv), samples + 1);
  EXPECT_EQ(csv.substr(0, csv.find(',', 5)), "time,q.shoulder_yaw");
}

TEST(ExecuteCli, FollowsTheHiddenStateAndStreamsJsonLines) {
  test::ScratchDir dir;
  const test::CliResult result =
      run(dir, bartenderRun() + "--rate 50 --json --profile blended --hidden " +
                   quoted(execData("bartender-1-empty.hidden.pddl")));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string last = result.out.substr(result.out.rfind('\n', result.out.size() - 2) + 1);
  const nlohmann::json end = nlohmann::json::parse(last);
  EXPECT_EQ(end["type"], "end");
  EXPECT_EQ(end["branch"]["outcomes"], nlohmann::json::array({"(isemptybottle o1) true"}));
  EXPECT_EQ(end["branch"]["actions"].size(), 6U);
  EXPECT_GT(test::lineCount(result.out), 50U);

  const test::CliResult full =
      run(dir, bartenderRun() + "-q --hidden " + quoted(execData("bartender-1-full.hidden.pddl")));
  ASSERT_EQ(full.exitCode, 0) << full.err;
  EXPECT_EQ(full.out,
            "execution: goal reached after 1 action(s) in 0.000 s; branch: (isemptybottle o1) "
            "false\n");
}

TEST(ExecuteCli, AsksOnTheTerminal) {
  test::ScratchDir dir;
  const std::string input = dir.write("answers.txt", "yes\n");
  const test::CliResult result = run(dir, bartenderRun() + "-q --ask <" + quoted(input));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("branch: (isemptybottle o1) true"), std::string::npos);
  EXPECT_NE(result.err.find("(isemptybottle o1)? [y/n] "), std::string::npos);
  const std::string maybe = dir.write("maybe.txt", "maybe\n");
  expectBadInput(run(dir, bartenderRun() + "-q --ask <" + quoted(maybe)),
                 "'maybe' is no outcome of (isemptybottle o1)");
}

TEST(ExecuteCli, AFailedPreconditionStopsWithExitCode1) {
  test::ScratchDir dir;
  const std::string state = dir.write(
      "state.json",
      R"({"objects": {"block": {"position": [0.45, 0.35, -0.0734], "quaternion_wxyz": [1, 0, 0, 0]}}})");
  const test::CliResult result = run(dir, pickAndPlaceRun() + "-q --world-state " + quoted(state));
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_EQ(result.out,
            "execution: STOPPED at 0.000 s: nodes[2] (pickup kr5 block left): step 3 (grasp): "
            "object 'block' is 0.100 m and 0.0° from where robot 'kr5' grasps it\n");
}

TEST(ExecuteCli, BadInputIsOneLineWithExitCode2) {
  test::ScratchDir dir;
  const std::string empty = quoted(execData("bartender-1-empty.hidden.pddl"));
  expectBadInput(run(dir, bartenderRun() + "--ask --hidden " + empty),
                 "--ask and --hidden: give one sensing source");
  expectBadInput(run(dir, pickAndPlaceRun() + "--rate 0"), "--rate 0: expected a rate");
  expectBadInput(run(dir, pickAndPlaceRun() + "--profile trapezoid"),
                 "--profile: 'trapezoid' is none of rest-to-rest, blended");
  expectBadInput(run(dir, bartenderRun()), "the plan branches on (isemptybottle o1)");
  const std::string moved =
      dir.write("moved.pddl", "(define (problem h)\n  (:hidden (isatlocation o1 dishwasher)))\n");
  expectBadInput(run(dir, bartenderRun() + "--hidden " + quoted(moved)),
                 "moved.pddl:2:3: hidden state is not one of the initial worlds the knowledge "
                 "admits");
  const std::string unknown =
      dir.write("unknown.pddl", "(define (problem h) (:hidden (isbroken o1)))\n");
  expectBadInput(run(dir, bartenderRun() + "--hidden " + quoted(unknown)), "unknown.pddl:1:");
  // A plan of another problem: pick and place's against the Bartender.
  expectBadInput(run(dir, "execute " + exampleFiles("bartender", "problem-1.pddl") +
                              quoted(execData("pick-and-place.plan.json"))),
                 "pick-and-place.plan.json: initial_state.objects: the scene has no object "
                 "'block'");
  const std::string state = dir.write("state.json", R"({"objects": {"cup": {}}})");
  expectBadInput(run(dir, pickAndPlaceRun() + "--world-state " + quoted(state)),
                 "state.json: objects.cup: no object 'cup' in the scene");
}

TEST(ExecuteCli, HelpNamesEveryOption) {
  test::ScratchDir dir;
  const test::CliResult result = test::runCli(dir, "execute --help");
  EXPECT_EQ(result.exitCode, 0);
  for (const char* option : {"--hidden", "--ask", "--world-state", "--out-dir", "--rate",
                             "--profile", "--json", "--quiet"}) {
    EXPECT_NE(result.out.find(option), std::string::npos) << option;
  }
}

}  // namespace kaboum::exec
