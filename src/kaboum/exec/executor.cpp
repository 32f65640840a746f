#include "kaboum/exec/executor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <istream>
#include <ostream>
#include <stdexcept>

#include "kaboum/core/error.hpp"
#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/motion/world_checkers.hpp"

namespace kaboum::exec {

using json = nlohmann::json;
using symbolic::PlanTree;
using tamp::GeometricStep;

SensingSource hiddenStateSource(const symbolic::KnowledgeTask& task, std::uint32_t world) {
  return [&task, world](const SensingQuery& query) {
    const PlanTree::Node& branch = *query.branch;
    const symbolic::StateView state = task.world(world);
    return branch.fluent >= 0 ? symbolic::sameValue(state.fluent(branch.fluent), branch.value)
                              : state.atom(branch.atom);
  };
}

SensingSource promptSource(std::istream& in, std::ostream& out) {
  return [&in, &out](const SensingQuery& query) {
    out << query.test << "? [y/n] " << std::flush;
    std::string answer;
    if (!std::getline(in, answer)) {
      throw InputError("--ask: no answer to " + query.test + " (end of input)");
    }
    std::string word;
    for (const char c : answer) {
      if (!std::isspace(static_cast<unsigned char>(c))) {
        word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      }
    }
    for (const char* yes : {"y", "yes", "true", "t", "1"}) {
      if (word == yes) return true;
    }
    for (const char* no : {"n", "no", "false", "f", "0"}) {
      if (word == no) return false;
    }
    throw InputError("--ask: '" + answer + "' is no outcome of " + query.test +
                     " (answer yes or no)");
  };
}

WorldObservation readWorldObservation(const json& file, const std::string& fileName,
                                      const world::World& world) {
  const auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(locate(fileName, key + ": " + what));
  };
  if (!file.is_object() || !file.contains("objects") || !file["objects"].is_object()) {
    fail("objects", "expected an object of object name → pose");
  }
  for (const auto& [key, value] : file.items()) {
    if (key != "objects") fail(key, "unknown key (known: objects)");
  }
  WorldObservation observation;
  for (const auto& [name, value] : file["objects"].items()) {
    const std::string at = "objects." + name;
    const std::optional<world::NamedEntity> found = world.find(name);
    if (!found || found->kind != world::NamedEntity::Kind::Object) {
      fail(at, "no object '" + name + "' in the scene");
    }
    if (!world.scene().movable(found->index)) fail(at, "object '" + name + "' is not movable");
    observation.objects[found->index] = io::poseFromJson(value, fileName, at);
  }
  return observation;
}

std::string preconditionFailure(const world::World& world, const world::GeometricState& state,
                                const std::vector<tamp::ActionGeometry>& geometry) {
  world::GeometricState current = state;
  std::size_t index = 0;
  for (const tamp::ActionGeometry& effect : geometry) {
    std::vector<world::GeometricState> states;
    try {
      states = tamp::statesAlong(world, current, effect);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    for (std::size_t s = 0; s < effect.steps.size(); ++s, ++index) {
      const GeometricStep& step = effect.steps[s];
      const std::string at = fmt::format("step {} ({})", index + 1, tamp::toString(step.kind));
      const std::string robot = world.robots()[step.robot].name;
      if (step.kind == GeometricStep::Kind::Grasp) {
        // Where the plan's grasp holds the object: the tool link at the robot's configuration.
        const Pose planned = tamp::objectPose(world, states[s + 1], step.object);
        const Pose observed = tamp::objectPose(world, states[s], step.object);
        const double distance = (planned.translation() - observed.translation()).norm();
        const double angle =
            Eigen::AngleAxisd(planned.linear().transpose() * observed.linear()).angle();
        if (distance > tamp::kPlanPositionTolerance || angle > tamp::kPlanAngleTolerance) {
          return fmt::format(
              "{}: object '{}' is {:.3f} m and {:.1f}° from where robot '{}' grasps it", at,
              world.scene().name(step.object), distance, angle * 180 / std::numbers::pi, robot);
        }
      }
      if (step.path.empty()) continue;
      const motion::MotionGroup group(world, states[s], {step.robot});
      const motion::QueryEpsilon ends =
          motion::sweepEpsilonForEnds(group, step.path.front(), step.path.back(), {});
      if (ends.status != PlannerStatus::Solved) return at + ": " + ends.problem;
      motion::WorldStateChecker checker(group, ends.epsilon);
      motion::SweptMotionValidator sweeps(group, ends.epsilon);
      for (std::size_t w = 0; w < step.path.size(); ++w) {
        if (const auto collision = checker.firstCollision(step.path[w])) {
          return fmt::format("{}: waypoint {}: {}", at, w + 1, world.describe(*collision));
        }
        if (w > 0 && !sweeps.isValid(step.path[w - 1], step.path[w])) {
          return fmt::format(
              "{}: the motion from waypoint {} to {} is not certified free of "
              "collisions (robot '{}', swept volumes within {:g} m)",
              at, w, w + 1, robot, ends.epsilon);
        }
      }
    }
    current = states.back();
  }
  return "";
}

namespace {

// The expected state with the observed objects where they are (held objects stay held).
world::GeometricState observedState(const world::World& world, world::GeometricState state,
                                    const WorldObservation& observed) {
  for (const auto& [object, pose] : observed.objects) {
    auto& placement = state.placements[world.scene().slot(object)];
    if (placement.present) placement.pose = pose;
  }
  return state;
}

}  // namespace

std::vector<LogRecord> executionLog(const ExecutionResult& result) {
  const std::vector<TimedAction>& actions = result.schedule.actions();
  const std::vector<GripperEvent>& events = result.schedule.events();
  std::vector<LogRecord> log;
  std::size_t event = 0;
  std::size_t sensed = 0;
  for (std::size_t a = 0; a <= actions.size(); ++a) {
    for (; sensed < result.sensed.size() && result.sensed[sensed].actionsBefore <= a; ++sensed) {
      log.push_back({LogRecord::Kind::Sensing, sensed, result.sensed[sensed].time});
    }
    if (a == actions.size()) break;
    log.push_back({LogRecord::Kind::Action, a, actions[a].start});
    for (; event < events.size() && events[event].node == actions[a].node; ++event) {
      log.push_back({LogRecord::Kind::Gripper, event, events[event].time});
    }
  }
  return log;
}

ExecutionResult execute(const world::World& world, const symbolic::KnowledgeTask& task,
                        const tamp::PlanFileContents& plan, const ExecutionOptions& options) {
  const std::vector<JointLimits> limits = jointLimits(world, options.trajectory);
  world::GeometricState current = world.initialState();
  std::vector<std::vector<double>> initial;
  for (const world::RobotState& robot : current.robots) initial.push_back(robot.configuration);
  ExecutionResult result{false,
                         "",
                         {},
                         Schedule(initial, limits, options.trajectory.profile),
                         branchTimings(plan, task, limits, options.trajectory.profile)};
  int n = plan.plan.root;
  // A run through a DAG meets each node at most once.
  for (std::size_t visited = 0; n >= 0 && visited <= plan.plan.nodes.size(); ++visited) {
    const auto node = static_cast<std::size_t>(n);
    const PlanTree::Node& at = plan.plan.nodes[node];
    if (at.kind == PlanTree::Node::Kind::Goal) {
      result.reachedGoal = true;
      return result;
    }
    if (at.kind == PlanTree::Node::Kind::Branch) {
      const SensingQuery query{node, &at, symbolic::branchTest(task, at)};
      if (!options.sensing) {
        throw InputError(
            fmt::format("nodes[{}]: the plan branches on {}: no sensing source", node, query.test));
      }
      const bool value = options.sensing(query);
      result.sensed.push_back(
          {node, query.test, value, result.schedule.duration(), result.schedule.actions().size()});
      n = value ? at.next : at.onFalse;
      continue;
    }
    const std::string name = actionName(task, at);
    if (options.observed) {
      const std::string failure = preconditionFailure(
          world, observedState(world, current, *options.observed), plan.geometry[node]);
      if (!failure.empty()) {
        result.stopReason = fmt::format("nodes[{}] {}: {}", node, name, failure);
        return result;
      }
    }
    for (const tamp::ActionGeometry& effect : plan.geometry[node]) {
      try {
        current = tamp::statesAlong(world, current, effect).back();
      } catch (const std::invalid_argument& error) {
        throw InputError(fmt::format("nodes[{}] {}: {}", node, name, error.what()));
      }
    }
    result.schedule.append(node, name, plan.geometry[node]);
    n = at.next;
  }
  throw InputError(fmt::format("nodes[{}]: the plan does not reach a goal node (a cycle)", n));
}

}  // namespace kaboum::exec
