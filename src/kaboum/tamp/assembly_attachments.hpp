// The assembly actions of the Bimanual Assembly scenario (thesis §6.2.3, Table 6.6, Figure 6.8):
// scenario-specific geometric effects built from the standard attachments' utilities (grasps,
// IK, certified and Cartesian motions, held objects carried along). Each inserts one part into
// another along the receiving part's axis of rotation, the last stretch a Cartesian motion; the
// part inserted then moves with the one it is in. Reference: docs/tamp.md ("Assembly actions").
#pragma once

#include <random>
#include <span>
#include <string>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/tamp/geometric_attachments.hpp"

namespace kaboum::tamp {

// Where a part sits in the part it is assembled into (the scenario's meshes, thesis Figure 6.6):
// its frame in the receiving part's frame is a translation along that part's axis, turned upside
// down or not; the part may turn freely about the axis. The insertion starts `approach` further
// along the axis (negative: from below).
struct AssemblyFit {
  double seatHeight = 0;  // metres along the receiving part's z axis
  double approach = 0;    // metres: the Cartesian insertion's length and side
  bool flipped = false;
};

// The fits of the scenario's parts (pipe.wrl, bearing.wrl, tree.wrl): a bearing pushed upside down
// from below into the pipe's lower seat (the arm holding the pipe from above keeps its upper end),
// a bearing on the tree's upper shaft, the pipe over the tree with that bearing in its upper seat.
struct AssemblyFits {
  AssemblyFit bearingInPipe{0.0115, -0.06, true};
  AssemblyFit bearingOnTree{0.017, 0.08, false};
  AssemblyFit pipeOnTree{0.0255, 0.08, false};
  // Metres: where assemblePipeBearing holds the pipe — horizontally within meetingSpread of where
  // it is held, from its height up to meetingRise above.
  double meetingSpread = 0.1;
  double meetingRise = 0.35;
  // Radians: how far its axis may tilt from where it points now towards the holder's base, the
  // inserter reaching its lower end from its own side.
  double meetingTilt = 1.6;
};

// The effects, registered beside the standard attachments of `attachments` (which must outlive
// this object): assemblePipeBearing(robot, pipe, robot', bearing), assembleBearingTree(robot,
// bearing, tree), assemblePipeTree(robot, pipe, tree). Each reads the geometric state's fluent
// and writes the state it leads to, as the standard effects do.
class AssemblyAttachments {
 public:
  explicit AssemblyAttachments(GeometricAttachments& attachments, AssemblyFits fits = {});

  // GeometricAttachments::registerProcedures calls it: the assembly effects are among its
  // procedureNames().
  void registerProcedures(symbolic::ProcedureRegistry& registry);

 private:
  using Arm = GeometricAttachments::Arm;
  bool assemblePipeBearing(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool assembleBearingTree(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool assemblePipeTree(const symbolic::AttachmentArgs& args, std::span<double> writes);
  // A pose of `base` (which `holder` holds) for a bimanual insertion by `inserter`: as held now,
  // turned about its axis at random and tilted up to AssemblyFits::meetingTilt towards the
  // holder, in the region of meetingSpread and meetingRise.
  Pose meetingPose(const GeometricState& state, const Arm& holder, const Arm& inserter,
                   std::size_t base, std::mt19937_64& rng) const;
  // The two insertions onto a part resting on a support: (robot, part, base).
  bool insertOntoResting(const char* name, const symbolic::AttachmentArgs& args,
                         const AssemblyFit& fit, std::span<double> writes);
  // One sample of an insertion by `inserter`, which holds `part`, into `base` at `basePose` (in
  // `state`; held by another robot or resting): a turn about the base's axis at random, IK of the
  // inserter at the start of the insertion, the Cartesian insertion along the base's axis, a
  // certified transfer path to its start, the inserter letting go and its Cartesian retreat back
  // along its tool's z axis. The part inserted (and what the inserter holds with it) goes to the
  // base's holder, or rests where it was put. Empty when it works, else why not.
  std::string tryInsertion(const GeometricState& state, const Arm& inserter, std::size_t part,
                           std::size_t base, const Pose& basePose, const AssemblyFit& fit,
                           std::mt19937_64& rng, std::vector<GeometricStep>& steps,
                           GeometricState& reached);

  GeometricAttachments* attachments_;
  AssemblyFits fits_;
};

}  // namespace kaboum::tamp
