// The motion-planning set-up users of MoveIt have today, as the baseline of `kaboum-compare
// motion`: OMPL's RRT-Connect with FCL on the ORIGINAL meshes as state validity checker (the
// verify module's ReferenceGeometry: link meshes as fcl::BVHModel<OBBRSS>, primitives as FCL
// shapes, bounding spheres culling the pairs), motions checked at discrete states (OMPL's
// DiscreteMotionValidator) and OMPL's PathSimplifier. Nothing is certified between the checked
// states: a motion can step over a thin obstacle.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "kaboum/motion/motion_group.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::cli {

// Whether one robot of a World collides at a configuration, by FCL on the original geometry:
// every link against every scene object (at its initial pose) and against every other link of
// the robot except the pairs the World's robot collision filter allows (adjacent links, the
// SRDF's pairs, pairs overlapping at home). Pairs whose bounding spheres are apart are skipped.
class FclStateChecker {
 public:
  // `geometry` must outlive the checker; `robot` indexes geometry.world().robots().
  FclStateChecker(const verify::ReferenceGeometry& geometry, std::size_t robot);

  // q: the robot's configuration. Counts the call.
  [[nodiscard]] bool isValid(std::span<const double> q);
  [[nodiscard]] std::size_t checks() const { return checks_; }

 private:
  const verify::ReferenceGeometry& geometry_;
  const world::WorldRobot& robot_;
  std::vector<std::pair<std::size_t, std::size_t>> links_;      // (link, body) with geometry
  std::vector<std::pair<std::size_t, Pose>> objects_;           // (body, world pose)
  std::vector<std::pair<std::size_t, std::size_t>> selfPairs_;  // indices into links_
  std::vector<Pose> linkPoses_;
  std::size_t checks_ = 0;
};

struct OmplFclOptions {
  double timeLimit = 10;  // seconds for planning; the simplification runs after it
  // The largest motion of any joint between two checked states of a motion (radians).
  double resolution = 0.017453292519943295;  // 1°
};

struct OmplFclResult {
  std::string status;  // OMPL's PlannerStatus as text ("Exact solution", "Timeout", ...)
  bool solved = false;
  std::vector<std::vector<double>> path;  // simplified; empty unless solved
  double planningSeconds = 0;
  double simplifySeconds = 0;
  std::size_t plannedWaypoints = 0;
  double plannedLength = 0;  // joint-space length before simplification
  double length = 0;
  std::size_t stateChecks = 0;  // FclStateChecker calls (planning and simplification)
};

// RRT-Connect from `start` to `goal` in the joint space of `group` (its joint limits), states
// checked by `checker`, motions by OMPL's DiscreteMotionValidator with at most
// `options.resolution` of motion of any joint between two checked states, then
// PathSimplifier::simplifyMax. OMPL's generators follow its global seed (ompl::RNG::setSeed).
OmplFclResult planWithOmplFcl(const motion::MotionGroup& group, FclStateChecker& checker,
                              std::span<const double> start, std::span<const double> goal,
                              const OmplFclOptions& options);

}  // namespace kaboum::cli
