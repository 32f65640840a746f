// Certified joint-space motion of a motion group (thesis §6.1.2 transit and transfer paths, §4.5
// swept volumes): the straight segment when its swept volume is free, otherwise a sampling-based
// planner of OMPL (RRT-Connect by default) with kaboum's state checker and swept-volume motion
// validator, then shortcutting. Every segment of a returned path is certified: it cannot pass
// through a collision between its waypoints. Reference: docs/motion.md.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "kaboum/core/planner_status.hpp"
#include "kaboum/motion/motion_group.hpp"
#include "kaboum/motion/validity.hpp"

namespace kaboum::motion {

using Waypoints = std::vector<std::vector<double>>;

struct MotionOptions {
  std::string planner = "rrtconnect";  // one of motionPlannerNames()
  double timeLimit = 10;               // seconds for the whole query
  std::uint64_t seed = 1;              // the same seed gives the same path
  // Metres: bound of the swept volumes that certify motions; default the scene's sweep_epsilon
  // (a larger one makes self-collision false alarms at home possible).
  std::optional<double> sweepEpsilon;
  int shortcutAttempts = 20;  // random shortcuts tried on a planned path (0: none)
  // Joint-space length (radians) of one tree extension of the planners that have one (OMPL's
  // "range"; 0: OMPL's default, a fifth of the joint space's extent). Shorter extensions are
  // cheaper to certify: on the MotionBenchMaker problems 1 rad cuts the slowest queries by 3–4×.
  double range = 1.0;
  const std::atomic<bool>* cancel = nullptr;  // the query stops once true; not owned
};

// Where the time of one query went.
struct MotionStatistics {
  CheckStatistics checks;
  bool straight = false;       // the straight segment from start to goal was certified
  double sweepEpsilon = 0;     // metres: the ε the query certified its motions at
  double planningSeconds = 0;  // inside the sampling-based planner, checks included
  double shortcutSeconds = 0;  // shortcutting and the final certification, checks included
  double totalSeconds = 0;
  std::size_t plannedWaypoints = 0;  // before shortcutting
  double plannedLength = 0;          // joint-space length before shortcutting
  double length = 0;                 // joint-space length of the returned path
};

struct MotionResult {
  PlannerStatus status = PlannerStatus::Unsolvable;
  std::string message;  // why the query failed, naming what collides or which joint is off
  Waypoints path;       // start ... goal when solved
  MotionStatistics statistics;
};

// One query's result under construction, its clock started at construction (planMotion,
// planCartesian).
class MotionQuery {
 public:
  MotionQuery() : begin_(std::chrono::steady_clock::now()) {}
  [[nodiscard]] double elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
  }
  // The result with `status` and `message`, the path cleared unless solved, the total time set.
  MotionResult finish(PlannerStatus status, std::string message = {}) {
    result.status = status;
    result.message = std::move(message);
    if (status != PlannerStatus::Solved) result.path.clear();
    result.statistics.totalSeconds = elapsedSeconds();
    return std::move(result);
  }

  MotionResult result;

 private:
  std::chrono::steady_clock::time_point begin_;
};

// The names `MotionOptions::planner` accepts: biest, est, prm, rrt, rrtconnect, rrtstar.
const std::vector<std::string>& motionPlannerNames();

// Plans from `start` to `goal` (configurations of `group`). A start outside the joint limits or
// colliding (anything in the context state with the group at `start`) gives InvalidStart, such a
// goal InvalidGoal, with the message naming the joint or both parties. The query certifies at
// sweepEpsilonForEnds (statistics.sweepEpsilon); running out of time gives TimeLimit, the cancel
// flag Cancelled. Throws std::invalid_argument for configurations of the wrong size or an unknown
// planner name.
MotionResult planMotion(const MotionGroup& group, std::span<const double> start,
                        std::span<const double> goal, const MotionOptions& options = {});

// The validator that certifies a query's straight motions: swept volumes bounded within
// `sweepEpsilon` (SweptMotionValidator), or, when the group's World uses exact predicates
// (World::usePredicates), samples at most the scene's joint_step apart in every revolute joint
// (default 1°, the Bimanual Assembly benchmark's resolution) and its tool_step in every prismatic
// one (DiscreteMotionValidator). Counts into `statistics` when given.
std::unique_ptr<MotionValidator> motionValidator(const MotionGroup& group, double sweepEpsilon,
                                                 CheckStatistics* statistics);

// The sweep ε of a query: the option's, or the scene's.
double sweepEpsilonOf(const MotionGroup& group, const MotionOptions& options);

// The sweep ε that a query between two ends certifies at: sweepEpsilonOf, halved while an end is
// closer than it to an obstacle (an object resting on its support, a grasp), down to 1/16 of it —
// certification holds at any ε, a smaller one costs finer sweeps. An end that collides, is outside
// the joint limits or is closer still gives InvalidStart or InvalidGoal with the problem.
struct QueryEpsilon {
  double epsilon = 0;
  PlannerStatus status = PlannerStatus::Solved;
  std::string problem;  // "start: …" or "goal: …"
};
QueryEpsilon sweepEpsilonForEnds(const MotionGroup& group, std::span<const double> start,
                                 std::span<const double> goal, const MotionOptions& options);

// Why `group` cannot be at q — a joint outside its limits, a collision of anything in the context
// with the group at q, or a moving robot closer than `clearance` to an object (2 × `clearance` to
// a robot) so that no certified motion can leave q, naming both parties — or nullopt when it can.
std::optional<std::string> configurationProblem(const MotionGroup& group, std::span<const double> q,
                                                double clearance);

// A configuration of `group` drawn uniformly within its joint limits (kinematics::uniformUnit, the
// same on every platform) until one has no configurationProblem at `clearance`, so that certified
// motions can leave it: the random queries of benchmarks and property tests. nullopt after `draws`
// draws.
std::optional<std::vector<double>> randomFreeConfiguration(const MotionGroup& group,
                                                           double clearance, std::mt19937_64& rng,
                                                           int draws = 100000);

// Sum of the Euclidean joint-space lengths of the segments.
double pathLength(const Waypoints& path);

}  // namespace kaboum::motion
