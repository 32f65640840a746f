// kaboum.Transition and kaboum.Step: an action's geometry built step by step from Python, and the
// steps of a plan's actions (docs/python.md, docs/plan-format.md).
#include "transition.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.hpp"
#include "kaboum/motion/cartesian_motion.hpp"
#include "kaboum/motion/motion_group.hpp"
#include "kaboum/tamp/plan_reader.hpp"

namespace kaboum::python {

using tamp::GeometricStep;

StepView stepView(const world::World& world, const GeometricStep& step) {
  const io::RobotSpec& robot = world.description().robots[step.robot];
  const bool event = step.kind == GeometricStep::Kind::Grasp ||
                     step.kind == GeometricStep::Kind::Release ||
                     step.kind == GeometricStep::Kind::Join;
  const auto name = [&](std::size_t object) { return world.description().objects[object].name; };
  return {
      tamp::toString(step.kind),
      robot.name,
      robot.tools[step.tool].name,
      waypointsArray(step.path, world.robots()[step.robot].home.size()),
      event ? std::optional(name(step.object)) : std::nullopt,
      step.kind == GeometricStep::Kind::Join ? std::optional(name(step.joinedTo)) : std::nullopt,
      poseArray(step.pose)};
}

Transition::Transition(std::shared_ptr<SceneWorld> scene, world::GeometricState from,
                       motion::MotionOptions motion, std::uint64_t seed,
                       std::shared_ptr<std::atomic<bool>> cancel)
    : scene_(std::move(scene)),
      from_(std::move(from)),
      state_(from_),
      motion_(std::move(motion)),
      seeds_(seed),
      cancel_(std::move(cancel)) {
  motion_.cancel = cancel_.get();
}

GeometricStep::Kind Transition::motionKind(std::size_t robot,
                                           const std::optional<std::string>& kind) const {
  if (!kind) {
    return state_.robots[robot].heldObjects.empty() ? GeometricStep::Kind::Transit
                                                    : GeometricStep::Kind::Transfer;
  }
  for (const GeometricStep::Kind motion :
       {GeometricStep::Kind::Transit, GeometricStep::Kind::Transfer, GeometricStep::Kind::Approach,
        GeometricStep::Kind::Retreat}) {
    if (*kind == tamp::toString(motion)) return motion;
  }
  throw std::invalid_argument(
      fmt::format("kind: expected one of transit, transfer, approach, retreat, got '{}'", *kind));
}

std::size_t Transition::movable(const std::string& object) const {
  const std::size_t index = scene_->object(object);
  if (!scene_->world().scene().movable(index)) {
    throw std::invalid_argument(fmt::format("object '{}' is not movable", object));
  }
  return index;
}

void Transition::add(GeometricStep step) {
  // The whole action replayed: a handover's release depends on the grasp before it.
  tamp::ActionGeometry action{"", {}, 0, 0, steps_};
  action.steps.push_back(std::move(step));
  state_ = tamp::statesAlong(scene_->world(), from_, action).back();
  steps_ = std::move(action.steps);
}

MotionPlan Transition::move(const std::string& robot, const Array& goal,
                            const std::optional<std::string>& tool,
                            const std::optional<std::string>& kind) {
  const std::size_t r = scene_->robot(robot);
  const GeometricStep::Kind motion = motionKind(r, kind);
  const std::size_t t = scene_->tool(r, tool);
  const std::vector<double> target = vectorFrom(goal);
  motion::MotionOptions options = motion_;
  options.seed = seeds_();
  motion::MotionResult result;
  {
    py::gil_scoped_release unlocked;
    const motion::MotionGroup group(scene_->world(), state_, {r});
    result = motion::planMotion(group, group.configuration(state_), target, options);
  }
  MotionPlan plan = motionPlan(result, state_.robots[r].configuration.size());
  if (result.status == PlannerStatus::Solved) add({motion, r, t, std::move(result.path)});
  return plan;
}

MotionPlan Transition::line(const std::string& robot, const Array& pose,
                            const std::optional<std::string>& tool, const std::string& kind) {
  const std::size_t r = scene_->robot(robot);
  const GeometricStep::Kind motion = motionKind(r, kind);
  const std::size_t t = scene_->tool(r, tool);
  const Pose target = poseFromArray(pose);
  motion::MotionOptions options = motion_;
  options.seed = seeds_();
  motion::MotionResult result;
  {
    py::gil_scoped_release unlocked;
    // Its own kinematics: the scene's are used under the GIL only.
    motion::ToolKinematics kinematics(scene_->world(), r, t, options.seed);
    const motion::MotionGroup group(scene_->world(), state_, {r});
    result =
        motion::planCartesian(group, kinematics, state_.robots[r].configuration, target, options);
  }
  MotionPlan plan = motionPlan(result, state_.robots[r].configuration.size());
  if (result.status == PlannerStatus::Solved) add({motion, r, t, std::move(result.path)});
  return plan;
}

std::optional<std::string> Transition::follow(const std::string& robot, const Array& path,
                                              const std::optional<std::string>& tool,
                                              const std::optional<std::string>& kind) {
  const std::size_t r = scene_->robot(robot);
  const GeometricStep::Kind motion = motionKind(r, kind);
  const std::size_t t = scene_->tool(r, tool);
  motion::Waypoints waypoints = waypointsFromArray(path);
  const std::vector<double>& at = state_.robots[r].configuration;
  if (waypoints.empty() || waypoints.front().size() != at.size()) {
    throw std::invalid_argument(
        fmt::format("a path of robot '{}' has waypoints of its {} joints", robot, at.size()));
  }
  for (std::size_t j = 0; j < at.size(); ++j) {
    if (std::abs(waypoints.front()[j] - at[j]) > tamp::kPlanJointTolerance) {
      throw std::invalid_argument(
          fmt::format("the path starts {:g} (joint {}) from where robot '{}' is",
                      std::abs(waypoints.front()[j] - at[j]), j, robot));
    }
  }
  std::optional<std::string> problem;
  {
    py::gil_scoped_release unlocked;
    problem = uncertifiedSegment(scene_->world(), state_, r, waypoints);
  }
  if (!problem) add({motion, r, t, std::move(waypoints)});
  return problem;
}

void Transition::grasp(const std::string& robot, const std::string& object,
                       const std::optional<std::string>& tool) {
  const std::size_t r = scene_->robot(robot);
  const std::size_t t = scene_->tool(r, tool);
  const std::size_t o = movable(object);
  const world::World& world = scene_->world();
  const world::RobotCollisionModel& model = world.robots()[r].collision;
  const int link = model.model().findLink(world.description().robots[r].tools[t].link).value();
  std::vector<Pose> links(model.model().links().size());
  model.model().linkPoses(state_.robots[r].configuration, links);
  const Pose linkPose = model.basePose() * links[static_cast<std::size_t>(link)];
  add({GeometricStep::Kind::Grasp,
       r,
       t,
       {},
       o,
       linkPose.inverse() * tamp::objectPose(world, state_, o)});
}

void Transition::release(const std::string& robot, const std::string& object) {
  const std::size_t o = movable(object);
  add({GeometricStep::Kind::Release,
       scene_->robot(robot),
       0,
       {},
       o,
       tamp::objectPose(scene_->world(), state_, o)});
}

void Transition::join(const std::string& robot, const std::string& object,
                      const std::string& joinedTo) {
  const std::size_t o = movable(object);
  const std::size_t other = movable(joinedTo);
  if (o == other) throw std::invalid_argument("an object cannot be joined to itself");
  add({GeometricStep::Kind::Join, scene_->robot(robot), 0, {}, o, Pose::Identity(), other});
}

void bindTransition(py::module_& module) {
  py::class_<StepView>(module, "Step",
                       "One step of an action's geometry, in execution order: a certified "
                       "motion of one robot, or a gripper event, or a join.")
      .def_readonly("kind", &StepView::kind,
                    "'transit', 'transfer', 'approach', 'retreat', 'grasp', 'release' or "
                    "'join'.")
      .def_readonly("robot", &StepView::robot)
      .def_readonly("tool", &StepView::tool)
      .def_readonly("path", &StepView::path,
                    "Motions: waypoints x the robot's joints, every segment certified; else "
                    "empty.")
      .def_readonly("object", &StepView::object,
                    "Grasp, release and join: the object (join: the one assembled); else None.")
      .def_readonly("joined_to", &StepView::joinedTo,
                    "Join: the object the other is assembled into (from here on they may touch); "
                    "else None.")
      .def_readonly("pose", &StepView::pose,
                    "Grasp: the object frame in the tool link frame; release: the object's world "
                    "pose (4x4).");

  py::class_<Transition>(
      module, "Transition",
      "The geometry of an action built step by step from a state: certified motions of one robot "
      "at a time and gripper events, each applied as the plan replays it. A geometric effect "
      "written in Python returns AttachmentCall.record(transition) (docs/python.md).")
      .def(py::init([](const SceneState& state, const std::string& planner, double timeLimit,
                       std::uint64_t seed) {
             if (!(timeLimit > 0))
               throw std::invalid_argument("time_limit: expected a positive number");
             motion::MotionOptions motion;
             motion.planner = planner;
             motion.timeLimit = timeLimit;
             return Transition(state.scene, state.state, motion, seed, nullptr);
           }),
           py::arg("state"), py::kw_only(), py::arg("planner") = "rrtconnect",
           py::arg("time_limit") = 2.0, py::arg("seed") = 1,
           "Starts at `state`; motions are planned by `planner` within `time_limit` seconds each, "
           "seeded in turn from `seed`.")
      .def("move", &Transition::move, py::arg("robot"), py::arg("goal"), py::kw_only(),
           py::arg("tool") = py::none(), py::arg("kind") = py::none(),
           "Plans a certified motion of `robot` from where it is to configuration `goal` (as "
           "World.plan_motion, in the current state, what the robot holds with it) and adds it "
           "as a step of `kind` ('transit', or 'transfer' while the robot holds something, by "
           "default) when solved. Returns the MotionPlan. Releases the GIL.")
      .def("line", &Transition::line, py::arg("robot"), py::arg("pose"), py::kw_only(),
           py::arg("tool") = py::none(), py::arg("kind") = "approach",
           "Plans a certified Cartesian line of the tool centre point to `pose` (4x4, world "
           "frame) and adds it as a step of `kind` ('approach' or 'retreat') when solved. "
           "Returns the MotionPlan. Releases the GIL.")
      .def("follow", &Transition::follow, py::arg("robot"), py::arg("path"), py::kw_only(),
           py::arg("tool") = py::none(), py::arg("kind") = py::none(),
           "Adds `path` (waypoints x joints, starting where the robot is) as a step when every "
           "segment's swept volume is certified free in the current state; else returns why "
           "not (World.swept_collision) and adds nothing. Releases the GIL.")
      .def("grasp", &Transition::grasp, py::arg("robot"), py::arg("object"), py::kw_only(),
           py::arg("tool") = py::none(),
           "The robot's tool grasps `object` where it is; from another robot's hand it is a "
           "handover, that robot's release follows. ValueError for a fixed object.")
      .def("release", &Transition::release, py::arg("robot"), py::arg("object"),
           "The robot lets go of `object` where it holds it. ValueError when it does not hold it "
           "(nor just handed it over).")
      .def("join", &Transition::join, py::arg("robot"), py::arg("object"), py::arg("joined_to"),
           "`robot` has assembled `object` into `joined_to`: from here on the two may touch, and "
           "no check tests one against the other.")
      .def_property_readonly(
          "start",
          [](const Transition& self) {
            return SceneState{self.scene(), self.from()};
          },
          "The state the transition starts in.")
      .def_property_readonly(
          "state",
          [](const Transition& self) {
            return SceneState{self.scene(), self.state()};
          },
          "The state after the last step.")
      .def_property_readonly(
          "steps",
          [](const Transition& self) {
            std::vector<StepView> views;
            for (const GeometricStep& step : self.steps()) {
              views.push_back(stepView(self.scene()->world(), step));
            }
            return views;
          },
          "The steps so far.");
}

}  // namespace kaboum::python
