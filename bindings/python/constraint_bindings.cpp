// kaboum.Shape, kaboum.Constraint and World.sample_constraints: configurations of one or more
// robots that satisfy Table 5.1's geometric constraints between points, lines and planes on their
// tools and fixed in the world, by constraint projection (thesis §5.2, Algorithm 3;
// docs/kinematics.md).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <map>

#include "bindings.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/kinematics/constraint_sampler.hpp"
#include "scene_world.hpp"

namespace kaboum::python {

namespace {

using kinematics::ConstraintType;
using kinematics::PrimitiveShape;

// A point, line or plane on a robot's tool centre point frame, or fixed in a world frame.
struct Shape {
  PrimitiveShape shape;
  std::optional<std::string> robot;
  std::optional<std::string> tool;
  Pose frame = Pose::Identity();
};

struct Constraint {
  ConstraintType type = ConstraintType::Coincident;
  Shape first;
  Shape second;
  double distance = 0;
};

Eigen::Vector3d vector3(const Array& values, const char* what) {
  const std::vector<double> v = vectorFrom(values);
  if (v.size() != 3) throw std::invalid_argument(fmt::format("{}: expected 3 values", what));
  return {v[0], v[1], v[2]};
}

Shape makeShape(const std::string& kind, const Array& point, const Array& direction,
                std::optional<std::string> robot, std::optional<std::string> tool,
                const std::optional<Array>& frame) {
  const Eigen::Vector3d p = vector3(point, "point");
  const Eigen::Vector3d d = vector3(direction, "direction");
  if (kind != "point" && d.norm() == 0) throw std::invalid_argument("direction: must not be zero");
  if (robot && frame) throw std::invalid_argument("a shape is on a robot's tool or in a frame");
  if (tool && !robot) throw std::invalid_argument("tool: names a tool of the shape's robot");
  Shape shape{
      {}, std::move(robot), std::move(tool), frame ? poseFromArray(*frame) : Pose::Identity()};
  if (kind == "point") {
    shape.shape = PrimitiveShape::makePoint(p);
  } else if (kind == "line") {
    shape.shape = PrimitiveShape::makeLine(p, d);
  } else if (kind == "plane") {
    shape.shape = PrimitiveShape::makePlane(p, d);
  } else {
    throw InputError("kind: expected one of point, line, plane, got '" + kind + "'");
  }
  return shape;
}

Constraint makeConstraint(const std::string& type, Shape first, Shape second, double distance) {
  static const std::map<std::string, ConstraintType> types{
      {"coincident", ConstraintType::Coincident},
      {"parallel", ConstraintType::Parallel},
      {"perpendicular", ConstraintType::Perpendicular},
      {"distance", ConstraintType::Distance}};
  const auto found = types.find(type);
  if (found == types.end()) {
    throw InputError("type: expected one of coincident, parallel, perpendicular, distance, got '" +
                     type + "'");
  }
  if (found->second != ConstraintType::Distance && distance != 0) {
    throw std::invalid_argument("distance: only a distance constraint takes one");
  }
  if (distance < 0) throw std::invalid_argument("distance: must not be negative");
  // Throws InputError for a pair Table 5.1 does not define, in the order given.
  (void)kinematics::costFunctionFor(found->second, first.shape.kind, second.shape.kind);
  return {found->second, std::move(first), std::move(second), distance};
}

// Robot configurations reaching the constraints (Algorithm 3 from random starts), each a copy of
// `state` with the constrained robots' tool chains moved; up to `samples` of them.
std::vector<SceneState> sampleConstraints(const std::shared_ptr<SceneWorld>& scene,
                                          const SceneState& state,
                                          const std::vector<Constraint>& constraints,
                                          std::size_t samples, std::uint64_t seed, double tolerance,
                                          int attempts) {
  if (constraints.empty()) throw std::invalid_argument("constraints: none given");
  if (!(tolerance > 0)) throw std::invalid_argument("tolerance: expected a positive number");
  if (attempts < 1) throw std::invalid_argument("attempts: expected at least 1");
  kinematics::ConstraintProblem problem;
  struct Arm {
    std::size_t robot;
    std::size_t tool;
    int index;  // in the problem
    motion::ToolKinematics* kinematics;
  };
  std::vector<Arm> arms;
  const auto attach = [&](const Shape& shape) {
    if (!shape.robot) return problem.attachToObject(shape.frame, shape.shape);
    const std::size_t robot = scene->robot(*shape.robot);
    const std::size_t tool = scene->tool(robot, shape.tool);
    auto arm =
        std::find_if(arms.begin(), arms.end(), [&](const Arm& a) { return a.robot == robot; });
    if (arm == arms.end()) {
      motion::ToolKinematics& kinematics = scene->kinematics(robot, tool);
      const int index = problem.addRobot(
          kinematics.chain(), kinematics.chainBase(state.state.robots[robot].configuration));
      arm = arms.insert(arms.end(), {robot, tool, index, &kinematics});
    } else if (arm->tool != tool) {
      throw std::invalid_argument(
          fmt::format("robot '{}': its shapes are on one tool only", *shape.robot));
    }
    return problem.attachToTool(arm->index, arm->kinematics->tcp(), shape.shape);
  };
  for (const Constraint& constraint : constraints) {
    const auto first = attach(constraint.first);
    const auto second = attach(constraint.second);
    problem.addConstraint(constraint.type, first, second, constraint.distance);
  }
  if (arms.empty()) throw std::invalid_argument("constraints: no shape is on a robot's tool");
  kinematics::ConstraintSamplerOptions options;
  options.tolerance = tolerance;
  options.maxAttempts = attempts;
  options.seed = seed;
  std::vector<SceneState> found;
  {
    py::gil_scoped_release unlocked;
    kinematics::ConstraintSampler sampler(problem, options);
    std::vector<double> q(static_cast<std::size_t>(problem.dof()));
    for (std::size_t s = 0; s < samples; ++s) {
      if (!sampler.sample(q)) continue;
      SceneState sample{scene, state.state};
      for (const Arm& arm : arms) {
        std::vector<double>& configuration = sample.state.robots[arm.robot].configuration;
        const auto first = q.begin() + problem.firstVariable(arm.index);
        configuration = arm.kinematics->withChainValues(
            configuration, std::span(first, first + problem.chain(arm.index).dof()));
      }
      found.push_back(std::move(sample));
    }
  }
  return found;
}

}  // namespace

void bindConstraints(py::module_& module) {
  py::class_<Shape>(module, "Shape",
                    "A point, line or plane (thesis Table 5.1) on a robot's tool centre point "
                    "frame, or fixed in a world frame.")
      .def(py::init(&makeShape), py::arg("kind"), py::arg("point") = py::make_tuple(0.0, 0.0, 0.0),
           py::arg("direction") = py::make_tuple(0.0, 0.0, 1.0), py::kw_only(),
           py::arg("robot") = py::none(), py::arg("tool") = py::none(),
           py::arg("frame") = py::none(),
           "`kind` 'point', 'line' (through `point` along `direction`) or 'plane' (through "
           "`point`, normal `direction`), given in the tool centre point frame of `robot` (its "
           "`tool`, default the first), else in `frame` (4x4 world pose, default the world).")
      .def_property_readonly(
          "kind",
          [](const Shape& self) { return lowerCase(kinematics::toString(self.shape.kind)); })
      .def_property_readonly("point",
                             [](const Shape& self) {
                               return vectorArray({self.shape.point.data(), 3});
                             })
      .def_property_readonly("direction",
                             [](const Shape& self) {
                               return vectorArray({self.shape.direction.data(), 3});
                             })
      .def_readonly("robot", &Shape::robot)
      .def_readonly("tool", &Shape::tool);
  py::class_<Constraint>(module, "Constraint",
                         "A geometric constraint between two shapes (thesis Table 5.1).")
      .def(py::init(&makeConstraint), py::arg("type"), py::arg("first"), py::arg("second"),
           py::arg("distance") = 0.0,
           "`type` 'coincident', 'parallel', 'perpendicular' or 'distance' (`distance` metres) "
           "between `first` and `second` in Table 5.1's order (point before line before plane: "
           "Distance(point, plane), not (plane, point)). InputError for a pair Table 5.1 does "
           "not define.")
      .def_property_readonly(
          "type", [](const Constraint& self) { return lowerCase(kinematics::toString(self.type)); })
      .def_readonly("distance", &Constraint::distance);

  py::object world = module.attr("World");
  world.attr("sample_constraints") = py::cpp_function(
      &sampleConstraints, py::name("sample_constraints"), py::is_method(world),
      py::sibling(py::getattr(world, "sample_constraints", py::none())), py::arg("state"),
      py::arg("constraints"), py::kw_only(), py::arg("samples") = 1, py::arg("seed") = 1,
      py::arg("tolerance") = 1e-6, py::arg("attempts") = 20,
      "Constraint sampling (thesis §5.2, Algorithm 3): up to `samples` states, each `state` with "
      "the tool chains of the robots the constraints name moved onto the constraint manifold "
      "(F(q) within `tolerance`) by projection from random starts (`attempts` per sample, "
      "seeded by `seed`), within the joint limits. Collisions are not checked. Releases the "
      "GIL.");
}

}  // namespace kaboum::python
