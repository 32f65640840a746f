// The geometry of an action built from Python (thesis §6.1.2; docs/python.md): certified motions
// of one robot at a time and gripper events from a geometric state, each step applied as the plan
// replays it (tamp::statesAlong) — what a geometric effect written in Python records, as the C++
// geometric attachments record theirs — and the read-only view of a plan's step.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "kaboum/tamp/geometric_attachments.hpp"
#include "scene_world.hpp"

namespace kaboum::python {

// A step of an action's geometry with the scene's names.
struct StepView {
  std::string kind;
  std::string robot;
  std::string tool;
  py::array_t<double> path;
  std::optional<std::string> object;    // grasp, release, join
  std::optional<std::string> joinedTo;  // join
  py::array_t<double> pose;
};

StepView stepView(const world::World& world, const tamp::GeometricStep& step);

class Transition {
 public:
  // Starts at `from`; motions are planned with `motion`'s planner and time limit, seeded in turn
  // from `seed`, and stop when `cancel` (may be null) is set.
  Transition(std::shared_ptr<SceneWorld> scene, world::GeometricState from,
             motion::MotionOptions motion, std::uint64_t seed,
             std::shared_ptr<std::atomic<bool>> cancel);

  // A certified joint-space motion of `robot` to configuration `goal` (motion::planMotion), added
  // as a step of `kind` (default transit, or transfer while the robot holds something) when
  // solved. Releases the GIL.
  MotionPlan move(const std::string& robot, const Array& goal,
                  const std::optional<std::string>& tool, const std::optional<std::string>& kind);
  // A certified Cartesian line of the tool centre point to `pose` (motion::planCartesian), added
  // as a step of `kind` when solved. Releases the GIL.
  MotionPlan line(const std::string& robot, const Array& pose,
                  const std::optional<std::string>& tool, const std::string& kind);
  // `path` (starting where the robot is) added as a step when every segment's swept volume is
  // certified free; else why not, and nothing is added. Releases the GIL.
  std::optional<std::string> follow(const std::string& robot, const Array& path,
                                    const std::optional<std::string>& tool,
                                    const std::optional<std::string>& kind);
  // The robot's tool grasps `object` where it is (from the robot holding it: a handover).
  void grasp(const std::string& robot, const std::string& object,
             const std::optional<std::string>& tool);
  // The robot lets go of `object` where it holds it (right after a handover's grasp: the giver).
  void release(const std::string& robot, const std::string& object);
  // `robot` has assembled `object` into `joinedTo`: from here on they may touch.
  void join(const std::string& robot, const std::string& object, const std::string& joinedTo);

  [[nodiscard]] const std::shared_ptr<SceneWorld>& scene() const { return scene_; }
  [[nodiscard]] const world::GeometricState& from() const { return from_; }
  [[nodiscard]] const world::GeometricState& state() const { return state_; }
  [[nodiscard]] const std::vector<tamp::GeometricStep>& steps() const { return steps_; }

 private:
  // Appends `step` and moves the state on; std::invalid_argument for a gripper event that does
  // not apply (nothing added).
  void add(tamp::GeometricStep step);
  // The index of a movable scene object; InputError for an unknown name, ValueError for a fixed
  // object.
  [[nodiscard]] std::size_t movable(const std::string& object) const;
  [[nodiscard]] tamp::GeometricStep::Kind motionKind(std::size_t robot,
                                                     const std::optional<std::string>& kind) const;

  std::shared_ptr<SceneWorld> scene_;
  world::GeometricState from_;
  world::GeometricState state_;
  std::vector<tamp::GeometricStep> steps_;
  motion::MotionOptions motion_;
  std::mt19937_64 seeds_;
  std::shared_ptr<std::atomic<bool>> cancel_;
};

}  // namespace kaboum::python
