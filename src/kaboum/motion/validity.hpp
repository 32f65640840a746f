// What the motion planners know of geometry (thesis §6.1.2, "Robotics components at planning
// time"), in the spirit of OMPL's StateValidityChecker and MotionValidator: whether a
// configuration is free, and whether the straight joint-space motion between two is. Planners
// call these and nothing else; kaboum's implementations (world_checkers.hpp) sit on the robot
// collision models and their swept volumes.
#pragma once

#include <cstddef>
#include <span>

namespace kaboum::motion {

// Whether a configuration of a motion group (motion_group.hpp) is collision-free.
class StateValidityChecker {
 public:
  virtual ~StateValidityChecker() = default;
  [[nodiscard]] virtual bool isValid(std::span<const double> q) = 0;
};

// Whether the straight joint-space motion from `from` to `to` is collision-free everywhere
// between them, not only at samples; both ends are taken as valid.
class MotionValidator {
 public:
  virtual ~MotionValidator() = default;
  [[nodiscard]] virtual bool isValid(std::span<const double> from, std::span<const double> to) = 0;
};

// Counts and seconds of the checks of one planning query; the positives are the checks that found
// a collision (Table 6.7's positive share: positives / checks).
struct CheckStatistics {
  std::size_t stateChecks = 0;
  std::size_t statePositives = 0;
  double stateSeconds = 0;
  std::size_t motionChecks = 0;
  std::size_t motionPositives = 0;
  double motionSeconds = 0;

  CheckStatistics& operator+=(const CheckStatistics& other);
};

inline CheckStatistics& CheckStatistics::operator+=(const CheckStatistics& other) {
  stateChecks += other.stateChecks;
  statePositives += other.statePositives;
  stateSeconds += other.stateSeconds;
  motionChecks += other.motionChecks;
  motionPositives += other.motionPositives;
  motionSeconds += other.motionSeconds;
  return *this;
}

}  // namespace kaboum::motion
