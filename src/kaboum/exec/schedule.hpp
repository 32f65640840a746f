// The timeline of a plan's execution (thesis §6.1.3): the actions of one run through the plan one
// after another, each action's steps in order — a motion of one robot timed as a TimedPath while
// the other robots hold still, a gripper event at an instant — on one clock shared by every robot,
// so that robots are synchronised sample by sample. Also the execution time of every branch of a
// plan. Reference: docs/execution.md.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "kaboum/exec/trajectory.hpp"
#include "kaboum/tamp/plan_reader.hpp"

namespace kaboum::exec {

struct TrajectoryOptions {
  Profile profile = Profile::RestToRest;
  // For joints whose limits neither the scene (`joint_limits`) nor the URDF gives: rad/s or m/s,
  // rad/s² or m/s².
  double defaultVelocity = 1.0;
  double defaultAcceleration = 2.0;
};

// Every robot's limits (World robot order): the scene's, else the URDF's, else the defaults.
std::vector<JointLimits> jointLimits(const world::World& world, const TrajectoryOptions& options);

// One motion step of an action, timed.
struct TimedMotion {
  std::size_t node = 0;  // the plan node of its action
  std::size_t step = 0;  // index among the action's steps (over all its geometric effects)
  tamp::GeometricStep::Kind kind = tamp::GeometricStep::Kind::Transit;
  std::size_t robot = 0;
  double start = 0;  // seconds from the start of execution
  TimedPath path;
};

// A grasp or release at an instant.
struct GripperEvent {
  std::size_t node = 0;
  double time = 0;
  tamp::GeometricStep::Kind kind = tamp::GeometricStep::Kind::Grasp;
  std::size_t robot = 0;
  std::size_t tool = 0;
  std::size_t object = 0;
  Pose pose = Pose::Identity();  // as GeometricStep::pose
};

struct TimedAction {
  std::size_t node = 0;
  std::string name;  // "(pickup kr5 block left)"
  double start = 0;
  double end = 0;
};

class Schedule {
 public:
  // Robots start at their configurations in `initial` (World robot order).
  Schedule(std::vector<std::vector<double>> initial, std::vector<JointLimits> limits,
           Profile profile);

  // Appends plan node `node`'s action `name` with the steps of its geometric effects, from the
  // current end. Throws std::invalid_argument for a path of another robot's size.
  void append(std::size_t node, const std::string& name,
              const std::vector<tamp::ActionGeometry>& geometry);

  [[nodiscard]] double duration() const { return duration_; }
  [[nodiscard]] std::size_t robotCount() const { return initial_.size(); }
  [[nodiscard]] std::size_t dof(std::size_t robot) const { return initial_[robot].size(); }
  [[nodiscard]] Profile profile() const { return profile_; }
  [[nodiscard]] const std::vector<TimedMotion>& motions() const { return motions_; }
  [[nodiscard]] const std::vector<GripperEvent>& events() const { return events_; }
  [[nodiscard]] const std::vector<TimedAction>& actions() const { return actions_; }
  // Robot `robot`'s position, velocity and acceleration at time t: along its motion then, else
  // held where its last motion ended (or at its initial configuration). Allocates nothing.
  void sample(double t, std::size_t robot, std::span<double> q, std::span<double> qd,
              std::span<double> qdd) const;

 private:
  std::vector<std::vector<double>> initial_;
  std::vector<JointLimits> limits_;
  Profile profile_;
  std::vector<TimedMotion> motions_;
  std::vector<std::vector<std::size_t>> robotMotions_;  // per robot: its motions, by start time
  std::vector<GripperEvent> events_;
  std::vector<TimedAction> actions_;
  double duration_ = 0;
};

// The sample times of `duration` seconds at `rate` Hz: 0, 1/rate, …, and `duration` itself.
std::vector<double> sampleTimes(double duration, double rate);

// One robot's trajectory sampled at a rate: per sample time, dof values each.
struct RobotSamples {
  std::size_t robot = 0;
  std::size_t dof = 0;
  std::vector<double> times;
  std::vector<double> positions;  // times.size() × dof, row by row
  std::vector<double> velocities;
  std::vector<double> accelerations;
};

RobotSamples sampleRobot(const Schedule& schedule, std::size_t robot, double rate);

// One way through a plan from its root to a goal: the sensing outcomes on the way, the actions,
// and how long they take.
struct BranchTiming {
  std::vector<std::string> outcomes;  // "(isemptybottle o1) true"
  std::vector<std::string> actions;
  double seconds = 0;
};

// Every way through the plan (the DAG unfolded into a tree), each action timed as a Schedule
// times it. Throws InputError for a plan with a cycle.
std::vector<BranchTiming> branchTimings(const tamp::PlanFileContents& plan,
                                        const symbolic::KnowledgeTask& task,
                                        const std::vector<JointLimits>& limits, Profile profile);

// "(pickup kr5 block left)": the action of plan node `node`.
std::string actionName(const symbolic::KnowledgeTask& task, const symbolic::PlanTree::Node& node);

}  // namespace kaboum::exec
