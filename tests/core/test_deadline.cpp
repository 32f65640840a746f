// Deadline: each limit names itself as a PlannerStatus; the defaults never stop a run.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <thread>

#include "kaboum/core/deadline.hpp"

namespace kaboum {
namespace {

constexpr std::size_t kMany = std::numeric_limits<std::size_t>::max() - 1;

void sleepMilliseconds(int milliseconds) {
  std::this_thread::sleep_for(std::chrono::milliseconds(milliseconds));
}

TEST(Deadline, InfiniteByDefaultNeverFires) {
  const Deadline deadline;
  sleepMilliseconds(2);
  for (const std::size_t expansions : {std::size_t{0}, std::size_t{64}, kMany}) {
    EXPECT_EQ(deadline.reached(expansions, kMany), std::nullopt) << expansions;
  }
}

TEST(Deadline, ExpansionLimitIsReachedExactlyAtTheLimit) {
  PlannerLimits limits;
  limits.expansions = 50;
  const Deadline deadline(limits);
  EXPECT_EQ(deadline.reached(0, 0), std::nullopt);
  EXPECT_EQ(deadline.reached(49, 0), std::nullopt);
  EXPECT_EQ(deadline.reached(50, 0), PlannerStatus::NodeLimit);
  EXPECT_EQ(deadline.reached(51, 0), PlannerStatus::NodeLimit);
}

TEST(Deadline, MemoryLimitIsReachedAboveTheLimit) {
  PlannerLimits limits;
  limits.memoryBytes = 64 * 1024;
  const Deadline deadline(limits);
  EXPECT_EQ(deadline.reached(7, 64 * 1024), std::nullopt);
  EXPECT_EQ(deadline.reached(7, 64 * 1024 + 1), PlannerStatus::MemoryLimit);
}

TEST(Deadline, CancelFlagSetByAnotherThreadStopsTheRun) {
  std::atomic<bool> cancel{false};
  PlannerLimits limits;
  limits.cancel = &cancel;
  const Deadline deadline(limits);
  EXPECT_EQ(deadline.reached(3, 0), std::nullopt);
  std::thread([&cancel] { cancel.store(true); }).join();
  EXPECT_EQ(deadline.reached(3, 0), PlannerStatus::Cancelled);
}

TEST(Deadline, CancelFlagComesBeforeEveryLimit) {
  std::atomic<bool> cancel{true};
  PlannerLimits limits;
  limits.seconds = 0.0;
  limits.memoryBytes = 0;
  limits.expansions = 0;
  limits.cancel = &cancel;
  const Deadline deadline(limits);
  sleepMilliseconds(2);
  EXPECT_EQ(deadline.reached(0, 1), PlannerStatus::Cancelled);
  cancel.store(false);
  EXPECT_EQ(deadline.reached(0, 1), PlannerStatus::NodeLimit);
}

TEST(Deadline, TimeLimitFiresOnceElapsed) {
  PlannerLimits limits;
  limits.seconds = 0.001;
  const Deadline deadline(limits);
  sleepMilliseconds(5);
  EXPECT_GT(deadline.elapsedSeconds(), limits.seconds);
  EXPECT_EQ(deadline.reached(0, 0), PlannerStatus::TimeLimit);
}

TEST(Deadline, ClockIsReadOnlyEveryPeriodOfExpansions) {
  PlannerLimits limits;
  limits.seconds = 0.0;
  const Deadline deadline(limits, 64);
  sleepMilliseconds(2);
  EXPECT_EQ(deadline.reached(1, 0), std::nullopt);
  EXPECT_EQ(deadline.reached(63, 0), std::nullopt);
  EXPECT_EQ(deadline.reached(64, 0), PlannerStatus::TimeLimit);
  EXPECT_EQ(deadline.reached(128, 0), PlannerStatus::TimeLimit);
}

}  // namespace
}  // namespace kaboum
