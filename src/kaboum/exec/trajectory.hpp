// Time parameterisation of a certified joint-space path (thesis §6.1.3, run-time components):
// quintic polynomials through the path's waypoints within every joint's velocity and acceleration
// limits. Rest-to-rest (the thesis's scheme, the default) keeps every sample on the straight
// segment between two waypoints, so the path's certification holds for the trajectory; blended
// passes through the via points without stopping and leaves the segments near them (by what
// pathDeviation() measures). Reference: docs/execution.md.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace kaboum::exec {

enum class Profile { RestToRest, Blended };

const char* toString(Profile profile);
// "rest-to-rest" or "blended"; throws std::invalid_argument otherwise.
Profile profileNamed(const std::string& name);

// Per joint of one robot (its configuration order): velocity (rad/s or m/s) and acceleration
// (rad/s² or m/s²) limits, each positive.
struct JointLimits {
  std::vector<double> velocity;
  std::vector<double> acceleration;
};

// A path of waypoints (whole configurations of one robot) timed by quintic polynomials: segment i
// runs from waypoint i to i + 1 in durations()[i] seconds. Waypoints equal to the one before are
// dropped (a zero-length segment takes no time).
class TimedPath {
 public:
  // Rest-to-rest: each segment q(t) = q_i + s(t/T_i) (q_{i+1} − q_i) with the quintic
  // s(τ) = 10τ³ − 15τ⁴ + 6τ⁵, T_i the shortest duration within every joint's limits.
  // Blended: one quintic per segment and joint with the velocity at a via point the mean of its
  // two segments' mean velocities (0 where they differ in sign or at an end), zero acceleration
  // at every waypoint; each segment's duration brought towards its own limits in a few rounds,
  // then all durations scaled together until the tightest limit is just met.
  // Throws std::invalid_argument for waypoints of different sizes or limits that are not positive.
  TimedPath(std::vector<std::vector<double>> waypoints, const JointLimits& limits, Profile profile);

  [[nodiscard]] double duration() const { return duration_; }
  [[nodiscard]] std::size_t dof() const { return dof_; }
  [[nodiscard]] const std::vector<std::vector<double>>& waypoints() const { return waypoints_; }
  [[nodiscard]] const std::vector<double>& durations() const { return durations_; }
  // Position, velocity and acceleration at time t (clamped to [0, duration()]) into spans of
  // dof() values. Allocates nothing.
  void sample(double t, std::span<double> q, std::span<double> qd, std::span<double> qdd) const;

 private:
  std::size_t segmentAt(double t, double& local) const;

  std::size_t dof_ = 0;
  Profile profile_ = Profile::RestToRest;
  std::vector<std::vector<double>> waypoints_;
  std::vector<double> durations_;
  std::vector<double> starts_;  // start time of each segment
  // Blended: per segment, per joint, the six coefficients of the quintic in local time.
  std::vector<double> coefficients_;
  double duration_ = 0;
};

// The Euclidean joint-space distance from `q` to the piecewise-linear path through `waypoints`.
double distanceToPath(std::span<const double> q, const std::vector<std::vector<double>>& waypoints);

// The largest distanceToPath() of `path` sampled every `step` seconds (and at its end): 0 up to
// rounding for rest-to-rest, what blending deviates by otherwise.
double pathDeviation(const TimedPath& path, double step);

}  // namespace kaboum::exec
