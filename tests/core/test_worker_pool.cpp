// WorkerPool: every task of a batch runs exactly once and the caller waits for all of them, with
// and without worker threads; batches nest and repeat, and a waiting caller helps only with the
// batches started inside its own; the lowest failing index's exception reaches the caller; results
// do not depend on the thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "kaboum/core/worker_pool.hpp"

namespace kaboum {
namespace {

// The thread counts tried: 0 and 1 (inline), 2 and 4.
const unsigned kThreadCounts[] = {0, 1, 2, 4};

// A failure that names its task.
struct TaskFailure : std::runtime_error {
  explicit TaskFailure(std::size_t failedIndex)
      : std::runtime_error("task " + std::to_string(failedIndex)), index(failedIndex) {}
  std::size_t index;
};

// Some floating-point work whose result depends on the index only.
double work(std::size_t i) {
  double x = static_cast<double>(i) + 0.5;
  for (int k = 0; k < 200; ++k) x = std::sin(x) * 1.0001 + std::sqrt(x * x + 1.0);
  return x;
}

TEST(WorkerPool, ReportsItsThreadsTheCallerIncluded) {
  EXPECT_EQ(WorkerPool(0).threads(), 1u);
  EXPECT_EQ(WorkerPool(1).threads(), 1u);
  EXPECT_EQ(WorkerPool(3).threads(), 3u);
}

TEST(WorkerPool, RunsEveryTaskExactlyOnceAndTheCallerWaitsForAll) {
  for (const unsigned threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    WorkerPool pool(threads);
    for (const std::size_t count : {0u, 1u, 2u, 3u, 1000u}) {
      std::vector<std::atomic<int>> runs(count);
      pool.run(count, [&](std::size_t i) {
        if (i % 97 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        runs[i].fetch_add(1);
      });
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << i;
    }
  }
}

TEST(WorkerPool, InlineModeRunsEveryTaskOnTheCallerInIndexOrder) {
  const std::thread::id caller = std::this_thread::get_id();
  for (const unsigned threads : {0u, 1u}) {
    WorkerPool pool(threads);
    std::vector<std::size_t> order;
    pool.run(50, [&](std::size_t i) {
      EXPECT_EQ(std::this_thread::get_id(), caller);
      order.push_back(i);
    });
    ASSERT_EQ(order.size(), 50u);
    for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  }
}

TEST(WorkerPool, TheCallerRunsTasksAndAnIdleWorkerRunsOthersAtTheSameTime) {
  WorkerPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> callerRan{false};
  std::atomic<int> started{0};
  pool.run(2, [&](std::size_t) {
    if (std::this_thread::get_id() == caller) callerRan = true;
    // Both tasks wait (for at most 10 s) until both have started: they run on two threads.
    started.fetch_add(1);
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started.load() < 2 && std::chrono::steady_clock::now() < giveUp) {
      std::this_thread::yield();
    }
  });
  EXPECT_TRUE(callerRan);
  EXPECT_EQ(started.load(), 2);
}

// Waits (for at most 10 s) until `flag` is set; false when it never was.
bool waitFor(const std::atomic<bool>& flag) {
  const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!flag.load() && std::chrono::steady_clock::now() < giveUp) std::this_thread::yield();
  return flag.load();
}

TEST(WorkerPool, AWaitingCallerRunsTasksStartedInsideItsBatchButNoOthers) {
  WorkerPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> workerTaskStarted{false}, innerSecondStarted{false}, otherBatchDone{false};
  std::atomic<bool> innerSecondOnCaller{false}, otherOnCaller{false};
  std::jthread otherCaller;
  pool.run(2, [&](std::size_t i) {
    if (i == 0) {
      // The caller takes task 0 and leaves task 1 to the worker.
      EXPECT_TRUE(waitFor(workerTaskStarted));
      return;
    }
    workerTaskStarted = true;
    // Another thread's batch while the caller waits for this task: the caller must not run it.
    otherCaller = std::jthread([&] {
      pool.run(20, [&](std::size_t) {
        if (std::this_thread::get_id() == caller) otherOnCaller = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      });
      otherBatchDone = true;
    });
    EXPECT_TRUE(waitFor(otherBatchDone));
    // A batch started inside the caller's: its task 1 can only run on the waiting caller while
    // this thread runs its task 0.
    pool.run(2, [&](std::size_t j) {
      if (j == 0) {
        EXPECT_TRUE(waitFor(innerSecondStarted));
        return;
      }
      innerSecondOnCaller = std::this_thread::get_id() == caller;
      innerSecondStarted = true;
    });
  });
  EXPECT_FALSE(otherOnCaller.load());
  EXPECT_TRUE(innerSecondOnCaller.load());
}

TEST(WorkerPool, NestedAndRepeatedBatchesComplete) {
  for (const unsigned threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    WorkerPool pool(threads);
    for (int repeat = 0; repeat < 50; ++repeat) {
      std::vector<std::vector<std::vector<int>>> runs(
          6, std::vector<std::vector<int>>(5, std::vector<int>(7, 0)));
      pool.run(6, [&](std::size_t i) {
        pool.run(5, [&](std::size_t j) { pool.run(7, [&](std::size_t k) { ++runs[i][j][k]; }); });
      });
      for (const auto& outer : runs) {
        for (const auto& inner : outer) {
          for (const int count : inner) ASSERT_EQ(count, 1);
        }
      }
    }
  }
}

TEST(WorkerPool, SeveralThreadsMayShareAPool) {
  WorkerPool pool(3);
  std::vector<std::size_t> sums(4, 0);
  {
    std::vector<std::jthread> callers;
    for (std::size_t c = 0; c < sums.size(); ++c) {
      callers.emplace_back([&, c] {
        for (int repeat = 0; repeat < 100; ++repeat) {
          std::vector<std::size_t> values(64, 0);
          pool.run(values.size(), [&](std::size_t i) { values[i] = i + c; });
          for (const std::size_t v : values) sums[c] += v;
        }
      });
    }
  }
  for (std::size_t c = 0; c < sums.size(); ++c) EXPECT_EQ(sums[c], 100 * (2016 + 64 * c)) << c;
}

TEST(WorkerPool, RethrowsTheExceptionOfTheLowestFailingIndex) {
  for (const unsigned threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    WorkerPool pool(threads);
    for (int repeat = 0; repeat < 20; ++repeat) {
      std::atomic<int> runsOfFailing{0};
      try {
        pool.run(100, [&](std::size_t i) {
          if (i == 61 || i == 17 || i == 90) {
            runsOfFailing.fetch_add(1);
            throw TaskFailure(i);
          }
        });
        FAIL() << "no exception";
      } catch (const TaskFailure& failure) {
        EXPECT_EQ(failure.index, 17u);
      }
      EXPECT_GE(runsOfFailing.load(), 1);
    }
    // The pool is still usable, and a failure deep in nested batches reaches the outer caller.
    std::atomic<int> runs{0};
    pool.run(10, [&](std::size_t) { runs.fetch_add(1); });
    EXPECT_EQ(runs.load(), 10);
    try {
      pool.run(4, [&](std::size_t i) {
        pool.run(8, [&](std::size_t j) {
          if (i >= 2 && j == 5) throw TaskFailure(10 * i + j);
        });
      });
      FAIL() << "no exception";
    } catch (const TaskFailure& failure) {
      EXPECT_EQ(failure.index, 25u);
    }
  }
}

TEST(WorkerPool, ResultsAreTheSameForEveryThreadCount) {
  std::vector<double> expected(3000);
  for (std::size_t i = 0; i < expected.size(); ++i) expected[i] = work(i);
  for (const unsigned threads : kThreadCounts) {
    SCOPED_TRACE(threads);
    WorkerPool pool(threads);
    std::vector<double> results(expected.size(), 0.0);
    pool.run(results.size(), [&](std::size_t i) { results[i] = work(i); });
    EXPECT_EQ(results, expected);
    std::vector<double> blocked(expected.size(), 0.0);
    pool.forEachIndex(blocked.size(), 100, [&](std::size_t i) { blocked[i] = work(i); });
    EXPECT_EQ(blocked, expected);
  }
}

TEST(WorkerPool, ForEachIndexCoversEveryIndexOnce) {
  const std::thread::id caller = std::this_thread::get_id();
  for (const unsigned threads : kThreadCounts) {
    WorkerPool pool(threads);
    for (const std::size_t count : {0u, 1u, 2u, 7u, 8191u, 8192u, 10001u}) {
      for (const std::size_t minimum : {0u, 1u, 3u, 4096u}) {
        SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(count) +
                     " indices, at least " + std::to_string(minimum) + " per task");
        std::vector<std::atomic<int>> runs(count);
        std::atomic<bool> offCaller{false};
        pool.forEachIndex(count, minimum, [&](std::size_t i) {
          runs[i].fetch_add(1);
          if (std::this_thread::get_id() != caller) offCaller = true;
        });
        for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << i;
        // Fewer than two blocks' worth of indices are one block, run by the caller.
        if (count < 2 * minimum) {
          EXPECT_FALSE(offCaller.load());
        }
      }
    }
  }
}

}  // namespace
}  // namespace kaboum
