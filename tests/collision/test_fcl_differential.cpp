// Differential test against FCL on the ORIGINAL triangle meshes (KR5 and WAM links): over random
// relative poses, the bounded collision predicate misses no collision (`kaboum-compare
// verify-collision`; the full 10^6 run and its false-alarm figures are in docs/collision-scene.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/test_support.hpp"

namespace kaboum::collision {

using namespace kaboum::testing;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kSamples = 10000;
#else
constexpr int kSamples = 100000;
#endif

TEST(FclDifferential, NoMissedCollisionOnRealMeshes) {
  const kaboum::test::ScratchDir dir;
  const auto result = kaboum::test::runCompare(
      dir, "verify-collision --samples " + std::to_string(kSamples) + " --seed 7 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto figures = nlohmann::json::parse(result.out);
  EXPECT_EQ(figures["samples"], kSamples);
  EXPECT_EQ(figures["meshes"], 14);
  EXPECT_EQ(figures["missed"], 0);
  // A meaningful mix: many real contacts and many free poses.
  EXPECT_GT(figures["fcl_collisions"].get<int>(), kSamples / 5);
  EXPECT_LT(figures["fcl_collisions"].get<int>(), kSamples * 4 / 5);
  // Every answer of FCL plus false alarms and containments is what kaboum reported.
  EXPECT_EQ(figures["kaboum_collisions"].get<int>(), figures["fcl_collisions"].get<int>() +
                                                         figures["false_alarms"].get<int>() +
                                                         figures["solid_contacts"].get<int>());
  // One convex hull per link until the bounding decomposition lands: false alarms stay within
  // the largest gap between a KR5/WAM link and its hull (a few centimetres).
  EXPECT_LT(figures["max_false_alarm_distance"].get<double>(), 0.1);
}

TEST(FclDifferential, BadInputIsOneLineAndExitCode2) {
  const kaboum::test::ScratchDir dir;
  for (const std::string& arguments :
       std::vector<std::string>{"verify-collision --samples 0", "verify-collision --reach-scale -1",
                                "verify-collision --mesh '" + dir.file("missing.stl") + "'"}) {
    const auto result = kaboum::test::runCompare(dir, arguments);
    EXPECT_EQ(result.exitCode, 2) << arguments;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
}

}  // namespace
}  // namespace kaboum::collision
