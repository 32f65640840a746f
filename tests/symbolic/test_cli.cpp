// CLI tests: `kaboum plan`, `kaboum validate` and `kaboum stacked` as users run them, including
// exit codes and one-line errors for each class of bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "kaboum/symbolic/sexpr.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

using testing::pddlPath;
using testing::runCli;
using testing::writeTempFile;

const std::string kDomain = pddlPath("blocks/domain.pddl");
const std::string kProblem = pddlPath("blocks/probBLOCKS-6-0.pddl");

TEST(Cli, PlanWritesAnIpcPlanThatValidates) {
  const std::string planFile = writeTempFile("blocks.plan", "");
  const auto planned =
      runCli("plan " + kDomain + " " + kProblem + " --quiet --plan-out " + planFile);
  ASSERT_EQ(planned.exitCode, 0) << planned.output;
  const std::string text = readTextFile(planFile);
  EXPECT_EQ(text.front(), '(');
  const auto validated = runCli("validate " + kDomain + " " + kProblem + " " + planFile);
  EXPECT_EQ(validated.exitCode, 0) << validated.output;
  EXPECT_NE(validated.output.find("valid plan of"), std::string::npos);
}

TEST(Cli, PlanJsonHasStatisticsForEveryMode) {
  for (const std::string mode : {"dfs", "bfs", "ids", "gbfs", "astar"}) {
    const auto result = runCli("plan " + pddlPath("blocks/domain.pddl") + " " +
                               pddlPath("blocks/probBLOCKS-4-0.pddl") + " --json --search " + mode +
                               " --heuristic add");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const auto json = nlohmann::json::parse(result.output);
    EXPECT_EQ(json["status"], "solved");
    EXPECT_EQ(json["plan_length"], json["plan"].size());
    EXPECT_GT(json["expanded"].get<int>(), 0) << mode;
    EXPECT_GE(json["generated"].get<int>(), json["plan_length"].get<int>());
    for (const char* key : {"parse", "ground", "search", "total"}) {
      EXPECT_GE(json["time"][key].get<double>(), 0.0) << key;
    }
    EXPECT_TRUE(json["attachments"].is_array());
  }
}

// The default gbfs (lazy, FF alternated with landmark count) and the older single-heuristic eager
// search selected by --eager --no-landmarks both write plans that validate.
TEST(Cli, GreedySearchVariantsWritePlansThatValidate) {
  for (const std::string flags : {"", "--eager --no-landmarks", "--eager", "--heuristic lmcount"}) {
    const std::string planFile = writeTempFile("variant.plan", "");
    const auto planned = runCli("plan " + kDomain + " " + kProblem + " --quiet --plan-out " +
                                planFile + " " + flags);
    ASSERT_EQ(planned.exitCode, 0) << flags << ": " << planned.output;
    const auto validated = runCli("validate " + kDomain + " " + kProblem + " " + planFile);
    EXPECT_EQ(validated.exitCode, 0) << flags << ": " << validated.output;
  }
}

TEST(Cli, LimitsEndWithExitCodeOneAndAStatus) {
  const std::string dir = std::filesystem::path(writeTempFile("x", "")).parent_path().string();
  ASSERT_EQ(runCli("stacked 9 --quiet --out-dir " + dir).exitCode, 0);
  const std::string domain = dir + "/stacked-domain.pddl";
  const std::string problem = dir + "/stacked-9.pddl";
  auto result = runCli("plan " + domain + " " + problem + " --search bfs --node-limit 10 --json");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(nlohmann::json::parse(result.output)["status"], "node-limit");
  result = runCli("plan " + domain + " " + problem + " --search bfs --memory-limit 0.05 --json");
  EXPECT_EQ(nlohmann::json::parse(result.output)["status"], "memory-limit");
  result = runCli("plan " + domain + " " + problem + " --search dfs --time-limit 0.000001 --json");
  EXPECT_EQ(nlohmann::json::parse(result.output)["status"], "time-limit");
}

TEST(Cli, ValidateReportsAnInvalidPlanWithExitCodeOne) {
  const std::string planFile = writeTempFile("bad.plan", "(pick-up b)\n(stack b b)\n");
  const auto result = runCli("validate " + kDomain + " " + kProblem + " " + planFile);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.output.find("invalid: step"), std::string::npos) << result.output;
}

// Each class of bad input: exit code 2 and exactly one line naming the place.
void expectBadInput(const std::string& arguments, const std::string& expected) {
  const auto result = runCli(arguments);
  EXPECT_EQ(result.exitCode, 2) << arguments;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
}

TEST(Cli, BadInputGivesOneLineAndExitCodeTwo) {
  const std::string bad =
      writeTempFile("bad-domain.pddl", "(define (domain d)\n  (:predicates (p)\n");
  expectBadInput("plan " + bad + " " + kProblem, "bad-domain.pddl:2:3: expected ')'");
  const std::string undefined =
      writeTempFile("undef.pddl",
                    "(define (domain blocks)\n (:predicates (p))\n (:action a :parameters ()\n"
                    "  :precondition (q) :effect (p)))\n");
  expectBadInput("plan " + undefined + " " + kProblem, "undef.pddl:4:18: undefined predicate 'q'");
  expectBadInput("plan /nonexistent/domain.pddl " + kProblem,
                 "/nonexistent/domain.pddl: cannot open file");
  const std::string module = writeTempFile(
      "module.pddl", "(define (domain blocks) (:modules (m conditionchecker f@libnone.so)))");
  const std::string problem =
      writeTempFile("module-problem.pddl", "(define (problem p) (:domain blocks) (:goal (and)))");
  expectBadInput("plan " + module + " " + problem, "cannot load library 'libnone.so'");
  const std::string plan = writeTempFile("unknown.plan", "(teleport a)\n");
  expectBadInput("validate " + kDomain + " " + kProblem + " " + plan,
                 "unknown.plan:1:2: undefined action 'teleport'");
  expectBadInput("plan " + kDomain + " " + kProblem + " --search beam", "--search");
  expectBadInput("stacked 1", "n must be at least 2");
}

}  // namespace
}  // namespace kaboum::symbolic
