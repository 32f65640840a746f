// PlannerStatus: the strings the CLI prints and writes in JSON.
#include <gtest/gtest.h>

#include "kaboum/core/planner_status.hpp"

namespace kaboum {
namespace {

TEST(PlannerStatus, ToStringGivesTheCliStatusValues) {
  EXPECT_EQ(toString(PlannerStatus::Solved), "solved");
  EXPECT_EQ(toString(PlannerStatus::Unsolvable), "unsolvable");
  EXPECT_EQ(toString(PlannerStatus::TimeLimit), "time-limit");
  EXPECT_EQ(toString(PlannerStatus::MemoryLimit), "memory-limit");
  EXPECT_EQ(toString(PlannerStatus::NodeLimit), "node-limit");
  EXPECT_EQ(toString(PlannerStatus::Cancelled), "cancelled");
  EXPECT_EQ(toString(PlannerStatus::InvalidStart), "invalid-start");
  EXPECT_EQ(toString(PlannerStatus::InvalidGoal), "invalid-goal");
}

}  // namespace
}  // namespace kaboum
