// The full-robot collision benchmark: a robot's convex pieces against a scene of about
// 50 convex obstacles, kaboum vs FCL's DynamicAABBTree manager on identical queries, and the
// Figure 4.9 per-check time distributions along random motions (original meshes vs convex hulls).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "kaboum/testing/data_paths.hpp"

namespace kaboum::cli {

using namespace kaboum::testing;

struct FullRobotBenchOptions {
  std::string urdf = kaboum::testing::kr5Urdf();
  int obstacles = 50;
  int queries = 10000;  // random configurations for the side-by-side check
  int motions = 50;     // random straight motions for the Figure 4.9 distributions
  int motionSteps = 100;
  int runs = 3;                 // every query is timed this often; the median counts
  double decomposePercent = 3;  // ε of the bounding convex decomposition, % of link diagonal
  std::uint64_t seed = 1;
  bool quiet = false;  // no progress on stderr
};

// Runs everything and returns the figures: per method ns per check (min, mean, median, p99,
// max of the per-query medians over `runs`), the FCL/kaboum ratios, collision fractions and
// boolean disagreements, for the robot's convex hulls and its bounding convex decomposition.
nlohmann::json runFullRobotBench(const FullRobotBenchOptions& options);

// The figures as a human-readable table.
void printFullRobotBench(const nlohmann::json& figures, std::ostream& out);

}  // namespace kaboum::cli
