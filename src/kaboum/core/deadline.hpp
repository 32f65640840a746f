// When a planner run must stop (thesis §3.2 and §6.2: searches end cleanly at their limits), in the
// spirit of OMPL's PlannerTerminationCondition: wall-clock time, expansions, memory, and a cancel
// flag another thread, a signal handler or the Python bindings may set. Polling allocates nothing,
// so it belongs in the hot search loop.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <limits>
#include <optional>

#include "kaboum/core/planner_status.hpp"

namespace kaboum {

// What may end a planner run; the defaults never do.
struct PlannerLimits {
  double seconds = std::numeric_limits<double>::infinity();  // wall-clock, from the run's start
  std::size_t memoryBytes = std::numeric_limits<std::size_t>::max();
  std::size_t expansions = std::numeric_limits<std::size_t>::max();
  // The run stops once this is true. Not owned; null for none.
  const std::atomic<bool>* cancel = nullptr;
};

// A run's limits and its clock, which starts at construction.
class Deadline {
 public:
  // The clock is read only when the expansion count is a multiple of `clockPeriod` (at least 1).
  explicit Deadline(const PlannerLimits& limits = {}, std::size_t clockPeriod = 1)
      : limits_(limits), clockPeriod_(clockPeriod), start_(std::chrono::steady_clock::now()) {}

  // The limit reached by a run that has made `expansions` expansions and holds `memoryBytes`,
  // asked before its next expansion; nothing while it may go on. Checked in this order: the cancel
  // flag, expansions (reached when `expansions` equals the limit), time and memory (reached when
  // strictly above the limit).
  std::optional<PlannerStatus> reached(std::size_t expansions, std::size_t memoryBytes) const {
    if (limits_.cancel != nullptr && limits_.cancel->load(std::memory_order_relaxed)) {
      return PlannerStatus::Cancelled;
    }
    if (expansions >= limits_.expansions) return PlannerStatus::NodeLimit;
    if (limits_.seconds < std::numeric_limits<double>::infinity() &&
        expansions % clockPeriod_ == 0 && elapsedSeconds() > limits_.seconds) {
      return PlannerStatus::TimeLimit;
    }
    if (memoryBytes > limits_.memoryBytes) return PlannerStatus::MemoryLimit;
    return std::nullopt;
  }

  double elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  PlannerLimits limits_;
  std::size_t clockPeriod_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace kaboum
