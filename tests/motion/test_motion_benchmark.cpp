// `kaboum-compare motion` on the six copied MotionBenchMaker problems and on random queries in the
// mobile manipulator scene: every kaboum path is found collision-free by the independent verifier,
// and the JSON has the summary and per-problem fields. No timing is asserted.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/test_support.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::motion {

namespace {

TEST(MotionBenchmark, EveryKaboumPathOfTheCopiedProblemsIsVerifiedFree) {
  const test::ScratchDir dir;
  const test::CliResult result = test::runCompare(
      dir, "motion --json --time-limit 5 --quiet --cache-dir '" + dir.file("cache") + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);

  for (const char* key : {"problems", "count", "time_limit", "seed", "sweep_epsilon",
                          "ompl_resolution_deg", "world_seconds", "kaboum", "ompl_fcl",
                          "both_solved", "ratio_of_medians", "cpu_ratio_of_medians", "runs"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["count"], 6);
  EXPECT_DOUBLE_EQ(json["sweep_epsilon"].get<double>(), 0.005);
  for (const char* planner : {"kaboum", "ompl_fcl"}) {
    const nlohmann::json& summary = json[planner];
    for (const char* key : {"solved", "valid", "total", "colliding_paths", "time_ms", "cpu_time_ms",
                            "length_before_median", "length_after_median", "min_clearance",
                            "failures", "collisions"}) {
      EXPECT_TRUE(summary.contains(key)) << planner << " " << key;
    }
    EXPECT_EQ(summary["total"], 6) << planner;
  }
  EXPECT_EQ(json["kaboum"]["colliding_paths"], 0);
  EXPECT_EQ(json["kaboum"]["valid"], json["kaboum"]["solved"]);

  ASSERT_EQ(json["runs"].size(), 6u);
  for (const nlohmann::json& run : json["runs"]) {
    const std::string name = run["problem"];
    EXPECT_TRUE(run.contains("world_seconds")) << name;
    const nlohmann::json& kaboum = run["kaboum"];
    if (kaboum["status"] == "solved") {
      EXPECT_EQ(kaboum["collision_free"], true) << name << ": " << kaboum["collision"];
      EXPECT_GE(kaboum["waypoints"].get<int>(), 2) << name;
      EXPECT_GE(kaboum["clearance"].get<double>(), 0.0) << name;
    } else {
      EXPECT_FALSE(kaboum["message"].get<std::string>().empty()) << name;
    }
    const nlohmann::json& ompl = run["ompl_fcl"];
    if (ompl["status"] == "solved") {
      EXPECT_TRUE(ompl["collision_free"].is_boolean()) << name;
    }
  }
}

TEST(MotionBenchmark, RandomQueriesInASceneFileAreVerifiedFree) {
  const test::ScratchDir dir;
  const test::CliResult result =
      test::runCompare(dir, "motion --json --quiet --no-cache --queries 3 --scene '" +
                                testing::exampleFile("scenes/mobile-manipulator.yaml") + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["scene"], true);
  EXPECT_EQ(json["count"], 3);
  EXPECT_DOUBLE_EQ(json["sweep_epsilon"].get<double>(), 0.005);
  EXPECT_EQ(json["kaboum"]["solved"], 3);
  EXPECT_EQ(json["kaboum"]["valid"], 3);
  EXPECT_EQ(json["ompl_fcl"]["total"], 3);
  ASSERT_EQ(json["runs"].size(), 3u);
  EXPECT_EQ(json["runs"][0]["problem"], "mobile-manipulator/query00");
  // The same scene seed draws the same queries, and the same planner seed gives the same paths.
  const test::CliResult again =
      test::runCompare(dir, "motion --json --quiet --no-cache --queries 3 --scene '" +
                                testing::exampleFile("scenes/mobile-manipulator.yaml") + "'");
  const nlohmann::json second = nlohmann::json::parse(again.out);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(second["runs"][i]["kaboum"]["length"], json["runs"][i]["kaboum"]["length"]) << i;
  }
}

TEST(MotionBenchmark, BadOptionsAreRefused) {
  const test::ScratchDir dir;
  EXPECT_EQ(test::runCompare(dir, "motion --time-limit 0").exitCode, 2);
  EXPECT_EQ(test::runCompare(dir, "motion --sweep-epsilon -1").exitCode, 2);
  EXPECT_EQ(test::runCompare(dir, "motion --problems '" + dir.file("missing") + "'").exitCode, 2);
  const std::string scene =
      "--scene '" + testing::exampleFile("scenes/mobile-manipulator.yaml") + "'";
  EXPECT_EQ(test::runCompare(dir, "motion --queries 0 " + scene).exitCode, 2);
  EXPECT_EQ(test::runCompare(dir, "motion --robot nobody " + scene).exitCode, 2);
  EXPECT_EQ(test::runCompare(dir, "motion --problems . " + scene).exitCode, 2);
}

}  // namespace

}  // namespace kaboum::motion
