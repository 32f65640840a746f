// Branched execution of a plan file (thesis §6.1.3; §3.3.3 execution of branches): the plan is
// walked from its root, each action's geometry timed into one Schedule; at a sensing branch a
// sensing source gives the outcome — a hidden true state, a person at a terminal, or the caller's
// callback — and execution follows that branch. With an observed world state, each action's
// geometric precondition is re-checked before it runs, and execution stops naming the action and
// the failed condition: the hook replanning starts from. Reference: docs/execution.md.
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "kaboum/exec/schedule.hpp"

namespace kaboum::exec {

// A sensing branch to decide: its plan node and its test, "(isemptybottle o1)" or "(= (f a) v)".
struct SensingQuery {
  std::size_t node = 0;
  const symbolic::PlanTree::Node* branch = nullptr;
  std::string test;
};

// The outcome of a sensing branch: whether its test holds. May throw InputError for an answer
// that is no outcome.
using SensingSource = std::function<bool(const SensingQuery&)>;

// The outcomes of a hidden true initial state (the `(:hidden …)` states of contingent problems):
// each test is evaluated in world `world` of `task` (KnowledgeTask::hiddenWorld), the facts the
// plan senses being ones no action changes. `task` must outlive the source.
SensingSource hiddenStateSource(const symbolic::KnowledgeTask& task, std::uint32_t world);

// Asks on `out` ("(isemptybottle o1)? [y/n] ") and reads one line of `in`: y, yes, true, t, 1
// or n, no, false, f, 0 (any case). Throws InputError naming the test for any other answer or
// the end of the input.
SensingSource promptSource(std::istream& in, std::ostream& out);

// Where objects are now, as observed: scene object → pose in the world.
struct WorldObservation {
  std::map<std::size_t, Pose> objects;
};

// Reads a world state file (docs/execution.md): {"objects": {name: pose}}, a pose as the plan
// file writes it. Throws InputError with one line naming the file and the key.
WorldObservation readWorldObservation(const nlohmann::json& json, const std::string& fileName,
                                      const world::World& world);

struct ExecutionOptions {
  TrajectoryOptions trajectory;
  SensingSource sensing;  // required when the run meets a branch
  // When given: before each action, its geometric precondition in the expected state with these
  // objects moved to where they are observed.
  const WorldObservation* observed = nullptr;
};

struct SensingOutcome {
  std::size_t node = 0;
  std::string test;
  bool value = false;
  double time = 0;
  std::size_t actionsBefore = 0;  // the actions of the run before it
};

struct ExecutionResult {
  bool reachedGoal = false;  // false when a precondition failed
  // "nodes[5] (pickup kr5 block left): object 'block' is 0.100 m from where the plan grasps it".
  std::string stopReason;
  std::vector<SensingOutcome> sensed;
  Schedule schedule;
  std::vector<BranchTiming> branches;  // every way through the plan
};

// One entry of an execution's log: result.schedule.actions()[index], result.schedule.events()
// [index] or result.sensed[index].
struct LogRecord {
  enum class Kind { Action, Gripper, Sensing };
  Kind kind = Kind::Action;
  std::size_t index = 0;
  double time = 0;
};

// The log of a run in the order things happened: each action, then its gripper events, and a
// sensing outcome after the actions before it.
std::vector<LogRecord> executionLog(const ExecutionResult& result);

// Walks `plan` (read with readPlanFile against `task` and `world`) from its root. Throws
// InputError when a sensing source answers badly or is missing at a branch, or when the plan
// does not follow on (a gripper event that does not apply).
ExecutionResult execute(const world::World& world, const symbolic::KnowledgeTask& task,
                        const tamp::PlanFileContents& plan, const ExecutionOptions& options);

// The geometric precondition of `geometry` from `state`: every grasped object where the plan
// grasps it, every motion's waypoints collision-free and its segments certified by swept volumes
// in the states along it. Returns the first failure ("step 2 (approach): …"), or "".
std::string preconditionFailure(const world::World& world, const world::GeometricState& state,
                                const std::vector<tamp::ActionGeometry>& geometry);

}  // namespace kaboum::exec
