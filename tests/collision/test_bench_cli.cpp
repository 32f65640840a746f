// `kaboum-compare collision`: the side-by-side report users and docs/benchmarks.md rely on, and
// its bad options.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/test_support.hpp"

namespace kaboum::test {

using namespace kaboum::testing;

namespace {

TEST(BenchCli, ReportsEveryLibraryPerVertexCountAsJson) {
  const ScratchDir dir;
  const CliResult result = runCompare(
      dir, "collision --pairs 40 --runs 1 --vertices 8 16 --section pairs --json --quiet");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const auto json = nlohmann::json::parse(result.out);
  for (const char* n : {"8", "16"}) {
    const auto& entry = json.at("pairs").at(n);
    EXPECT_EQ(entry.at("pairs"), 40);
    const auto& methods = entry.at("methods");
    for (const char* method : {"kaboum", "fcl_libccd", "fcl_indep", "bullet_gjk_pair_detector",
                               "bullet_gjk_epa2", "libccd_gjk", "libccd_mpr"}) {
      ASSERT_TRUE(methods.contains(method)) << method;
      EXPECT_GT(methods.at(method).at("boolean_ns").get<double>(), 0.0) << method;
    }
    EXPECT_EQ(methods.at("kaboum").at("missed_overlaps"), 0);
    EXPECT_EQ(methods.at("kaboum").at("distance_overestimates"), 0);
    EXPECT_DOUBLE_EQ(methods.at("kaboum").at("boolean_ratio_to_kaboum").get<double>(), 1.0);
    EXPECT_FALSE(methods.at("libccd_mpr").contains("distance_ns"));
  }
}

// Every library is timed round by round with the others, and its ratio to kaboum is the median
// of the same-round ratios (a drift of the machine's speed reaches both sides of a ratio alike).
TEST(BenchCli, RatiosAreMediansOfSameRoundRatios) {
  const ScratchDir dir;
  const CliResult result =
      runCompare(dir, "collision --pairs 30 --runs 3 --vertices 8 --section pairs --json --quiet");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto methods = nlohmann::json::parse(result.out).at("pairs").at("8").at("methods");
  const auto ours = methods.at("kaboum");
  for (const char* method : {"fcl_libccd", "bullet_gjk_epa2"}) {
    for (const std::string query : {"boolean", "distance"}) {
      const auto theirs = methods.at(method);
      const auto theirRounds = theirs.at(query + "_rounds_ns").get<std::vector<double>>();
      const auto ourRounds = ours.at(query + "_rounds_ns").get<std::vector<double>>();
      ASSERT_EQ(theirRounds.size(), 3U);
      ASSERT_EQ(ourRounds.size(), 3U);
      std::vector<double> ratios;
      for (std::size_t r = 0; r < 3; ++r) ratios.push_back(theirRounds[r] / ourRounds[r]);
      std::sort(ratios.begin(), ratios.end());
      EXPECT_DOUBLE_EQ(theirs.at(query + "_ratio_to_kaboum").get<double>(), ratios[1])
          << method << " " << query;
      std::vector<double> sorted = theirRounds;
      std::sort(sorted.begin(), sorted.end());
      EXPECT_DOUBLE_EQ(theirs.at(query + "_ns").get<double>(), sorted[1]) << method << " " << query;
    }
  }
}

// The full-robot section: the KR5 (dart-doc) against 50 convex obstacles, kaboum and FCL on the
// same pieces agree on every check, and the per-check statistics are consistent.
TEST(BenchCli, FullRobotSectionAgreesWithFclAndReportsEveryStatistic) {
  const ScratchDir dir;
  const CliResult result =
      runCompare(dir, "collision --section robot --runs 1 --seed 2 --json --quiet");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto robot = nlohmann::json::parse(result.out).at("robot");
  EXPECT_EQ(robot.at("runs"), 1);
  const auto ordered = [](const nlohmann::json& stats) {
    return stats.at("min").get<double>() > 0.0 &&
           stats.at("min").get<double>() <= stats.at("median").get<double>() &&
           stats.at("median").get<double>() <= stats.at("p99").get<double>() &&
           stats.at("p99").get<double>() <= stats.at("max").get<double>() &&
           stats.at("min").get<double>() <= stats.at("mean").get<double>() &&
           stats.at("mean").get<double>() <= stats.at("max").get<double>();
  };
  for (const char* model : {"bounding_convex_sets", "convex_hulls"}) {
    const auto& figures = robot.at(model);
    EXPECT_EQ(figures.at("disagreements"), 0) << model;
    EXPECT_GT(figures.at("pieces").get<int>(), 6) << model;
    const double colliding = figures.at("collision_fraction").get<double>();
    EXPECT_GT(colliding, 0.1) << model;
    EXPECT_LT(colliding, 0.9) << model;
    EXPECT_TRUE(ordered(figures.at("kaboum_ns"))) << model << figures.at("kaboum_ns");
    EXPECT_TRUE(ordered(figures.at("fcl_dynamic_aabb_tree_ns")))
        << model << figures.at("fcl_dynamic_aabb_tree_ns");
  }
  for (const char* checker :
       {"original_meshes_fcl", "convex_hulls_kaboum", "bounding_convex_sets_kaboum"}) {
    EXPECT_TRUE(ordered(robot.at("figure_4_9_ns").at(checker))) << checker;
  }
}

TEST(BenchCli, PrintsATableWithProgressOnStderr) {
  const ScratchDir dir;
  const CliResult result = runCompare(dir, "collision --pairs 20 --runs 1 --vertices 8");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("N=8 vertices: 20 pairs"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("fcl_libccd"), std::string::npos);
  EXPECT_NE(result.err.find("exact reference"), std::string::npos);
}

TEST(BenchCli, BadOptionsGiveOneLineAndExitCode2) {
  const ScratchDir dir;
  for (const char* arguments :
       {"collision --pairs 0", "collision --runs 0", "collision --vertices 3",
        "collision --section nosuch", "collision --pairs x", "", "nosuch"}) {
    const CliResult result = runCompare(dir, arguments);
    EXPECT_EQ(result.exitCode, 2) << arguments;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << arguments << result.err;
    EXPECT_EQ(result.err.rfind("kaboum-compare: error: ", 0), 0U) << arguments << result.err;
  }
}

}  // namespace
}  // namespace kaboum::test
