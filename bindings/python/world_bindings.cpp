// kaboum.World and kaboum.State: a scene's geometry and its geometric states, with the queries
// the geometric attachments use (thesis §6.1.2): forward and inverse kinematics of a tool,
// collisions through the bounded (or exact) predicates, certified motions.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/motion/motion_group.hpp"
#include "kaboum/tamp/geometric_attachments.hpp"
#include "kaboum/tamp/solver.hpp"
#include "scene_world.hpp"

namespace kaboum::python {

namespace {

// The scene object held, and where the state's robot holds it, by name.
std::optional<std::string> holderName(const SceneState& self, const std::string& object) {
  const std::optional<std::size_t> holder = tamp::holderOf(self.state, self.scene->object(object));
  if (!holder) return std::nullopt;
  return self.scene->world().robots()[*holder].name;
}

std::vector<std::string> heldNames(const SceneState& self, const std::string& robot) {
  std::vector<std::string> names;
  for (const std::size_t object : self.state.robots[self.scene->robot(robot)].heldObjects) {
    names.push_back(self.scene->world().description().objects[object].name);
  }
  return names;
}

void setConfiguration(SceneState& self, const std::string& robot, const Array& q) {
  std::vector<double>& configuration = self.state.robots[self.scene->robot(robot)].configuration;
  std::vector<double> values = vectorFrom(q);
  if (values.size() != configuration.size()) {
    throw std::invalid_argument(fmt::format("robot '{}' has {} joints, got {} values", robot,
                                            configuration.size(), values.size()));
  }
  configuration = std::move(values);
}

std::optional<std::string> firstCollision(const SceneWorld& self, const SceneState& state) {
  const std::optional<world::Collision> collision = self.world().firstCollision(state.state);
  if (!collision) return std::nullopt;
  return self.world().describe(*collision);
}

MotionPlan planMotion(const SceneWorld& self, const SceneState& state, const std::string& robot,
                      const Array& goal, const std::string& planner, double timeLimit,
                      std::uint64_t seed) {
  const std::size_t index = self.robot(robot);
  const std::vector<double> target = vectorFrom(goal);
  motion::MotionOptions options;
  options.planner = planner;
  options.timeLimit = timeLimit;
  options.seed = seed;
  motion::MotionResult result;
  {
    py::gil_scoped_release unlocked;
    const motion::MotionGroup group(self.world(), state.state, {index});
    result = motion::planMotion(group, group.configuration(state.state), target, options);
  }
  return motionPlan(result, state.state.robots[index].configuration.size());
}

std::optional<std::string> sweptCollision(const SceneWorld& self, const SceneState& state,
                                          const std::string& robot, const Array& path) {
  const motion::Waypoints waypoints = waypointsFromArray(path);
  const std::size_t index = self.robot(robot);
  py::gil_scoped_release unlocked;
  return uncertifiedSegment(self.world(), state.state, index, waypoints);
}

// The independent check of a motion (verify::verifyPath, docs/verify.md), as Python receives it.
struct PathCheck {
  bool collisionFree = true;
  std::size_t samples = 0;
  std::optional<double> clearance;
  std::string firstCollision;
};

PathCheck verifyMotion(SceneWorld& self, const SceneState& state, const std::string& robot,
                       const Array& path, double jointStepDegrees, double toolStepMillimetres) {
  tamp::ActionGeometry motion;
  motion.procedure = "path";
  tamp::GeometricStep step;
  step.robot = self.robot(robot);
  step.path = waypointsFromArray(path);
  motion.steps.push_back(std::move(step));
  const verify::VerifyOptions options = cli::verifyOptions({jointStepDegrees, toolStepMillimetres});
  const verify::ReferenceGeometry& reference = self.reference();
  tamp::PlanVerification verification;
  {
    py::gil_scoped_release unlocked;
    tamp::verifyActionPaths(reference, 0, motion, {state.state}, options, verification);
  }
  const verify::PathVerification& result = verification.checks.front().result;
  PathCheck check{result.collisionFree(), result.samples, std::nullopt,
                  verification.firstCollision};
  if (result.clearance) check.clearance = result.clearance->distance;
  return check;
}

}  // namespace

void bindWorld(py::module_& module) {
  py::class_<SceneWorld, std::shared_ptr<SceneWorld>>(
      module, "World",
      "A scene file built into collision geometry (docs/scene-format.md, docs/world.md): robots "
      "with their tools, objects with grasps, locations. Shared, read-only, by every query.")
      .def(
          py::init([](const std::string& scene, bool noCache, const std::string& cacheDir,
                      unsigned threads, std::optional<std::string> epsilon,
                      std::optional<std::uint64_t> placementSeed, const std::string& geometry,
                      const std::string& pieces) {
            if (pieces != "decomposition" && pieces != "hulls") {
              throw InputError("pieces: expected 'decomposition' or 'hulls', got '" + pieces + "'");
            }
            cli::SceneLoadOptions load;
            load.noCache = noCache;
            load.cacheDirectory = cacheDir;
            load.threads = threads;
            load.epsilon = std::move(epsilon);
            load.placementSeed = placementSeed;
            load.pieces =
                pieces == "hulls" ? world::MeshPieces::Hulls : world::MeshPieces::Decomposition;
            py::gil_scoped_release unlocked;
            return std::make_shared<SceneWorld>(scene, load, geometry);
          }),
          py::arg("scene"), py::kw_only(), py::arg("no_cache") = false, py::arg("cache_dir") = "",
          py::arg("threads") = 0u, py::arg("epsilon") = py::none(),
          py::arg("placement_seed") = py::none(), py::arg("geometry") = "bounded",
          py::arg("pieces") = "decomposition",
          "Reads and builds `scene` as `kaboum scene` does: decompositions cached in `cache_dir` "
          "(default $KABOUM_CACHE_DIR, $XDG_CACHE_HOME/kaboum or ~/.cache/kaboum) unless "
          "`no_cache`; `epsilon` ('0.005' metres or '1%') overrides the scene's, and "
          "`placement_seed` its placement_seed (objects with place_in); `geometry` "
          "'exact' answers collision queries with FCL on the original meshes; `pieces` 'hulls' "
          "bounds each mesh by its convex hull instead of decomposing it (fast, coarse: for "
          "tests). Raises InputError.")
      .def_property_readonly("file", &SceneWorld::file)
      .def_property_readonly("geometry", &SceneWorld::geometry)
      .def_property_readonly(
          "robots",
          [](const SceneWorld& self) {
            std::vector<std::string> names;
            for (const world::WorldRobot& robot : self.world().robots())
              names.push_back(robot.name);
            return names;
          },
          "Robot names, in the scene file's order.")
      .def_property_readonly(
          "objects",
          [](const SceneWorld& self) {
            std::vector<std::string> names;
            for (const io::ObjectSpec& object : self.world().description().objects) {
              names.push_back(object.name);
            }
            return names;
          },
          "Object names (fixed and movable), in the scene file's order.")
      .def_property_readonly(
          "locations",
          [](const SceneWorld& self) {
            std::vector<std::string> names;
            for (const io::LocationSpec& location : self.world().description().locations) {
              names.push_back(location.name);
            }
            return names;
          },
          "Location names (regions, support surfaces).")
      .def(
          "tools",
          [](const SceneWorld& self, const std::string& robot) {
            std::vector<std::string> names;
            for (const io::ToolSpec& tool :
                 self.world().description().robots[self.robot(robot)].tools) {
              names.push_back(tool.name);
            }
            return names;
          },
          py::arg("robot"), "The robot's tool names; the first is its default tool.")
      .def_property_readonly(
          "preprocessing_seconds",
          [](const SceneWorld& self) { return self.world().preprocessingSeconds(); },
          "Seconds spent building the geometry (decompositions read from the cache included).")
      .def(
          "initial_state",
          [](const std::shared_ptr<SceneWorld>& self) {
            return SceneState{self, self->world().initialState()};
          },
          "Every robot at home holding nothing, every object at its initial pose.")
      .def("first_collision", &firstCollision, py::arg("state"),
           "The first collision in `state` as a sentence (\"robot 'kr5' link 'link_6' collides "
           "with object 'table'\"), or None.")
      .def(
          "tool_pose",
          [](const std::shared_ptr<SceneWorld>& self, const SceneState& state,
             const std::string& robot, std::optional<std::string> tool) {
            const std::size_t r = self->robot(robot);
            return poseArray(self->kinematics(r, self->tool(r, tool))
                                 .tcpPose(state.state.robots[r].configuration));
          },
          py::arg("state"), py::arg("robot"), py::arg("tool") = py::none(),
          "Forward kinematics: the tool centre point's world pose (4x4) in `state`.")
      .def(
          "inverse_kinematics",
          [](const std::shared_ptr<SceneWorld>& self, const SceneState& state,
             const std::string& robot, const Array& pose, std::optional<std::string> tool) {
            const std::size_t r = self->robot(robot);
            std::vector<py::array_t<double>> solutions;
            for (const std::vector<double>& q :
                 self->kinematics(r, self->tool(r, tool))
                     .solutions(poseFromArray(pose), state.state.robots[r].configuration)) {
              solutions.push_back(vectorArray(q));
            }
            return solutions;
          },
          py::arg("state"), py::arg("robot"), py::arg("pose"), py::arg("tool") = py::none(),
          "Robot configurations placing the tool centre point at `pose` (4x4, world frame): the "
          "closed form's solutions or numeric ones, nearest the robot's configuration in `state` "
          "first; empty when the pose is out of reach. Collisions are not checked.")
      .def("plan_motion", &planMotion, py::arg("state"), py::arg("robot"), py::arg("goal"),
           py::kw_only(), py::arg("planner") = "rrtconnect", py::arg("time_limit") = 10.0,
           py::arg("seed") = 1,
           "A certified motion of `robot` from its configuration in `state` to `goal` (every "
           "segment's swept volume free of the rest of `state`): the straight segment, else the "
           "planner's path shortcut. Releases the GIL.")
      .def("swept_collision", &sweptCollision, py::arg("state"), py::arg("robot"), py::arg("path"),
           "Why the swept volumes of the path's segments (the robot moving in `state`, what it "
           "holds with it) are not certified free at the scene's sweep epsilon, or None when "
           "they all are. Releases the GIL.")
      .def("verify_path", &verifyMotion, py::arg("state"), py::arg("robot"), py::arg("path"),
           py::kw_only(), py::arg("joint_step") = 0.5, py::arg("tool_step") = 1.0,
           "The independent check of `kaboum verify-path`: the path replayed densely (joints at "
           "most `joint_step` degrees, link origins and tool points at most `tool_step` mm "
           "apart) in `state` with FCL on the original meshes. Releases the GIL.");

  py::class_<PathCheck>(module, "PathCheck", "The result of World.verify_path.")
      .def_readonly("collision_free", &PathCheck::collisionFree)
      .def_readonly("samples", &PathCheck::samples, "Configurations checked.")
      .def_readonly("clearance", &PathCheck::clearance,
                    "Metres: the smallest distance between parties checked, or None.")
      .def_readonly("first_collision", &PathCheck::firstCollision, "'' when collision free.");

  py::class_<SceneState>(module, "State",
                         "A geometric state: every robot's configuration and what it holds, every "
                         "movable object's placement. A copy owned by Python.")
      .def_property_readonly("world", [](const SceneState& self) { return self.scene; })
      .def(
          "configuration",
          [](const SceneState& self, const std::string& robot) {
            return vectorArray(self.state.robots[self.scene->robot(robot)].configuration);
          },
          py::arg("robot"), "The robot's joint values (radians, metres), URDF variable order.")
      .def("set_configuration", &setConfiguration, py::arg("robot"), py::arg("q"),
           "Sets the robot's joint values; what it holds moves with it.")
      .def(
          "object_pose",
          [](const SceneState& self, const std::string& object) {
            return poseArray(
                tamp::objectPose(self.scene->world(), self.state, self.scene->object(object)));
          },
          py::arg("object"), "The object's world pose (4x4), held or placed.")
      .def("holder", &holderName, py::arg("object"), "The robot holding the object, or None.")
      .def("held", &heldNames, py::arg("robot"), "The objects the robot holds.")
      .def("copy", [](const SceneState& self) { return SceneState(self); })
      .def("__eq__",
           [](const SceneState& self, const SceneState& other) {
             return self.scene == other.scene && self.state == other.state;
           })
      .def("__hash__", [](const SceneState& self) { return self.state.hashValue(); });

  py::class_<MotionPlan>(module, "MotionPlan", "The result of World.plan_motion.")
      .def_readonly("status", &MotionPlan::status, "'solved', 'time-limit', 'invalid-goal', …")
      .def_readonly("message", &MotionPlan::message, "Why the query failed, or ''.")
      .def_readonly("path", &MotionPlan::path, "Waypoints x joints; empty unless solved.")
      .def_readonly("sweep_epsilon", &MotionPlan::sweepEpsilon,
                    "Metres: the bound the swept volumes certified at.")
      .def_readonly("seconds", &MotionPlan::seconds)
      .def_property_readonly("solved",
                             [](const MotionPlan& self) { return self.status == "solved"; });
}

}  // namespace kaboum::python
