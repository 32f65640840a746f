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

// Whether the robots of a motion group collide at a configuration, by FCL on the original
// geometry: every moving link against every scene object present in the group's context state and
// every link of the robots outside the group (at their context configurations), against every
// link of the other moving robots, and against every other link of its robot except the pairs the
// World's robot collision filter allows (adjacent links, the SRDF's pairs, pairs overlapping at
// home). Objects held in the context are not modelled. Pairs whose bounding spheres are apart are
// skipped.
class FclStateChecker {
 public:
  // `geometry` and `group` must outlive the checker; the group's World is geometry.world().
  FclStateChecker(const verify::ReferenceGeometry& geometry, const motion::MotionGroup& group);

  // q: the group's configuration. Counts the call.
  [[nodiscard]] bool isValid(std::span<const double> q);
  [[nodiscard]] std::size_t checks() const { return checks_; }

 private:
  struct MovingLink {
    std::size_t robot = 0;  // index into group.robots()
    std::size_t link = 0;
    std::size_t body = 0;
  };
  const verify::ReferenceGeometry& geometry_;
  const motion::MotionGroup& group_;
  std::vector<MovingLink> links_;                           // the moving links with geometry
  std::vector<std::pair<std::size_t, Pose>> obstacles_;     // (body, world pose)
  std::vector<std::pair<std::size_t, std::size_t>> pairs_;  // indices into links_
  std::vector<std::vector<Pose>> linkPoses_;                // by moving robot
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
