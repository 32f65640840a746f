// The standard geometric attachments of the integrated planner (thesis §6.1.2, "Robotics
// components at planning time"; seed 004 §II): procedures a domain names in its `:modules`, each
// the geometric precondition and effect of a symbolic action on the geometric state whose
// identifier (the symbolic–geometric map, Definition 5) the planner holds in a numeric fluent.
// An effect returns the identifier of the state it leads to and records the certified motions
// that get there; it fails (the action is inapplicable) when no sample of it works. Reference:
// docs/tamp.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/motion/tool_kinematics.hpp"
#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/tamp/grasp_sampler.hpp"
#include "kaboum/tamp/state_map.hpp"
#include "kaboum/world/placement.hpp"

namespace kaboum::tamp {

class AssemblyAttachments;

struct TampOptions {
  // Every motion query (transit, transfer, approach, retreat): planner, time limit, seed.
  motion::MotionOptions motion;
  int graspSamples = 16;      // grasps tried per pickUp call
  int placementSamples = 16;  // placements tried per putDown call
  // How freeSpaceFound samples a location's footprint for putDown and the freeSpaceFound checker
  // (seeded per call with the call's generator); the samples it may try per placement.
  SearchStrategy placementStrategy = SearchStrategy::Random;
  std::size_t placementCandidates = 200;
  int moveSamples = 8;  // random configurations tried per move call
  // Metres: the pre-grasp pose is this far back along the tool's z axis (its approach axis) from
  // the grasp, and the hand backs off as far after a release.
  double approachDistance = 0.05;
  // Metres: an object is lifted this far (world z) after a grasp, and lowered as far to a
  // placement.
  double liftHeight = 0.05;
  int handoverSamples = 16;  // object poses tried per handover call
  // Metres: where handover holds the object — horizontally within handoverSpread of the midpoint
  // of the two arms' bases, from the object's height when the call starts up to handoverRise
  // above it.
  double handoverSpread = 0.1;
  double handoverRise = 0.1;
  std::uint64_t seed = 1;  // with each call's state and arguments, seeds its sampling
};

// One step of an action's geometry, in execution order: a certified joint-space motion of one
// robot (waypoints of its whole configuration), or a gripper event. A Grasp of an object another
// robot holds takes it from that robot, whose Release right after it (a handover) leaves the
// object with the new holder.
struct GeometricStep {
  // Join: `robot` assembles `object` into `joinedTo` — from this step on the two are joined
  // (GeometricState::joined): they may touch, and no check tests one against the other.
  enum class Kind { Transit, Transfer, Approach, Retreat, Grasp, Release, Join };
  Kind kind = Kind::Transit;
  std::size_t robot = 0;
  std::size_t tool = 0;
  motion::Waypoints path;  // motions only
  std::size_t object = 0;  // Grasp, Release, Join: the scene object
  // Grasp: the object frame in the tool link frame; Release: the object's pose in the world.
  Pose pose = Pose::Identity();
  std::size_t joinedTo = 0;  // Join: the scene object `object` is joined to
};

const char* toString(GeometricStep::Kind kind);

// Why an attachment call fails when an argument names no arm or no movable object (the standard
// and the scenario attachments alike).
inline constexpr std::string_view kNotAnArm = "not a robot with a tool nor a tool of the scene";
inline constexpr std::string_view kNotAMovableObject = "not a movable object of the scene";

// The robot holding scene object `object` in `state`, if one does.
std::optional<std::size_t> holderOf(const GeometricState& state, std::size_t object);
// Where scene object `object` is in `state`: its placement, or where the robot holding it holds
// it.
Pose objectPose(const World& world, const GeometricState& state, std::size_t object);

// The geometry of one effect: from geometric state `from` to `to` (identifiers of the map).
struct ActionGeometry {
  std::string procedure;
  std::vector<std::string> arguments;
  std::size_t from = 0;
  std::size_t to = 0;
  std::vector<GeometricStep> steps;
};

// Where the geometric time went (Table 6.7's rows).
struct GeometricStatistics {
  std::size_t calls = 0;  // procedure calls (the attachment memo answers repeats)
  std::size_t failures = 0;
  std::size_t ikCalls = 0;  // grasp and pose IK samples
  double ikSeconds = 0;
  std::size_t motionQueries = 0;  // planMotion and planCartesian queries
  double motionSeconds = 0;       // in those queries, their checks included
  motion::CheckStatistics checks;
  // The latest failed calls (at most kRecentFailures, oldest first) and why each one's last sample
  // failed: "pickUp(kr5, block): approach: …".
  static constexpr std::size_t kRecentFailures = 8;
  std::vector<std::string> recentFailures;
};

class GeometricAttachments {
 public:
  // The effects and checkers act on `world`, which must outlive this object. The map starts with
  // the world's initial state as identifier 0.
  GeometricAttachments(const World& world, TampOptions options = {});
  ~GeometricAttachments();
  GeometricAttachments(const GeometricAttachments&) = delete;
  GeometricAttachments& operator=(const GeometricAttachments&) = delete;

  // Registers every procedure under its name (procedureNames()).
  void registerProcedures(symbolic::ProcedureRegistry& registry);
  // Effects: move(robot), moveHome(robot), pickUp(robot, object), putDown(robot, object,
  // location), handover(robot, object, robot), and the Bimanual Assembly scenario's
  // assemblePipeBearing, assembleBearingTree, assemblePipeTree (AssemblyAttachments); checkers:
  // isColliding(), isReachable(robot, object), isInside(object, location),
  // isOnSupportSurface(object), freeSpaceFound(object, location). A robot argument names a scene
  // robot (its first tool) or a tool.
  static const std::vector<std::string>& procedureNames();
  // Whether procedure `name` is an effect that writes a geometric state identifier.
  static bool isGeometricEffect(const std::string& name);
  // The number of arguments procedure `name` takes.
  static std::size_t arity(const std::string& name);
  // Whether `name` names a robot, tool, object or location of the scene. An argument of the wrong
  // kind (a robot where an object is expected, as PDDL's root type `object` allows) makes the call
  // fail, with the reason in statistics().recentFailures.
  [[nodiscard]] bool namesSceneEntity(const std::string& name) const;

  [[nodiscard]] const World& world() const { return *world_; }
  [[nodiscard]] const GeometricStateMap& map() const { return map_; }
  // The identifier of `state`, added to the map if new: how the condition checkers see a state
  // they did not make (a plan file's, replayed).
  std::size_t intern(const GeometricState& state) { return map_.intern(state); }
  [[nodiscard]] const TampOptions& options() const { return options_; }
  // The recorded geometry of an effect from state `from` to state `to`, if one was applied.
  [[nodiscard]] const ActionGeometry* transition(std::size_t from, std::size_t to) const;
  // Records the geometry of an effect computed elsewhere (the Python API's, docs/python.md), from
  // state geometry.from to `reached`, as the effects here record theirs; returns the identifier
  // of `reached`.
  std::size_t record(ActionGeometry geometry, const GeometricState& reached);
  [[nodiscard]] const GeometricStatistics& statistics() const { return statistics_; }

 private:
  // The scenario-specific effects are built from the utilities below.
  friend class AssemblyAttachments;

  struct Arm {
    std::size_t robot = 0;
    std::size_t tool = 0;
    std::vector<int> fingers;  // the variables of its hand's finger joints, still while it moves
  };
  // The joint space of `arm`'s robot over `context`, its fingers held still.
  [[nodiscard]] motion::MotionGroup armGroup(const GeometricState& context, const Arm& arm) const;

  bool move(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool moveHome(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool pickUp(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool putDown(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool handover(const symbolic::AttachmentArgs& args, std::span<double> writes);
  bool isInside(const symbolic::AttachmentArgs& args);
  bool isOnSupportSurface(const symbolic::AttachmentArgs& args);
  bool freeSpaceFound(const symbolic::AttachmentArgs& args);
  bool isReachable(const symbolic::AttachmentArgs& args);
  bool isColliding(const symbolic::AttachmentArgs& args);

  // The geometric state of the call's first read value; throws InputError for a value that is no
  // identifier.
  const GeometricState& stateOf(const symbolic::AttachmentArgs& args,
                                const std::string& procedure) const;
  // The arguments as scene entities of the kinds the procedures take, nullopt for another kind.
  [[nodiscard]] std::optional<Arm> arm(const symbolic::AttachmentArgs& args,
                                       std::size_t index) const;
  [[nodiscard]] std::optional<std::size_t> object(const symbolic::AttachmentArgs& args,
                                                  std::size_t index) const;
  [[nodiscard]] std::optional<std::size_t> location(const symbolic::AttachmentArgs& args,
                                                    std::size_t index) const;
  motion::ToolKinematics& tool(const Arm& arm);
  // The call's generator: the options' seed, the procedure, its arguments, read values and sample.
  std::mt19937_64 generator(const std::string& procedure,
                            const symbolic::AttachmentArgs& args) const;
  motion::MotionResult plan(const GeometricState& context, const Arm& arm,
                            std::span<const double> goal);
  motion::MotionResult line(const GeometricState& context, const Arm& arm, const Pose& target);
  // Adds one motion query's counts and times to the statistics.
  void record(const motion::MotionResult& result);
  // The link a tool is on.
  [[nodiscard]] int toolLink(const Arm& arm) const;
  // The first IK solution of the arm with its tool centre point at `tcpPose` (nearest its
  // configuration in `state` first) at which it collides with nothing in `state`, counted in the
  // statistics: on success an empty string and `solution`, else "no IK solution <where>" or
  // "<where>: <the first solution's collision>".
  std::string freeSolution(const GeometricState& state, const Arm& arm, const Pose& tcpPose,
                           std::string_view where, std::vector<double>& solution);
  // A grasp the arm can approach: its configuration at the pre-grasp and the tool pose at the
  // grasp.
  struct ApproachableGrasp {
    std::vector<double> preGrasp;
    Pose tcpAtGrasp = Pose::Identity();
  };
  // One grasp sample (GraspSampler) of `object` at `objectPose` whose pre-grasp has an IK solution
  // on the grasp's branch at which the arm collides with nothing in `state`: on success an empty
  // string and `found`, else why not.
  std::string approachableGrasp(const GeometricState& state, const Arm& arm, std::size_t object,
                                const Pose& objectPose, std::mt19937_64& rng,
                                ApproachableGrasp& found);
  // The Cartesian approach of the arm from its configuration in `state` to `tcpAtGrasp`: on
  // success an empty string, the path, `state` with the arm at the grasp, and where the object at
  // `objectPose` is in the tool link frame there; else why not.
  std::string approachGrasp(GeometricState& state, const Arm& arm, const Pose& tcpAtGrasp,
                            const Pose& objectPose, motion::Waypoints& approach,
                            Pose& objectInLink);
  // One grasp sample of pickUp: on success an empty string, the steps, and the state reached.
  std::string tryGrasp(const GeometricState& state, const Arm& arm, std::size_t object,
                       std::mt19937_64& rng, std::vector<GeometricStep>& steps,
                       GeometricState& reached);
  // One placement sample of putDown for the object `held` holds as `index`-th held object.
  std::string tryPlacement(const GeometricState& state, const Arm& arm, std::size_t object,
                           std::size_t location, std::mt19937_64& rng,
                           std::vector<GeometricStep>& steps, GeometricState& reached);
  [[nodiscard]] FreeSpaceOptions placementOptions(std::mt19937_64& rng) const;
  // A pose of `object` for a handover between `giver` (holding it) and `receiver`: its
  // orientation in `state` turned about the vertical at random, at a random point of the region of
  // TampOptions::handoverSpread and handoverRise.
  Pose handoverPose(const GeometricState& state, const Arm& giver, const Arm& receiver,
                    std::size_t object, std::mt19937_64& rng);
  // One object pose of handover: on success an empty string, the steps, and the state reached.
  std::string tryHandover(const GeometricState& state, const Arm& giver, std::size_t object,
                          const Arm& receiver, std::mt19937_64& rng,
                          std::vector<GeometricStep>& steps, GeometricState& reached);
  [[nodiscard]] std::vector<std::size_t> facesForGrasp(std::size_t object,
                                                       const Pose& tcpInObject) const;
  // One sample of an effect: on success an empty string, the steps, and the state reached.
  using SampleAttempt = std::function<std::string(
      std::mt19937_64& rng, std::vector<GeometricStep>& steps, GeometricState& reached)>;
  // Up to `samples` attempts with the call's generator; the first that works is recorded (finish),
  // else the last reason is the failure.
  bool firstSample(const std::string& procedure, const symbolic::AttachmentArgs& args,
                   const GeometricState& state, int samples, std::span<double> writes,
                   const SampleAttempt& attempt);
  // Records the geometry and writes the new state's identifier.
  bool finish(ActionGeometry geometry, const GeometricState& reached, std::span<double> writes);
  // Counts a failed call of `procedure` and keeps `reason` as the last failure.
  bool fail(const std::string& procedure, const symbolic::AttachmentArgs& args,
            std::string_view reason);

  const World* world_;
  TampOptions options_;
  GeometricStateMap map_;
  PlacementGeometry placements_;
  QueryScratch scratch_;
  std::map<std::pair<std::size_t, std::size_t>, ActionGeometry> transitions_;
  std::map<std::pair<std::size_t, std::size_t>, std::unique_ptr<motion::ToolKinematics>> tools_;
  std::unordered_map<std::string, Arm> arms_;  // lower-case robot and tool names
  GeometricStatistics statistics_;
  std::unique_ptr<AssemblyAttachments> assembly_;
};

}  // namespace kaboum::tamp
