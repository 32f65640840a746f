#include "kaboum/tamp/assembly_attachments.hpp"

#include <algorithm>
#include <numbers>

#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/motion/cartesian_motion.hpp"

namespace kaboum::tamp {

using symbolic::AttachmentArgs;

namespace {

// The index of `object` among what robot `robot` holds in `state`.
std::size_t heldIndex(const GeometricState& state, std::size_t robot, std::size_t object) {
  const std::vector<std::size_t>& held = state.robots[robot].heldObjects;
  return static_cast<std::size_t>(std::find(held.begin(), held.end(), object) - held.begin());
}

bool holds(const GeometricState& state, std::size_t robot, std::size_t object) {
  return heldIndex(state, robot, object) < state.robots[robot].heldObjects.size();
}

// `pose` moved `height` along its own z axis, turned upside down if `flipped`, and turned by
// `angle` about its z axis.
Pose alongAxis(const Pose& pose, double height, bool flipped, double angle) {
  return pose * Eigen::Translation3d(0, 0, height) *
         Eigen::AngleAxisd(flipped ? std::numbers::pi : 0.0, Vec3::UnitX()) *
         Eigen::AngleAxisd(angle, Vec3::UnitZ());
}

// The tool of scene robot `robot` on link `link` (a held object's link is its holder's tool link).
std::size_t toolOnLink(const World& world, std::size_t robot, int link) {
  const RobotModel& model = world.robots()[robot].collision.model();
  const auto& tools = world.description().robots[robot].tools;
  for (std::size_t t = 0; t < tools.size(); ++t) {
    if (model.findLink(tools[t].link) == link) return t;
  }
  return 0;
}

// The assembly of `base` at `basePose` in `state`: the base and every part on its axis within its
// height (a part assembled into it), resting or held, but for what robot `inserter` carries.
std::vector<std::size_t> assemblyOf(const World& world, const GeometricState& state,
                                    std::size_t base, const Pose& basePose, std::size_t inserter) {
  constexpr double kOnAxis = 1e-6;  // metres
  constexpr double kAssemblyHeight = 0.1;
  const CollisionScene& scene = world.scene();
  std::vector<std::size_t> parts;
  for (std::size_t object = 0; object < scene.size(); ++object) {
    if (!scene.movable(object) || holderOf(state, object) == inserter) continue;
    const Vec3 inBase = basePose.inverse() * objectPose(world, state, object).translation();
    if (object == base ||
        (inBase.head<2>().norm() < kOnAxis && inBase.z() >= 0 && inBase.z() <= kAssemblyHeight)) {
      parts.push_back(object);
    }
  }
  return parts;
}

// The pairs of a part in `moved` and one in `receiving` whose bounding pieces come within `margin`
// of each other somewhere along `path`, the configurations of robot `robot` from `state` on: the
// contacts the motion brings about (Join steps of robot `robot`).
std::vector<GeometricStep> contactsAlong(const World& world, const GeometricState& state,
                                         std::size_t robot, const motion::Waypoints& path,
                                         const std::vector<std::size_t>& moved,
                                         const std::vector<std::size_t>& receiving, double margin) {
  const CollisionScene& scene = world.scene();
  std::vector<GeometricStep> joins;
  GeometricState along = state;
  for (const std::vector<double>& q : path) {
    along.robots[robot].configuration = q;
    for (const std::size_t part : moved) {
      const Pose pose = objectPose(world, along, part);
      for (const std::size_t into : receiving) {
        const bool known = std::any_of(joins.begin(), joins.end(), [&](const GeometricStep& s) {
          return s.object == part && s.joinedTo == into;
        });
        if (!known && bodiesCollide(scene.body(part), pose, scene.body(into),
                                    objectPose(world, along, into), margin)) {
          joins.push_back({GeometricStep::Kind::Join, robot, 0, {}, part, Pose::Identity(), into});
        }
      }
    }
  }
  return joins;
}

// `state` without `objects`, resting or held.
GeometricState without(const World& world, const GeometricState& state,
                       const std::vector<std::size_t>& objects) {
  GeometricState rest = state;
  for (const std::size_t object : objects) {
    if (const std::optional<std::size_t> holder = holderOf(rest, object)) {
      RobotState& robot = rest.robots[*holder];
      const auto index = static_cast<std::ptrdiff_t>(heldIndex(rest, *holder, object));
      robot.held.erase(robot.held.begin() + index);
      robot.heldObjects.erase(robot.heldObjects.begin() + index);
    } else {
      rest.placements[world.scene().slot(object)].present = false;
    }
  }
  return rest;
}

}  // namespace

AssemblyAttachments::AssemblyAttachments(GeometricAttachments& attachments, AssemblyFits fits)
    : attachments_(&attachments), fits_(fits) {}

void AssemblyAttachments::registerProcedures(symbolic::ProcedureRegistry& registry) {
  const auto effect = [&](const char* name, bool (AssemblyAttachments::*procedure)(
                                                const AttachmentArgs&, std::span<double>)) {
    registry.addApplicator(name,
                           [this, procedure](const AttachmentArgs& args, std::span<double> writes) {
                             return (this->*procedure)(args, writes);
                           });
  };
  effect("assemblePipeBearing", &AssemblyAttachments::assemblePipeBearing);
  effect("assembleBearingTree", &AssemblyAttachments::assembleBearingTree);
  effect("assemblePipeTree", &AssemblyAttachments::assemblePipeTree);
}

std::string AssemblyAttachments::tryInsertion(const GeometricState& state, const Arm& inserter,
                                              std::size_t part, std::size_t base,
                                              const Pose& basePose, const AssemblyFit& fit,
                                              std::mt19937_64& rng,
                                              std::vector<GeometricStep>& steps,
                                              GeometricState& reached) {
  GeometricAttachments& geometry = *attachments_;
  const World& world = *geometry.world_;
  const RobotState& robot = state.robots[inserter.robot];
  motion::ToolKinematics& kinematics = geometry.tool(inserter);
  const Pose tcpInPart =
      robot.held[heldIndex(state, inserter.robot, part)].inLink.inverse() * kinematics.tcp();
  const double turn = 2 * std::numbers::pi * uniformUnit(rng);
  const Pose seated = alongAxis(basePose, fit.seatHeight, fit.flipped, turn);
  std::vector<double> start;
  if (std::string reason = geometry.freeSolution(
          state, inserter,
          alongAxis(basePose, fit.seatHeight + fit.approach, fit.flipped, turn) * tcpInPart,
          "at the start of the insertion", start);
      !reason.empty()) {
    return reason;
  }
  // The insertion and the retreat first: they fail more often and cost less than the transfer.
  const std::uint64_t transferSeed = rng();
  GeometricState atSeat = state;
  atSeat.robots[inserter.robot].configuration = start;
  // The contacts an assembly needs, between the parts moved and the parts they go into, allowed
  // and no other: each line is certified twice, once without either set of parts.
  const std::vector<std::size_t> carried = robot.heldObjects;
  const std::vector<std::size_t> receiving =
      assemblyOf(world, state, base, basePose, inserter.robot);
  const auto certified = [&](const GeometricState& context, const Pose& target,
                             motion::MotionResult& result) {
    result = geometry.line(without(world, context, carried), inserter, target);
    if (result.status != PlannerStatus::Solved) return false;
    result = geometry.line(without(world, context, receiving), inserter, target);
    return result.status == PlannerStatus::Solved;
  };
  motion::MotionResult insertion;
  if (!certified(atSeat, seated * tcpInPart, insertion)) {
    return "insertion: " + insertion.message;
  }
  // The contacts of the insertion, allowed from its start on. Its waypoints are at most a tool
  // step apart, so parts that touch between two of them come within half a step at one.
  std::vector<GeometricStep> joins =
      contactsAlong(world, atSeat, inserter.robot, insertion.path, carried, receiving,
                    world.description().settings.toolStep / 2);
  for (GeometricStep& join : joins) {
    join.tool = inserter.tool;
    atSeat.join(join.object, join.joinedTo);
  }
  atSeat.robots[inserter.robot].configuration = insertion.path.back();
  // What the inserter holds goes with the part: to the robot holding the base, on the base's
  // link, or resting where it is.
  std::vector<GeometricStep> events;
  const std::optional<std::size_t> baseHolder = holderOf(state, base);
  for (const std::size_t object : carried) {
    const Pose pose = objectPose(world, atSeat, object);
    world.release(atSeat, inserter.robot, object);
    if (baseHolder) {
      // A copy: hold() below appends to the vector it is in.
      const Attachment baseGrasp =
          atSeat.robots[*baseHolder].held[heldIndex(atSeat, *baseHolder, base)];
      const Pose inLink = baseGrasp.inLink * basePose.inverse() * pose;
      world.hold(atSeat, *baseHolder, baseGrasp.link, object, inLink);
      events.push_back({GeometricStep::Kind::Grasp,
                        *baseHolder,
                        toolOnLink(world, *baseHolder, baseGrasp.link),
                        {},
                        object,
                        inLink});
    }
    events.push_back(
        {GeometricStep::Kind::Release, inserter.robot, inserter.tool, {}, object, pose});
  }
  motion::MotionResult retreat;
  if (!certified(atSeat,
                 kinematics.tcpPose(insertion.path.back()) *
                     Eigen::Translation3d(0, 0, -geometry.options_.approachDistance),
                 retreat)) {
    return "retreat: " + retreat.message;
  }
  geometry.options_.motion.seed = transferSeed;
  motion::MotionResult transfer = geometry.plan(state, inserter, start);
  if (transfer.status != PlannerStatus::Solved) return "transfer: " + transfer.message;
  reached = std::move(atSeat);
  reached.robots[inserter.robot].configuration = retreat.path.back();
  steps.push_back({GeometricStep::Kind::Transfer, inserter.robot, inserter.tool,
                   std::move(transfer.path), 0, Pose::Identity()});
  steps.insert(steps.end(), joins.begin(), joins.end());
  steps.push_back({GeometricStep::Kind::Approach, inserter.robot, inserter.tool,
                   std::move(insertion.path), 0, Pose::Identity()});
  steps.insert(steps.end(), events.begin(), events.end());
  steps.push_back({GeometricStep::Kind::Retreat, inserter.robot, inserter.tool,
                   std::move(retreat.path), 0, Pose::Identity()});
  return {};
}

Pose AssemblyAttachments::meetingPose(const GeometricState& state, const Arm& holder,
                                      const Arm& inserter, std::size_t base,
                                      std::mt19937_64& rng) const {
  GeometricAttachments& geometry = *attachments_;
  const Pose now = objectPose(*geometry.world_, state, base);
  Vec3 towardHolder =
      geometry.tool(holder).chainBase(state.robots[holder.robot].configuration).translation() -
      geometry.tool(inserter).chainBase(state.robots[inserter.robot].configuration).translation();
  towardHolder.z() = 0;
  const Vec3 tiltAxis = Vec3::UnitZ().cross(towardHolder).normalized();
  const auto spread = [&] { return fits_.meetingSpread * (2 * uniformUnit(rng) - 1); };
  Pose pose = Pose::Identity();
  pose.linear() = Eigen::AngleAxisd(fits_.meetingTilt * uniformUnit(rng), tiltAxis) *
                  Eigen::AngleAxisd(2 * std::numbers::pi * uniformUnit(rng), Vec3::UnitZ()) *
                  now.linear();
  pose.translation() =
      now.translation() + Vec3(spread(), spread(), fits_.meetingRise * uniformUnit(rng));
  return pose;
}

// assemblePipeBearing(robot, pipe, robot', bearing): robot holds the pipe, robot' the bearing
// from the inside (Figure 6.8c). A pose of the pipe near where it is held (meetingPose), the
// holder's IK there with its grasp, then the insertion of the bearing into the pipe's upper seat
// (tryInsertion) and the holder's certified transfer path there. The bearing stays in the pipe,
// held with it.
bool AssemblyAttachments::assemblePipeBearing(const AttachmentArgs& args,
                                              std::span<double> writes) {
  GeometricAttachments& geometry = *attachments_;
  ++geometry.statistics_.calls;
  const char* name = "assemblePipeBearing";
  const GeometricState& state = geometry.stateOf(args, name);
  const std::optional<Arm> holder = geometry.arm(args, 0);
  const std::optional<std::size_t> pipe = geometry.object(args, 1);
  const std::optional<Arm> inserter = geometry.arm(args, 2);
  const std::optional<std::size_t> bearing = geometry.object(args, 3);
  if (!holder || !inserter) return geometry.fail(name, args, kNotAnArm);
  if (!pipe || !bearing) return geometry.fail(name, args, kNotAMovableObject);
  if (holder->robot == inserter->robot) {
    return geometry.fail(name, args, "the two arms are one robot");
  }
  if (!holds(state, holder->robot, *pipe) || !holds(state, inserter->robot, *bearing)) {
    return geometry.fail(name, args, "each arm must hold its part");
  }
  return geometry.firstSample(
      name, args, state, geometry.options_.handoverSamples, writes,
      [&](std::mt19937_64& rng, std::vector<GeometricStep>& steps, GeometricState& reached) {
        const RobotState& holding = state.robots[holder->robot];
        motion::ToolKinematics& kinematics = geometry.tool(*holder);
        const Pose tcpInPipe =
            holding.held[heldIndex(state, holder->robot, *pipe)].inLink.inverse() *
            kinematics.tcp();
        const Pose meeting = meetingPose(state, *holder, *inserter, *pipe, rng);
        std::vector<double> holderAtMeeting;
        if (std::string reason =
                geometry.freeSolution(state, *holder, meeting * tcpInPipe,
                                      "at the holder's meeting pose", holderAtMeeting);
            !reason.empty()) {
          return reason;
        }
        GeometricState atMeeting = state;
        atMeeting.robots[holder->robot].configuration = holderAtMeeting;
        std::vector<GeometricStep> insertion;
        if (std::string reason = tryInsertion(atMeeting, *inserter, *bearing, *pipe, meeting,
                                              fits_.bearingInPipe, rng, insertion, reached);
            !reason.empty()) {
          return reason;
        }
        geometry.options_.motion.seed = rng();
        motion::MotionResult transfer = geometry.plan(state, *holder, holderAtMeeting);
        if (transfer.status != PlannerStatus::Solved) {
          return "holder's transfer: " + transfer.message;
        }
        steps.push_back({GeometricStep::Kind::Transfer, holder->robot, holder->tool,
                         std::move(transfer.path), 0, Pose::Identity()});
        steps.insert(steps.end(), std::make_move_iterator(insertion.begin()),
                     std::make_move_iterator(insertion.end()));
        return std::string();
      });
}

// An insertion by `robot`, which holds `part`, onto `base` resting on a support: up to
// placementSamples turns about the base's axis (tryInsertion).
bool AssemblyAttachments::insertOntoResting(const char* name, const AttachmentArgs& args,
                                            const AssemblyFit& fit, std::span<double> writes) {
  GeometricAttachments& geometry = *attachments_;
  ++geometry.statistics_.calls;
  const GeometricState& state = geometry.stateOf(args, name);
  const std::optional<Arm> inserter = geometry.arm(args, 0);
  const std::optional<std::size_t> part = geometry.object(args, 1);
  const std::optional<std::size_t> base = geometry.object(args, 2);
  if (!inserter) return geometry.fail(name, args, kNotAnArm);
  if (!part || !base) return geometry.fail(name, args, kNotAMovableObject);
  if (!holds(state, inserter->robot, *part)) {
    return geometry.fail(name, args, "the robot does not hold the part");
  }
  const Placement& resting = state.placements[geometry.world_->scene().slot(*base)];
  if (!resting.present) return geometry.fail(name, args, "the base part is held");
  return geometry.firstSample(
      name, args, state, geometry.options_.placementSamples, writes,
      [&](std::mt19937_64& rng, std::vector<GeometricStep>& steps, GeometricState& reached) {
        return tryInsertion(state, *inserter, *part, *base, resting.pose, fit, rng, steps, reached);
      });
}

// assembleBearingTree(robot, bearing, tree): the bearing, held from outside, slid down the
// standing tree's shaft onto its shoulder (Figure 6.8e).
bool AssemblyAttachments::assembleBearingTree(const AttachmentArgs& args,
                                              std::span<double> writes) {
  return insertOntoResting("assembleBearingTree", args, fits_.bearingOnTree, writes);
}

// assemblePipeTree(robot, pipe, tree): the pipe (with the bearing in it) lowered over the standing
// tree (with its bearing) and let go: the gearbox (Figure 6.8f).
bool AssemblyAttachments::assemblePipeTree(const AttachmentArgs& args, std::span<double> writes) {
  return insertOntoResting("assemblePipeTree", args, fits_.pipeOnTree, writes);
}

}  // namespace kaboum::tamp
