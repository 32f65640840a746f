#include "kaboum/tamp/geometric_attachments.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/motion/cartesian_motion.hpp"
#include "kaboum/tamp/assembly_attachments.hpp"

namespace kaboum::tamp {

using symbolic::AttachmentArgs;

namespace {

class Stopwatch {
 public:
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
  }

 private:
  std::chrono::steady_clock::time_point begin_ = std::chrono::steady_clock::now();
};

void mix(std::uint64_t& seed, std::uint64_t value) {
  seed ^= value + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
}

Pose translated(const Vec3& offset, const Pose& pose) {
  Pose moved = pose;
  moved.translation() += offset;
  return moved;
}

}  // namespace

const char* toString(GeometricStep::Kind kind) {
  switch (kind) {
    case GeometricStep::Kind::Transit:
      return "transit";
    case GeometricStep::Kind::Transfer:
      return "transfer";
    case GeometricStep::Kind::Approach:
      return "approach";
    case GeometricStep::Kind::Retreat:
      return "retreat";
    case GeometricStep::Kind::Grasp:
      return "grasp";
    case GeometricStep::Kind::Release:
      return "release";
    case GeometricStep::Kind::Join:
      return "join";
  }
  return "?";
}

std::optional<std::size_t> holderOf(const GeometricState& state, std::size_t object) {
  for (std::size_t r = 0; r < state.robots.size(); ++r) {
    const std::vector<std::size_t>& held = state.robots[r].heldObjects;
    if (std::find(held.begin(), held.end(), object) != held.end()) return r;
  }
  return std::nullopt;
}

Pose objectPose(const World& world, const GeometricState& state, std::size_t object) {
  const std::optional<std::size_t> holder = holderOf(state, object);
  if (!holder) return world.scene().pose(object, state.placements);
  const RobotState& robot = state.robots[*holder];
  const std::size_t index = static_cast<std::size_t>(
      std::find(robot.heldObjects.begin(), robot.heldObjects.end(), object) -
      robot.heldObjects.begin());
  const RobotCollisionModel& model = world.robots()[*holder].collision;
  std::vector<Pose> links(model.model().links().size());
  model.model().linkPoses(robot.configuration, links);
  const Attachment& attachment = robot.held[index];
  return model.basePose() * links[static_cast<std::size_t>(attachment.link)] * attachment.inLink;
}

GeometricAttachments::GeometricAttachments(const World& world, TampOptions options)
    : world_(&world),
      options_(std::move(options)),
      placements_(world),
      scratch_(world.scratch()),
      assembly_(std::make_unique<AssemblyAttachments>(*this)) {
  map_.intern(world.initialState());
  const SceneDescription& scene = world.description();
  for (std::size_t r = 0; r < scene.robots.size(); ++r) {
    const RobotModel& model = world.robots()[r].collision.model();
    const std::vector<ToolSpec>& tools = scene.robots[r].tools;
    for (std::size_t t = 0; t < tools.size(); ++t) {
      Arm arm{r, t, {}};
      if (tools[t].hand && tools[t].hand->fingers) {
        for (const Joint& joint : model.joints()) {
          if (joint.variable >= 0 && tools[t].hand->fingers->open.contains(joint.name)) {
            arm.fingers.push_back(joint.variable);
          }
        }
      }
      if (t == 0) arms_[lowerCase(scene.robots[r].name)] = arm;
      arms_.try_emplace(lowerCase(tools[t].name), std::move(arm));
    }
  }
}

motion::MotionGroup GeometricAttachments::armGroup(const GeometricState& context,
                                                   const Arm& arm) const {
  motion::MotionGroup group(*world_, context, {arm.robot});
  for (const int finger : arm.fingers) group.holdStill(0, finger);
  return group;
}

GeometricAttachments::~GeometricAttachments() = default;

namespace {

constexpr std::string_view kNotALocation = "not a location of the scene";
// Parts joined by an assembly move only with the assembly actions.
constexpr std::string_view kJoined = "the object is assembled with another part";
constexpr std::string_view kNoFreePlacement = "no free placement in the location";

// Each procedure: its name, its number of arguments (robots, objects, locations by name), and
// whether it is an effect (else a condition checker).
struct Signature {
  std::string name;
  std::size_t arity = 0;
  bool effect = false;
};

const std::vector<Signature>& signatures() {
  static const std::vector<Signature> table{{"move", 1, true},
                                            {"moveHome", 1, true},
                                            {"pickUp", 2, true},
                                            {"putDown", 3, true},
                                            {"handover", 3, true},
                                            {"isColliding", 0, false},
                                            {"isReachable", 2, false},
                                            {"isInside", 2, false},
                                            {"isOnSupportSurface", 1, false},
                                            {"freeSpaceFound", 2, false},
                                            {"assemblePipeBearing", 4, true},
                                            {"assembleBearingTree", 3, true},
                                            {"assemblePipeTree", 3, true}};
  return table;
}

}  // namespace

const std::vector<std::string>& GeometricAttachments::procedureNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const Signature& signature : signatures()) list.push_back(signature.name);
    return list;
  }();
  return names;
}

bool GeometricAttachments::isGeometricEffect(const std::string& name) {
  return std::any_of(signatures().begin(), signatures().end(),
                     [&](const Signature& s) { return s.effect && s.name == name; });
}

std::size_t GeometricAttachments::arity(const std::string& name) {
  for (const Signature& signature : signatures()) {
    if (signature.name == name) return signature.arity;
  }
  throw std::invalid_argument("no geometric attachment '" + name + "'");
}

bool GeometricAttachments::namesSceneEntity(const std::string& name) const {
  return arms_.contains(lowerCase(name)) || world_->find(name).has_value();
}

void GeometricAttachments::registerProcedures(symbolic::ProcedureRegistry& registry) {
  const auto effect = [&](const char* name, bool (GeometricAttachments::*procedure)(
                                                const AttachmentArgs&, std::span<double>)) {
    registry.addApplicator(name,
                           [this, procedure](const AttachmentArgs& args, std::span<double> writes) {
                             return (this->*procedure)(args, writes);
                           });
  };
  const auto checker = [&](const char* name,
                           bool (GeometricAttachments::*procedure)(const AttachmentArgs&)) {
    registry.addChecker(
        name, [this, procedure](const AttachmentArgs& args) { return (this->*procedure)(args); });
  };
  effect("move", &GeometricAttachments::move);
  effect("moveHome", &GeometricAttachments::moveHome);
  effect("pickUp", &GeometricAttachments::pickUp);
  effect("putDown", &GeometricAttachments::putDown);
  effect("handover", &GeometricAttachments::handover);
  checker("isColliding", &GeometricAttachments::isColliding);
  checker("isReachable", &GeometricAttachments::isReachable);
  checker("isInside", &GeometricAttachments::isInside);
  checker("isOnSupportSurface", &GeometricAttachments::isOnSupportSurface);
  checker("freeSpaceFound", &GeometricAttachments::freeSpaceFound);
  assembly_->registerProcedures(registry);
}

const ActionGeometry* GeometricAttachments::transition(std::size_t from, std::size_t to) const {
  const auto it = transitions_.find({from, to});
  return it == transitions_.end() ? nullptr : &it->second;
}

const GeometricState& GeometricAttachments::stateOf(const AttachmentArgs& args,
                                                    const std::string& procedure) const {
  const double id = args.reads.empty() ? -1 : args.reads[0];
  if (!(id >= 0) || id != std::floor(id) || id >= static_cast<double>(map_.size())) {
    throw InputError("attachment '" + procedure +
                     "' must read the geometric state's fluent first (:reads ((geometry) …)), "
                     "but read " +
                     (args.reads.empty() ? std::string("nothing") : std::to_string(id)));
  }
  return map_.state(static_cast<std::size_t>(id));
}

std::optional<GeometricAttachments::Arm> GeometricAttachments::arm(const AttachmentArgs& args,
                                                                   std::size_t index) const {
  const auto it = arms_.find(lowerCase(std::string(args.name(index))));
  if (it == arms_.end()) return std::nullopt;
  return it->second;
}

std::optional<std::size_t> GeometricAttachments::object(const AttachmentArgs& args,
                                                        std::size_t index) const {
  const std::optional<NamedEntity> entity = world_->find(std::string(args.name(index)));
  if (!entity || entity->kind != NamedEntity::Kind::Object ||
      !world_->scene().movable(entity->index)) {
    return std::nullopt;
  }
  return entity->index;
}

std::optional<std::size_t> GeometricAttachments::location(const AttachmentArgs& args,
                                                          std::size_t index) const {
  const std::optional<NamedEntity> entity = world_->find(std::string(args.name(index)));
  if (!entity || entity->kind != NamedEntity::Kind::Location) return std::nullopt;
  return entity->index;
}

motion::ToolKinematics& GeometricAttachments::tool(const Arm& arm) {
  auto& slot = tools_[{arm.robot, arm.tool}];
  if (!slot) {
    slot = std::make_unique<motion::ToolKinematics>(*world_, arm.robot, arm.tool, options_.seed);
  }
  return *slot;
}

std::mt19937_64 GeometricAttachments::generator(const std::string& procedure,
                                                const AttachmentArgs& args) const {
  std::uint64_t seed = options_.seed;
  mix(seed, std::hash<std::string>{}(procedure));
  for (const auto object : args.objects) mix(seed, static_cast<std::uint64_t>(object));
  for (const double value : args.reads) mix(seed, std::hash<double>{}(value));
  if (args.sample != 0) mix(seed, args.sample);  // sample 0 draws as a single sample does
  return std::mt19937_64(seed);
}

motion::MotionResult GeometricAttachments::plan(const GeometricState& context, const Arm& arm,
                                                std::span<const double> goal) {
  const motion::MotionGroup group = armGroup(context, arm);
  motion::MotionResult result =
      motion::planMotion(group, context.robots[arm.robot].configuration, goal, options_.motion);
  record(result);
  return result;
}

motion::MotionResult GeometricAttachments::line(const GeometricState& context, const Arm& arm,
                                                const Pose& target) {
  const motion::MotionGroup group = armGroup(context, arm);
  motion::MotionResult result = motion::planCartesian(
      group, tool(arm), context.robots[arm.robot].configuration, target, options_.motion);
  record(result);
  return result;
}

void GeometricAttachments::record(const motion::MotionResult& result) {
  const motion::MotionStatistics& query = result.statistics;
  ++statistics_.motionQueries;
  statistics_.motionSeconds += query.totalSeconds;
  statistics_.checks += query.checks;
}

std::size_t GeometricAttachments::record(ActionGeometry geometry, const GeometricState& reached) {
  geometry.to = map_.intern(reached);
  const std::size_t to = geometry.to;
  transitions_.try_emplace({geometry.from, to}, std::move(geometry));
  return to;
}

bool GeometricAttachments::finish(ActionGeometry geometry, const GeometricState& reached,
                                  std::span<double> writes) {
  writes[0] = static_cast<double>(record(std::move(geometry), reached));
  return true;
}

bool GeometricAttachments::fail(const std::string& procedure, const AttachmentArgs& args,
                                std::string_view reason) {
  ++statistics_.failures;
  std::string call = procedure + "(";
  for (std::size_t i = 0; i < args.objects.size(); ++i) {
    call += (i ? ", " : "") + std::string(args.name(i));
  }
  std::vector<std::string>& recent = statistics_.recentFailures;
  if (recent.size() == GeometricStatistics::kRecentFailures) recent.erase(recent.begin());
  recent.push_back(call + "): " + std::string(reason));
  return false;
}

// move(robot): a random configuration of its joints (its fingers as they are) within the joint
// limits, reached by a certified path.
bool GeometricAttachments::move(const AttachmentArgs& args, std::span<double> writes) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "move");
  const std::optional<Arm> found = arm(args, 0);
  if (!found) return fail("move", args, kNotAnArm);
  const Arm moving = *found;
  std::mt19937_64 rng = generator("move", args);
  const RobotModel& model = world_->robots()[moving.robot].collision.model();
  const bool holding = !state.robots[moving.robot].heldObjects.empty();
  std::string reason = "no samples";
  for (int sample = 0; sample < options_.moveSamples; ++sample) {
    std::vector<double> goal = randomConfiguration(model, rng);
    for (const int finger : moving.fingers) {  // a move leaves the hand as it is
      goal[static_cast<std::size_t>(finger)] =
          state.robots[moving.robot].configuration[static_cast<std::size_t>(finger)];
    }
    options_.motion.seed = rng();
    motion::MotionResult path = plan(state, moving, goal);
    if (path.status != PlannerStatus::Solved) {
      reason = "path: " + path.message;
      continue;
    }
    GeometricState reached = state;
    reached.robots[moving.robot].configuration = path.path.back();
    ActionGeometry geometry{"move", {std::string(args.name(0))}, *map_.find(state), 0, {}};
    geometry.steps.push_back(
        {holding ? GeometricStep::Kind::Transfer : GeometricStep::Kind::Transit, moving.robot,
         moving.tool, std::move(path.path), 0, Pose::Identity()});
    return finish(std::move(geometry), reached, writes);
  }
  return fail("move", args, reason);
}

// moveHome(robot): a certified path to the robot's home configuration (the scene file's), where
// it is out of the other robots' way; fails when it is there already.
bool GeometricAttachments::moveHome(const AttachmentArgs& args, std::span<double> writes) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "moveHome");
  const std::optional<Arm> found = arm(args, 0);
  if (!found) return fail("moveHome", args, kNotAnArm);
  const std::vector<double>& home = world_->robots()[found->robot].home;
  if (state.robots[found->robot].configuration == home) {
    return fail("moveHome", args, "the robot is at home");
  }
  std::mt19937_64 rng = generator("moveHome", args);
  options_.motion.seed = rng();
  motion::MotionResult path = plan(state, *found, home);
  if (path.status != PlannerStatus::Solved) return fail("moveHome", args, "path: " + path.message);
  GeometricState reached = state;
  reached.robots[found->robot].configuration = home;
  ActionGeometry geometry{"moveHome", {std::string(args.name(0))}, *map_.find(state), 0, {}};
  const bool holding = !state.robots[found->robot].heldObjects.empty();
  geometry.steps.push_back({holding ? GeometricStep::Kind::Transfer : GeometricStep::Kind::Transit,
                            found->robot, found->tool, std::move(path.path), 0, Pose::Identity()});
  return finish(std::move(geometry), reached, writes);
}

bool GeometricAttachments::firstSample(const std::string& procedure, const AttachmentArgs& args,
                                       const GeometricState& state, int samples,
                                       std::span<double> writes, const SampleAttempt& attempt) {
  std::mt19937_64 rng = generator(procedure, args);
  std::string reason = "no samples";
  for (int sample = 0; sample < samples; ++sample) {
    ActionGeometry geometry{procedure, {}, *map_.find(state), 0, {}};
    for (std::size_t i = 0; i < args.objects.size(); ++i) {
      geometry.arguments.emplace_back(args.name(i));
    }
    GeometricState reached;
    reason = attempt(rng, geometry.steps, reached);
    if (reason.empty()) return finish(std::move(geometry), reached, writes);
  }
  return fail(procedure, args, reason);
}

namespace {

// The four steps of a pick or a place: the motion there, the approach, the gripper event, the
// retreat.
void appendManipulation(std::vector<GeometricStep>& steps, std::size_t robot, std::size_t tool,
                        GeometricStep::Kind motionKind, motion::Waypoints motion,
                        motion::Waypoints approach, GeometricStep::Kind event, std::size_t object,
                        const Pose& pose, motion::Waypoints retreat) {
  steps.push_back({motionKind, robot, tool, std::move(motion), 0, Pose::Identity()});
  steps.push_back(
      {GeometricStep::Kind::Approach, robot, tool, std::move(approach), 0, Pose::Identity()});
  steps.push_back({event, robot, tool, {}, object, pose});
  steps.push_back(
      {GeometricStep::Kind::Retreat, robot, tool, std::move(retreat), 0, Pose::Identity()});
}

}  // namespace

int GeometricAttachments::toolLink(const Arm& arm) const {
  return world_->robots()[arm.robot]
      .collision.model()
      .findLink(world_->description().robots[arm.robot].tools[arm.tool].link)
      .value();
}

std::string GeometricAttachments::freeSolution(const GeometricState& state, const Arm& arm,
                                               const Pose& tcpPose, std::string_view where,
                                               std::vector<double>& solution) {
  const Stopwatch ik;
  const std::vector<std::vector<double>> solutions =
      tool(arm).solutions(tcpPose, state.robots[arm.robot].configuration);
  ++statistics_.ikCalls;
  statistics_.ikSeconds += ik.seconds();
  if (solutions.empty()) return "no IK solution " + std::string(where);
  const motion::MotionGroup group(*world_, state, {arm.robot});
  const auto free = std::find_if(solutions.begin(), solutions.end(), [&](const auto& q) {
    return !motion::configurationProblem(group, q, 0);
  });
  if (free == solutions.end()) {
    return std::string(where) + ": " + *motion::configurationProblem(group, solutions.front(), 0);
  }
  solution = *free;
  return {};
}

std::string GeometricAttachments::approachableGrasp(const GeometricState& state, const Arm& arm,
                                                    std::size_t object, const Pose& objectPose,
                                                    std::mt19937_64& rng,
                                                    ApproachableGrasp& found) {
  motion::ToolKinematics& kinematics = tool(arm);
  GraspSampler sampler(*world_, kinematics);
  const Stopwatch ik;
  const std::vector<GraspCandidate> grasps =
      sampler.sample(object, objectPose, state.robots[arm.robot].configuration, rng);
  // The first IK solution of the sample whose pre-grasp is reachable on its branch and free.
  const motion::MotionGroup group(*world_, state, {arm.robot});
  std::string reason =
      grasps.empty() ? "no IK solution for the grasp sample" : "no IK solution for the pre-grasp";
  for (const GraspCandidate& grasp : grasps) {
    const Pose tcpAtGrasp = objectPose * grasp.tcpInObject;
    std::optional<std::vector<double>> preGrasp = kinematics.solveNear(
        tcpAtGrasp * Eigen::Translation3d(0, 0, -options_.approachDistance), grasp.configuration);
    if (!preGrasp) continue;
    const std::optional<std::string> problem = motion::configurationProblem(group, *preGrasp, 0);
    if (!problem) {
      found = {std::move(*preGrasp), tcpAtGrasp};
      reason.clear();
      break;
    }
    reason = "pre-grasp: " + *problem;
  }
  ++statistics_.ikCalls;
  statistics_.ikSeconds += ik.seconds();
  return reason;
}

std::string GeometricAttachments::approachGrasp(GeometricState& state, const Arm& arm,
                                                const Pose& tcpAtGrasp, const Pose& objectPose,
                                                motion::Waypoints& approach, Pose& objectInLink) {
  motion::MotionResult path = line(state, arm, tcpAtGrasp);
  if (path.status != PlannerStatus::Solved) return "approach: " + path.message;
  state.robots[arm.robot].configuration = path.path.back();
  motion::ToolKinematics& kinematics = tool(arm);
  const Pose tcp = kinematics.tcpPose(path.path.back());
  objectInLink = (tcp * kinematics.tcp().inverse()).inverse() * objectPose;
  approach = std::move(path.path);
  return {};
}

// One grasp sample of pickUp: IK for the grasp and its pre-grasp (approachDistance back along the
// tool's z axis), a certified transit path to the pre-grasp, the Cartesian approach, the grasp,
// and a Cartesian lift of liftHeight holding the object. Empty when it works, else why not.
std::string GeometricAttachments::tryGrasp(const GeometricState& state, const Arm& arm,
                                           std::size_t object, std::mt19937_64& rng,
                                           std::vector<GeometricStep>& steps,
                                           GeometricState& reached) {
  const Pose objectPose = state.placements[world_->scene().slot(object)].pose;
  ApproachableGrasp grasp;
  if (std::string reason = approachableGrasp(state, arm, object, objectPose, rng, grasp);
      !reason.empty()) {
    return reason;
  }
  // The approach and the lift start where the transit ends: checked first, since a grasp that
  // another object blocks fails there, before the costlier transit is planned.
  const std::uint64_t transitSeed = rng();
  GeometricState atGrasp = state;
  atGrasp.robots[arm.robot].configuration = grasp.preGrasp;
  motion::Waypoints approach;
  Pose objectInLink = Pose::Identity();
  if (std::string reason =
          approachGrasp(atGrasp, arm, grasp.tcpAtGrasp, objectPose, approach, objectInLink);
      !reason.empty()) {
    return reason;
  }
  world_->hold(atGrasp, arm.robot, toolLink(arm), object, objectInLink);
  const Pose tcp = tool(arm).tcpPose(atGrasp.robots[arm.robot].configuration);
  motion::MotionResult lift = line(atGrasp, arm, translated(Vec3(0, 0, options_.liftHeight), tcp));
  if (lift.status != PlannerStatus::Solved) return "lift: " + lift.message;
  options_.motion.seed = transitSeed;
  motion::MotionResult transit = plan(state, arm, grasp.preGrasp);
  if (transit.status != PlannerStatus::Solved) return "transit: " + transit.message;
  reached = std::move(atGrasp);
  reached.robots[arm.robot].configuration = lift.path.back();
  appendManipulation(steps, arm.robot, arm.tool, GeometricStep::Kind::Transit,
                     std::move(transit.path), std::move(approach), GeometricStep::Kind::Grasp,
                     object, objectInLink, std::move(lift.path));
  return {};
}

// pickUp(robot, object): up to graspSamples grasp samples (tryGrasp); the first that works. An
// object another one stands on is not picked (the one on top would fall): the call fails at once.
bool GeometricAttachments::pickUp(const AttachmentArgs& args, std::span<double> writes) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "pickUp");
  const std::optional<Arm> picking = arm(args, 0);
  const std::optional<std::size_t> target = object(args, 1);
  if (!picking) return fail("pickUp", args, kNotAnArm);
  if (!target) return fail("pickUp", args, kNotAMovableObject);
  if (!state.placements[world_->scene().slot(*target)].present) {
    return fail("pickUp", args, "the object is held");
  }
  if (state.isJoined(*target)) return fail("pickUp", args, kJoined);
  if (const std::optional<std::size_t> above = placements_.objectOnTop(state, *target)) {
    return fail("pickUp", args, "'" + world_->scene().name(*above) + "' stands on the object");
  }
  if (!state.robots[picking->robot].heldObjects.empty()) {
    return fail("pickUp", args, "the robot holds an object");
  }
  return firstSample(
      "pickUp", args, state, options_.graspSamples, writes,
      [&](std::mt19937_64& rng, std::vector<GeometricStep>& steps, GeometricState& reached) {
        return tryGrasp(state, *picking, *target, rng, steps, reached);
      });
}

FreeSpaceOptions GeometricAttachments::placementOptions(std::mt19937_64& rng) const {
  FreeSpaceOptions options;
  options.strategy = options_.placementStrategy;
  options.maxSamples = options_.placementCandidates;
  options.seed = rng();
  return options;
}

// The resting faces of `object` that leave the tool's z axis (its approach) at most 30° above
// horizontal when the object held at `tcpInObject` rests on them, the most downward first: an
// upside-down bottle held from above is no placement an arm reaches from above.
std::vector<std::size_t> GeometricAttachments::facesForGrasp(std::size_t object,
                                                             const Pose& tcpInObject) const {
  const std::span<const RestingFace> faces = placements_.restingFaces(object);
  std::vector<std::pair<double, std::size_t>> upward;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const double z = (faces[f].down * tcpInObject.rotation().col(2)).z();
    if (z <= 0.5) upward.emplace_back(z, f);
  }
  std::sort(upward.begin(), upward.end());
  std::vector<std::size_t> order;
  for (const auto& entry : upward) order.push_back(entry.second);
  return order;
}

// One placement sample of putDown: freeSpaceFound's placement in the location, IK above it
// (liftHeight), a certified transfer path there, the Cartesian descent, the release, and a
// Cartesian retreat of approachDistance back along the tool's z axis.
std::string GeometricAttachments::tryPlacement(const GeometricState& state, const Arm& arm,
                                               std::size_t object, std::size_t location,
                                               std::mt19937_64& rng,
                                               std::vector<GeometricStep>& steps,
                                               GeometricState& reached) {
  const RobotState& robot = state.robots[arm.robot];
  const std::size_t index = static_cast<std::size_t>(
      std::find(robot.heldObjects.begin(), robot.heldObjects.end(), object) -
      robot.heldObjects.begin());
  motion::ToolKinematics& kinematics = tool(arm);
  const Pose tcpInObject = robot.held[index].inLink.inverse() * kinematics.tcp();
  FreeSpaceOptions options = placementOptions(rng);
  options.faces = facesForGrasp(object, tcpInObject);
  if (options.faces.empty()) return "no resting face leaves the grasp reachable from above";
  const FreeSpace found = placements_.freeSpaceFound(state, object, location, options, scratch_);
  if (!found.pose) return std::string(kNoFreePlacement);
  const Pose tcpAtPlace = *found.pose * tcpInObject;
  std::vector<double> above;
  if (std::string reason =
          freeSolution(state, arm, translated(Vec3(0, 0, options_.liftHeight), tcpAtPlace),
                       "above the placement", above);
      !reason.empty()) {
    return reason;
  }
  // The descent, the release and the retreat start where the transfer ends: checked first, since
  // they fail more often and cost less.
  const std::uint64_t transferSeed = rng();
  GeometricState atPlace = state;
  atPlace.robots[arm.robot].configuration = above;
  motion::MotionResult descent = line(atPlace, arm, tcpAtPlace);
  if (descent.status != PlannerStatus::Solved) return "descent: " + descent.message;
  atPlace.robots[arm.robot].configuration = descent.path.back();
  const Pose placed = world_->release(atPlace, arm.robot, object);
  motion::MotionResult retreat = line(atPlace, arm,
                                      kinematics.tcpPose(descent.path.back()) *
                                          Eigen::Translation3d(0, 0, -options_.approachDistance));
  if (retreat.status != PlannerStatus::Solved) return "retreat: " + retreat.message;
  options_.motion.seed = transferSeed;
  motion::MotionResult transfer = plan(state, arm, above);
  if (transfer.status != PlannerStatus::Solved) return "transfer: " + transfer.message;
  reached = std::move(atPlace);
  reached.robots[arm.robot].configuration = retreat.path.back();
  appendManipulation(steps, arm.robot, arm.tool, GeometricStep::Kind::Transfer,
                     std::move(transfer.path), std::move(descent.path),
                     GeometricStep::Kind::Release, object, placed, std::move(retreat.path));
  return {};
}

// putDown(robot, object, location): up to placementSamples placements (tryPlacement); the first
// that works. When freeSpaceFound finds no placement at all, the location is full: no more samples.
bool GeometricAttachments::putDown(const AttachmentArgs& args, std::span<double> writes) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "putDown");
  const std::optional<Arm> placing = arm(args, 0);
  const std::optional<std::size_t> target = object(args, 1);
  const std::optional<std::size_t> where = location(args, 2);
  if (!placing) return fail("putDown", args, kNotAnArm);
  if (!target) return fail("putDown", args, kNotAMovableObject);
  if (!where) return fail("putDown", args, kNotALocation);
  const std::vector<std::size_t>& held = state.robots[placing->robot].heldObjects;
  if (std::find(held.begin(), held.end(), *target) == held.end()) {
    return fail("putDown", args, "the robot does not hold the object");
  }
  if (state.isJoined(*target)) return fail("putDown", args, kJoined);
  bool full = false;
  return firstSample(
      "putDown", args, state, options_.placementSamples, writes,
      [&](std::mt19937_64& rng, std::vector<GeometricStep>& steps, GeometricState& reached) {
        if (full) return std::string(kNoFreePlacement);
        std::string reason = tryPlacement(state, *placing, *target, *where, rng, steps, reached);
        full = reason == kNoFreePlacement;
        return reason;
      });
}

Pose GeometricAttachments::handoverPose(const GeometricState& state, const Arm& giver,
                                        const Arm& receiver, std::size_t object,
                                        std::mt19937_64& rng) {
  const Vec3 between =
      0.5 * (tool(giver).chainBase(state.robots[giver.robot].configuration).translation() +
             tool(receiver).chainBase(state.robots[receiver.robot].configuration).translation());
  const Pose now = objectPose(*world_, state, object);
  const auto spread = [&] { return options_.handoverSpread * (2 * uniformUnit(rng) - 1); };
  Pose pose = Pose::Identity();
  pose.linear() =
      Eigen::AngleAxisd(2 * std::numbers::pi * uniformUnit(rng), Vec3::UnitZ()) * now.linear();
  pose.translation() = Vec3(between.x() + spread(), between.y() + spread(),
                            now.translation().z() + options_.handoverRise * uniformUnit(rng));
  return pose;
}

// One object pose of handover: IK for the giver holding the object there (its grasp unchanged)
// and a grasp of the receiver that it can approach (approachableGrasp) with the giver there; a
// certified transfer path of the giver, a certified transit path of the receiver to its
// pre-grasp, the receiver's Cartesian approach and grasp, the giver's release, and its Cartesian
// retreat of approachDistance back along its tool's z axis.
std::string GeometricAttachments::tryHandover(const GeometricState& state, const Arm& giver,
                                              std::size_t object, const Arm& receiver,
                                              std::mt19937_64& rng,
                                              std::vector<GeometricStep>& steps,
                                              GeometricState& reached) {
  const RobotState& holder = state.robots[giver.robot];
  const std::size_t index = static_cast<std::size_t>(
      std::find(holder.heldObjects.begin(), holder.heldObjects.end(), object) -
      holder.heldObjects.begin());
  motion::ToolKinematics& giving = tool(giver);
  const Pose tcpInObject = holder.held[index].inLink.inverse() * giving.tcp();
  const Pose meeting = handoverPose(state, giver, receiver, object, rng);
  std::vector<double> giverAtMeeting;
  if (std::string reason = freeSolution(state, giver, meeting * tcpInObject,
                                        "at the giver's handover pose", giverAtMeeting);
      !reason.empty()) {
    return reason;
  }
  GeometricState atMeeting = state;
  atMeeting.robots[giver.robot].configuration = giverAtMeeting;
  ApproachableGrasp grasp;
  if (std::string reason = approachableGrasp(atMeeting, receiver, object, meeting, rng, grasp);
      !reason.empty()) {
    return "receiver: " + reason;
  }
  options_.motion.seed = rng();
  motion::MotionResult transfer = plan(state, giver, giverAtMeeting);
  if (transfer.status != PlannerStatus::Solved) return "giver's transfer: " + transfer.message;
  options_.motion.seed = rng();
  motion::MotionResult transit = plan(atMeeting, receiver, grasp.preGrasp);
  if (transit.status != PlannerStatus::Solved) return "receiver's transit: " + transit.message;
  GeometricState atGrasp = atMeeting;
  atGrasp.robots[receiver.robot].configuration = grasp.preGrasp;
  motion::Waypoints approach;
  Pose objectInLink = Pose::Identity();
  if (std::string reason =
          approachGrasp(atGrasp, receiver, grasp.tcpAtGrasp, meeting, approach, objectInLink);
      !reason.empty()) {
    return "receiver's " + reason;
  }
  const Pose handed = world_->release(atGrasp, giver.robot, object);
  world_->hold(atGrasp, receiver.robot, toolLink(receiver), object, objectInLink);
  options_.motion.seed = rng();
  motion::MotionResult retreat =
      line(atGrasp, giver,
           giving.tcpPose(giverAtMeeting) * Eigen::Translation3d(0, 0, -options_.approachDistance));
  if (retreat.status != PlannerStatus::Solved) return "giver's retreat: " + retreat.message;
  reached = std::move(atGrasp);
  reached.robots[giver.robot].configuration = retreat.path.back();
  steps.push_back({GeometricStep::Kind::Transfer, giver.robot, giver.tool, std::move(transfer.path),
                   0, Pose::Identity()});
  steps.push_back({GeometricStep::Kind::Transit, receiver.robot, receiver.tool,
                   std::move(transit.path), 0, Pose::Identity()});
  steps.push_back({GeometricStep::Kind::Approach, receiver.robot, receiver.tool,
                   std::move(approach), 0, Pose::Identity()});
  steps.push_back(
      {GeometricStep::Kind::Grasp, receiver.robot, receiver.tool, {}, object, objectInLink});
  steps.push_back({GeometricStep::Kind::Release, giver.robot, giver.tool, {}, object, handed});
  steps.push_back({GeometricStep::Kind::Retreat, giver.robot, giver.tool, std::move(retreat.path),
                   0, Pose::Identity()});
  return {};
}

// handover(robot, object, robot'): up to handoverSamples object poses (tryHandover); the first
// that works. Afterwards robot' holds the object and robot's hand is empty.
bool GeometricAttachments::handover(const AttachmentArgs& args, std::span<double> writes) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "handover");
  const std::optional<Arm> giver = arm(args, 0);
  const std::optional<std::size_t> target = object(args, 1);
  const std::optional<Arm> receiver = arm(args, 2);
  if (!giver || !receiver) return fail("handover", args, kNotAnArm);
  if (!target) return fail("handover", args, kNotAMovableObject);
  if (giver->robot == receiver->robot) {
    return fail("handover", args, "the giver and the receiver are one robot");
  }
  const std::vector<std::size_t>& held = state.robots[giver->robot].heldObjects;
  if (std::find(held.begin(), held.end(), *target) == held.end()) {
    return fail("handover", args, "the giver does not hold the object");
  }
  if (state.isJoined(*target)) return fail("handover", args, kJoined);
  if (!state.robots[receiver->robot].heldObjects.empty()) {
    return fail("handover", args, "the receiver holds an object");
  }
  return firstSample(
      "handover", args, state, options_.handoverSamples, writes,
      [&](std::mt19937_64& rng, std::vector<GeometricStep>& steps, GeometricState& reached) {
        return tryHandover(state, *giver, *target, *receiver, rng, steps, reached);
      });
}

// isInside(object, location): every vertex of the object's pieces in the location's region.
bool GeometricAttachments::isInside(const AttachmentArgs& args) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "isInside");
  const std::optional<std::size_t> target = object(args, 0);
  const std::optional<std::size_t> where = location(args, 1);
  return target && where && placements_.isInside(state, *target, *where);
}

// isOnSupportSurface(object): the object rests on another object or a support-surface location.
bool GeometricAttachments::isOnSupportSurface(const AttachmentArgs& args) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "isOnSupportSurface");
  const std::optional<std::size_t> target = object(args, 0);
  return target && placements_.isOnSupportSurface(state, *target, scratch_).has_value();
}

// freeSpaceFound(object, location): the location has room for the object (seed 003's suggester,
// sampled as putDown samples it).
bool GeometricAttachments::freeSpaceFound(const AttachmentArgs& args) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "freeSpaceFound");
  const std::optional<std::size_t> target = object(args, 0);
  const std::optional<std::size_t> where = location(args, 1);
  if (!target || !where) return false;
  std::mt19937_64 rng = generator("freeSpaceFound", args);
  return placements_.freeSpaceFound(state, *target, *where, placementOptions(rng), scratch_)
      .pose.has_value();
}

// isReachable(robot, object): some grasp of the object at its pose has an IK solution at which
// the robot collides with nothing.
bool GeometricAttachments::isReachable(const AttachmentArgs& args) {
  ++statistics_.calls;
  const GeometricState& state = stateOf(args, "isReachable");
  const std::optional<Arm> reaching = arm(args, 0);
  const std::optional<std::size_t> target = object(args, 1);
  if (!reaching || !target) return false;
  const Placement& placement = state.placements[world_->scene().slot(*target)];
  std::mt19937_64 rng = generator("isReachable", args);
  GraspSampler sampler(*world_, tool(*reaching));
  bool reachable = false;
  const motion::MotionGroup group(*world_, state, {reaching->robot});
  for (int sample = 0; placement.present && sample < options_.graspSamples && !reachable;
       ++sample) {
    const Stopwatch ik;
    const std::vector<GraspCandidate> grasps =
        sampler.sample(*target, placement.pose, state.robots[reaching->robot].configuration, rng);
    ++statistics_.ikCalls;
    statistics_.ikSeconds += ik.seconds();
    reachable = std::any_of(grasps.begin(), grasps.end(), [&](const GraspCandidate& grasp) {
      return !motion::configurationProblem(group, grasp.configuration, 0);
    });
  }
  return reachable;
}

// isColliding(): whether the state has a collision (the bounded predicates at distance 0).
bool GeometricAttachments::isColliding(const AttachmentArgs& args) {
  ++statistics_.calls;
  const bool colliding = world_->firstCollision(stateOf(args, "isColliding")).has_value();
  return colliding;
}

}  // namespace kaboum::tamp
