// The scene as the Python module holds it: a World (thesis §6.1.1) with the collision predicates
// the user chose, its robots, tools, objects and locations by name, and geometric states owned by
// Python; plus the numpy forms of poses (4×4) and paths (waypoints × joints).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/motion/tool_kinematics.hpp"
#include "kaboum/verify/exact_predicates.hpp"
#include "kaboum/verify/reference_geometry.hpp"
#include "kaboum/world/world.hpp"
#include "scene_cli.hpp"

namespace kaboum::python {

namespace py = pybind11;

class SceneWorld {
 public:
  // Reads and builds the scene as `kaboum scene` does; `geometry` "exact" answers the collision
  // queries with FCL on the original meshes (thesis Proposition 4), "bounded" with the bounding
  // convex decomposition. Throws InputError naming the file, or the option.
  SceneWorld(const std::string& sceneFile, const cli::SceneLoadOptions& load,
             const std::string& geometry);
  SceneWorld(const SceneWorld&) = delete;
  SceneWorld& operator=(const SceneWorld&) = delete;

  [[nodiscard]] const world::World& world() const { return world_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] const std::string& geometry() const { return geometry_; }

  // Indices of the scene's names (compared without case); InputError naming the scene otherwise.
  [[nodiscard]] std::size_t robot(const std::string& name) const;
  [[nodiscard]] std::size_t object(const std::string& name) const;
  [[nodiscard]] std::size_t location(const std::string& name) const;
  [[nodiscard]] std::size_t tool(std::size_t robot, const std::optional<std::string>& name) const;

  // The kinematics of a robot's tool, made on first use (under the GIL: not thread-safe).
  motion::ToolKinematics& kinematics(std::size_t robot, std::size_t tool);
  // The original meshes of the independent verifier, read on first use (under the GIL).
  const verify::ReferenceGeometry& reference();

 private:
  [[nodiscard]] std::size_t entity(const std::string& name, world::NamedEntity::Kind kind,
                                   const char* what) const;

  std::string file_;
  std::string geometry_;
  world::World world_;
  std::unique_ptr<verify::ExactPredicates> exact_;
  std::unique_ptr<verify::ReferenceGeometry> reference_;
  std::map<std::pair<std::size_t, std::size_t>, std::unique_ptr<motion::ToolKinematics>> tools_;
};

// A geometric state of a scene (robot configurations, object placements, who holds what), owned
// by Python.
struct SceneState {
  std::shared_ptr<SceneWorld> scene;
  world::GeometricState state;
};

// A pose as a 4×4 homogeneous matrix, and back (ValueError for another shape or a last row other
// than 0 0 0 1).
py::array_t<double> poseArray(const Pose& pose);
Pose poseFromArray(const py::array_t<double, py::array::c_style | py::array::forcecast>& matrix);
// Waypoints as a (waypoints × joints) array, and back (ValueError for rows of unequal length).
py::array_t<double> waypointsArray(const motion::Waypoints& path, std::size_t joints);
motion::Waypoints waypointsFromArray(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& path);
py::array_t<double> vectorArray(std::span<const double> values);
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
// A one-dimensional array as a vector (ValueError otherwise).
std::vector<double> vectorFrom(const Array& values);

// A certified motion of one robot (motion::planMotion, motion::planCartesian), as Python receives
// it.
struct MotionPlan {
  std::string status;
  std::string message;
  py::array_t<double> path;
  double sweepEpsilon = 0;
  double seconds = 0;
};
MotionPlan motionPlan(const motion::MotionResult& result, std::size_t joints);

// Why the swept volumes of `path`'s segments (robot `robot` moving in `state`, what it holds with
// it) are not certified free, as the motion planner certifies them (thesis §4.5), or nullopt when
// they all are. Call without the GIL.
std::optional<std::string> uncertifiedSegment(const world::World& world,
                                              const world::GeometricState& state, std::size_t robot,
                                              const motion::Waypoints& path);

}  // namespace kaboum::python
