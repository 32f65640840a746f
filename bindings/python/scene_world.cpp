#include "scene_world.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/motion/motion_group.hpp"

namespace kaboum::python {

SceneWorld::SceneWorld(const std::string& sceneFile, const cli::SceneLoadOptions& load,
                       const std::string& geometry)
    : file_(sceneFile), geometry_(geometry), world_([&] {
        if (geometry != "bounded" && geometry != "exact") {
          throw InputError("geometry: expected 'bounded' or 'exact', got '" + geometry + "'");
        }
        return cli::loadWorld(sceneFile, load);
      }()) {
  if (geometry_ == "exact") {
    exact_ = std::make_unique<verify::ExactPredicates>(world_);
    world_.usePredicates(exact_.get());
  }
}

std::size_t SceneWorld::entity(const std::string& name, world::NamedEntity::Kind kind,
                               const char* what) const {
  const std::optional<world::NamedEntity> found = world_.find(name);
  if (!found || found->kind != kind) {
    throw InputError(locate(file_, fmt::format("no {} named '{}'", what, name)));
  }
  return found->index;
}

std::size_t SceneWorld::robot(const std::string& name) const {
  return entity(name, world::NamedEntity::Kind::Robot, "robot");
}

std::size_t SceneWorld::object(const std::string& name) const {
  return entity(name, world::NamedEntity::Kind::Object, "object");
}

std::size_t SceneWorld::location(const std::string& name) const {
  return entity(name, world::NamedEntity::Kind::Location, "location");
}

std::size_t SceneWorld::tool(std::size_t robot, const std::optional<std::string>& name) const {
  const io::RobotSpec& spec = world_.description().robots[robot];
  if (spec.tools.empty()) {
    throw InputError(locate(file_, fmt::format("robot '{}' has no tool", spec.name)));
  }
  if (!name) return 0;
  for (std::size_t t = 0; t < spec.tools.size(); ++t) {
    if (lowerCase(spec.tools[t].name) == lowerCase(*name)) return t;
  }
  throw InputError(
      locate(file_, fmt::format("robot '{}' has no tool named '{}'", spec.name, *name)));
}

motion::ToolKinematics& SceneWorld::kinematics(std::size_t robot, std::size_t tool) {
  std::unique_ptr<motion::ToolKinematics>& kinematics = tools_[{robot, tool}];
  if (!kinematics) kinematics = std::make_unique<motion::ToolKinematics>(world_, robot, tool);
  return *kinematics;
}

const verify::ReferenceGeometry& SceneWorld::reference() {
  if (!reference_) reference_ = std::make_unique<verify::ReferenceGeometry>(world_);
  return *reference_;
}

py::array_t<double> poseArray(const Pose& pose) {
  py::array_t<double> matrix({4, 4});
  auto out = matrix.mutable_unchecked<2>();
  for (py::ssize_t r = 0; r < 4; ++r) {
    for (py::ssize_t c = 0; c < 4; ++c) out(r, c) = pose.matrix()(r, c);
  }
  return matrix;
}

Pose poseFromArray(const py::array_t<double, py::array::c_style | py::array::forcecast>& matrix) {
  if (matrix.ndim() != 2 || matrix.shape(0) != 4 || matrix.shape(1) != 4) {
    throw std::invalid_argument("a pose is a 4x4 homogeneous matrix");
  }
  const auto in = matrix.unchecked<2>();
  Pose pose = Pose::Identity();
  for (py::ssize_t r = 0; r < 4; ++r) {
    for (py::ssize_t c = 0; c < 4; ++c) pose.matrix()(r, c) = in(r, c);
  }
  if (in(3, 0) != 0 || in(3, 1) != 0 || in(3, 2) != 0 || in(3, 3) != 1) {
    throw std::invalid_argument("a pose's last row must be 0 0 0 1");
  }
  return pose;
}

py::array_t<double> waypointsArray(const motion::Waypoints& path, std::size_t joints) {
  py::array_t<double> array({path.size(), joints});
  auto out = array.mutable_unchecked<2>();
  for (std::size_t w = 0; w < path.size(); ++w) {
    for (std::size_t j = 0; j < joints; ++j) {
      out(static_cast<py::ssize_t>(w), static_cast<py::ssize_t>(j)) = path[w][j];
    }
  }
  return array;
}

motion::Waypoints waypointsFromArray(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& path) {
  if (path.ndim() != 2) throw std::invalid_argument("a path is a (waypoints x joints) array");
  const auto in = path.unchecked<2>();
  motion::Waypoints waypoints(static_cast<std::size_t>(in.shape(0)));
  for (py::ssize_t w = 0; w < in.shape(0); ++w) {
    for (py::ssize_t j = 0; j < in.shape(1); ++j) {
      waypoints[static_cast<std::size_t>(w)].push_back(in(w, j));
    }
  }
  return waypoints;
}

py::array_t<double> vectorArray(std::span<const double> values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

std::vector<double> vectorFrom(const Array& values) {
  if (values.ndim() != 1) throw std::invalid_argument("expected a one-dimensional array");
  return {values.data(), values.data() + values.size()};
}

MotionPlan motionPlan(const motion::MotionResult& result, std::size_t joints) {
  return {toString(result.status), result.message, waypointsArray(result.path, joints),
          result.statistics.sweepEpsilon, result.statistics.totalSeconds};
}

std::optional<std::string> uncertifiedSegment(const world::World& world,
                                              const world::GeometricState& state, std::size_t robot,
                                              const motion::Waypoints& path) {
  if (path.empty()) throw std::invalid_argument("a path has at least one waypoint");
  const motion::MotionGroup group(world, state, {robot});
  const motion::QueryEpsilon epsilon =
      motion::sweepEpsilonForEnds(group, path.front(), path.back(), {});
  if (epsilon.status != PlannerStatus::Solved) return epsilon.problem;
  const std::unique_ptr<motion::MotionValidator> validator =
      motion::motionValidator(group, epsilon.epsilon, nullptr);
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (!validator->isValid(path[i], path[i + 1])) {
      return fmt::format("segment {} (waypoints {} to {}) is not certified free", i, i, i + 1);
    }
  }
  return std::nullopt;
}

}  // namespace kaboum::python
