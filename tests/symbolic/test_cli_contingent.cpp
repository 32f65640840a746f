// CLI tests of `kaboum contingent`, `kaboum contingent-validate` and `kaboum force-sensing` as
// users run them: tree and JSON output, validation and hidden-state execution, exit codes, and
// one-line errors for each class of bad input.
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

std::string instance(const std::string& name, const std::string& file) {
  return pddlPath("contingent/" + name + "/" + file);
}

std::string lineCount(const std::string& text) {
  return std::to_string(std::count(text.begin(), text.end(), '\n'));
}

TEST(CliContingent, ForceSensingPlanIsATreeThatValidates) {
  const std::string dir = std::filesystem::path(writeTempFile("x", "")).parent_path().string();
  ASSERT_EQ(runCli("force-sensing 2 --quiet --out-dir " + dir).exitCode, 0);
  const std::string domain = dir + "/force-sensing-domain.pddl";
  const std::string problem = dir + "/force-sensing-2.pddl";
  const std::string planFile = dir + "/fs2.plan";
  const auto planned =
      runCli("contingent " + domain + " " + problem + " --quiet --plan-out " + planFile);
  ASSERT_EQ(planned.exitCode, 0) << planned.output;
  const std::string text = readTextFile(planFile);
  EXPECT_EQ(text.rfind("(plan\n  (grasp o", 0), 0u) << text;
  EXPECT_NE(text.find("\n  (branch (isspillable o"), std::string::npos) << text;
  EXPECT_NE(text.find("\n    (true\n      (transferupright o"), std::string::npos) << text;
  const auto validated = runCli("contingent-validate " + domain + " " + problem + " " + planFile);
  EXPECT_EQ(validated.exitCode, 0) << validated.output;
  EXPECT_NE(validated.output.find("valid: every branch reaches the goal (4 branch(es)"),
            std::string::npos)
      << validated.output;
}

TEST(CliContingent, JsonHasThePlanDagAndTreeMetrics) {
  const auto result = runCli("contingent " + instance("ebtcs", "d.pddl") + " " +
                             instance("ebtcs", "p.pddl") + " --json");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const auto json = nlohmann::json::parse(result.output);
  EXPECT_EQ(json["status"], "solved");
  EXPECT_EQ(json["initial_worlds"], 10);
  EXPECT_EQ(json["tree"]["leaves"], 10.0);  // one leaf per possible armed package
  const auto& nodes = json["plan"]["nodes"];
  ASSERT_FALSE(nodes.empty());
  std::size_t branches = 0;
  for (const auto& node : nodes) {
    if (node["kind"] == "branch") {
      ++branches;
      EXPECT_TRUE(node.contains("on_true") && node.contains("on_false"));
    }
  }
  EXPECT_GE(branches, 9u);
  EXPECT_GT(json["expanded"].get<int>(), 0);
}

TEST(CliContingent, ValidateExecutesEveryHiddenState) {
  const std::string planFile = writeTempFile("unix.plan", "");
  const std::string d = instance("unix", "d.pddl");
  const std::string p = instance("unix", "p.pddl");
  ASSERT_EQ(runCli("contingent " + d + " " + p + " --quiet --plan-out " + planFile).exitCode, 0);
  const auto result = runCli("contingent-validate " + d + " " + p + " " + planFile + " --hidden " +
                             instance("unix", "hidden.pddl") + " --json");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const auto json = nlohmann::json::parse(result.output);
  EXPECT_TRUE(json["valid"].get<bool>());
  ASSERT_FALSE(json["executions"].empty());
  for (const auto& run : json["executions"]) {
    EXPECT_TRUE(run["reached_goal"].get<bool>()) << run.dump();
    EXPECT_NE(run["steps"].dump().find("(mv my-file"), std::string::npos) << run.dump();
  }
}

TEST(CliContingent, InvalidPlanExitsOneAndNamesTheStep) {
  const std::string dir = std::filesystem::path(writeTempFile("x", "")).parent_path().string();
  ASSERT_EQ(runCli("force-sensing 1 --quiet --out-dir " + dir).exitCode, 0);
  const std::string plan =
      writeTempFile("bad.plan", "(plan (grasp o1)\n  (transferfast o1) (ungrasp o1))\n");
  const auto result = runCli("contingent-validate " + dir + "/force-sensing-domain.pddl " + dir +
                             "/force-sensing-1.pddl " + plan);
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_NE(result.output.find("bad.plan:2:3: precondition of (transferfast o1)"),
            std::string::npos)
      << result.output;
}

TEST(CliContingent, LimitsEndWithExitCodeOne) {
  const std::string dir = std::filesystem::path(writeTempFile("x", "")).parent_path().string();
  ASSERT_EQ(runCli("force-sensing 8 --quiet --out-dir " + dir).exitCode, 0);
  const auto result = runCli("contingent " + dir + "/force-sensing-domain.pddl " + dir +
                             "/force-sensing-8.pddl --node-limit 5 --json");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(nlohmann::json::parse(result.output)["status"], "node-limit");
}

TEST(CliContingent, EverySearchModeGivesAPlanThatValidates) {
  const std::string d = instance("ebtcs", "d.pddl");
  const std::string p = instance("ebtcs", "p.pddl");
  for (const std::string mode : {"gbfs", "astar", "bfs", "dfs"}) {
    const std::string planFile = writeTempFile("ebtcs-" + mode + ".plan", "");
    const auto planned = runCli("contingent " + d + " " + p + " --quiet --search " + mode +
                                " --plan-out " + planFile);
    ASSERT_EQ(planned.exitCode, 0) << mode << ": " << planned.output;
    const auto validated = runCli("contingent-validate " + d + " " + p + " " + planFile +
                                  " --hidden " + instance("ebtcs", "hidden.pddl"));
    EXPECT_EQ(validated.exitCode, 0) << mode << ": " << validated.output;
  }
  const auto json = runCli("contingent " + d + " " + p + " --search bfs --json");
  ASSERT_EQ(json.exitCode, 0) << json.output;
  EXPECT_EQ(nlohmann::json::parse(json.output)["search"], "bfs");
}

TEST(CliContingent, ScenariosNeedTheToyGeometry) {
  const std::string d = instance("scenarios", "bimanual-assembly-domain.pddl");
  const std::string p = instance("scenarios", "bimanual-assembly.pddl");
  const auto without = runCli("contingent " + d + " " + p);
  EXPECT_EQ(without.exitCode, 2) << without.output;
  EXPECT_EQ(lineCount(without.output), "1") << without.output;
  EXPECT_NE(without.output.find("reaches"), std::string::npos) << without.output;
  const auto with = runCli("contingent " + d + " " + p + " --toy-geometry --quiet");
  EXPECT_EQ(with.exitCode, 0) << with.output;
  EXPECT_NE(with.output.find("(assemblepipetree robot1 o3 o4)"), std::string::npos);
}

void expectBadInput(const std::string& arguments, const std::string& expected) {
  const auto result = runCli(arguments);
  EXPECT_EQ(result.exitCode, 2) << arguments << "\n" << result.output;
  EXPECT_EQ(lineCount(result.output), "1") << result.output;
  EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
}

TEST(CliContingent, BadInputGivesOneLineAndExitCodeTwo) {
  const std::string sensingDomain =
      writeTempFile("sense.pddl",
                    "(define (domain d) (:predicates (a) (b))\n"
                    "  (:action s :effect (a) :observe (a))\n  (:action t :observe (b)))\n");
  const std::string domain = writeTempFile(
      "d.pddl", "(define (domain d) (:predicates (a) (b)) (:action t :observe (b)))\n");
  const auto problem = [](const std::string& name, const std::string& body) {
    return writeTempFile(name, "(define (problem p) (:domain d)\n" + body + ")\n");
  };
  const std::string good = problem("good.pddl", "(:init (unknown (b))) (:goal (b))");
  expectBadInput("contingent " + sensingDomain + " " + good,
                 "sense.pddl:2:22: sensing action changes the atom it observes (a)");
  expectBadInput(
      "contingent " + domain + " " + problem("c.pddl", "(:init (a) (not (a))) (:goal (a))"),
      "c.pddl:2:12: contradictory initial knowledge");
  expectBadInput("contingent " + domain + " " +
                     problem("n.pddl", "(:init (a) (b) (oneof (a) (b))) (:goal (a))"),
                 "n.pddl:2:1: contradictory initial knowledge: no world satisfies");
  expectBadInput(
      "contingent " + domain + " " + problem("g.pddl", "(:init (unknown (a)))\n (:goal (a))"),
      "g.pddl:3:9: goal atom (a) is unknown initially");
  expectBadInput("contingent " + domain + " " + problem("o.pddl", "(:init (oneof)) (:goal (b))"),
                 "o.pddl:2:8: 'oneof' needs at least one atom");
  expectBadInput(
      "contingent " + domain + " " + problem("o2.pddl", "(:init (oneof (a) (or (b)))) (:goal (b))"),
      "o2.pddl:2:19: malformed 'oneof'");
  expectBadInput("contingent " + domain + " " + good + " --max-worlds 1",
                 "more than 1 possible worlds");
  const std::string plan = writeTempFile("p.plan", "(plan (s) (frobnicate))");
  expectBadInput("contingent-validate " + domain + " " + good + " " + plan,
                 "p.plan:1:7: unknown or never applicable action (s)");
  const std::string branchPlan = writeTempFile("b.plan", "(plan (t) (branch (b) (true)))");
  expectBadInput("contingent-validate " + domain + " " + good + " " + branchPlan,
                 "b.plan:1:11: expected '(branch (p …) (true …) (false …))'");
  const std::string gotoPlan = writeTempFile("g.plan", "(plan (t) (goto n9))");
  expectBadInput("contingent-validate " + domain + " " + good + " " + gotoPlan,
                 "g.plan:1:11: undefined label 'n9'");
  const std::string okPlan = writeTempFile("ok.plan", "(plan (t) (branch (b) (true) (false)))");
  const std::string hidden = writeTempFile("h.pddl", "(define (problem h)\n (:hidden (a)))");
  expectBadInput(
      "contingent-validate " + domain + " " + good + " " + okPlan + " --hidden " + hidden,
      "h.pddl:2:2: hidden state is not one of the initial worlds");
  expectBadInput("force-sensing 0", "n must be at least 1");
  expectBadInput("contingent " + domain + " " + good + " --search beam", "--search");
  const std::string forgetDomain = writeTempFile(
      "forget.pddl",
      "(define (domain d) (:predicates (a) (b))\n  (:action t :effect (del kq (b))))\n");
  expectBadInput("contingent " + forgetDomain + " " + good,
                 "forget.pddl:2:27: unknown database 'kq': expected kf, kw or kv");
}

}  // namespace
}  // namespace kaboum::symbolic
