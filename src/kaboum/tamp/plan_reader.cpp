#include "kaboum/tamp/plan_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <tuple>

#include "kaboum/core/error.hpp"
#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/symbolic/sexpr.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::tamp {

using json = nlohmann::json;
using namespace kaboum::symbolic;

namespace {

// Metres and radians: how far a plan file's initial object pose may lie from the scene's (the
// file's numbers are printed at full precision).
constexpr double kInitialPoseTolerance = 1e-6;

// The keys of one plan file: each read names where it failed.
class Reader {
 public:
  Reader(const std::string& file, const KnowledgeTask& task, const World& world)
      : file_(file), task_(task), world_(world) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(locate(file_, key + ": " + what));
  }

  const json& member(const json& object, const std::string& key, const std::string& name) const {
    if (!object.is_object()) fail(key, "expected an object");
    const auto found = object.find(name);
    if (found == object.end()) fail(key, "missing key '" + name + "'");
    return *found;
  }
  std::string string(const json& object, const std::string& key, const std::string& name) const {
    const json& value = member(object, key, name);
    if (!value.is_string()) fail(key + "." + name, "expected a string");
    return value.get<std::string>();
  }
  std::size_t index(const json& object, const std::string& key, const std::string& name) const {
    const json& value = member(object, key, name);
    if (!value.is_number_integer() || value.get<std::int64_t>() < 0) {
      fail(key + "." + name, "expected a non-negative integer");
    }
    return value.get<std::size_t>();
  }
  const json& array(const json& object, const std::string& key, const std::string& name) const {
    const json& value = member(object, key, name);
    if (!value.is_array()) fail(key + "." + name, "expected an array");
    return value;
  }
  std::vector<double> numbers(const json& value, const std::string& key) const {
    if (!value.is_array()) fail(key, "expected an array of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (!value[i].is_number()) fail(fmt::format("{}[{}]", key, i), "expected a number");
      out.push_back(value[i].get<double>());
    }
    return out;
  }
  // The plan's initial object poses against the World's: a plan made on another layout (another
  // scene file, or --placement-seed) does not apply.
  void checkInitialPlacements(const json& state) const {
    const json& objects = member(state, "initial_state", "objects");
    if (!objects.is_object()) fail("initial_state.objects", "expected an object");
    const GeometricState initial = world_.initialState();
    for (const auto& [name, value] : objects.items()) {
      const std::optional<NamedEntity> entity = world_.find(name);
      if (!entity || entity->kind != NamedEntity::Kind::Object) {
        fail("initial_state.objects", "the scene has no object '" + name + "'");
      }
      const Pose planned = pose(objects, "initial_state.objects", name);
      const Pose scene = world_.scene().pose(entity->index, initial.placements);
      const double offset = (planned.translation() - scene.translation()).norm();
      const double turn = Eigen::AngleAxisd(planned.linear().transpose() * scene.linear()).angle();
      if (offset > kInitialPoseTolerance || turn > kInitialPoseTolerance) {
        fail("initial_state.objects." + name,
             fmt::format("the scene starts the object elsewhere ({:.1f} mm, {:.2f}° away): the "
                         "plan was made on another scene or --placement-seed",
                         1000 * offset, turn * 180 / std::numbers::pi));
      }
    }
  }

  // A pose as io::toJson(Pose) writes it: {position, quaternion_wxyz}.
  Pose pose(const json& object, const std::string& key, const std::string& name) const {
    return io::poseFromJson(member(object, key, name), file_, key + "." + name);
  }
  // One S-expression, written the way the task names things.
  SExpr expression(const std::string& text, const std::string& key) const {
    std::vector<SExpr> read;
    try {
      read = readSExprs(text, file_);
    } catch (const InputError&) {
      fail(key, "not an S-expression: " + text);
    }
    if (read.size() != 1) fail(key, "expected one S-expression: " + text);
    return read.front();
  }
  std::size_t entity(const json& object, const std::string& key, const std::string& name,
                     NamedEntity::Kind kind, const char* what) const {
    const std::string written = string(object, key, name);
    const std::optional<NamedEntity> found = world_.find(written);
    if (!found || found->kind != kind) {
      fail(key + "." + name, fmt::format("no {} '{}' in the scene", what, written));
    }
    return found->index;
  }

  GeometricStep step(const json& value, const std::string& key) const {
    GeometricStep step;
    const std::string kind = string(value, key, "kind");
    constexpr GeometricStep::Kind kinds[] = {
        GeometricStep::Kind::Transit, GeometricStep::Kind::Transfer, GeometricStep::Kind::Approach,
        GeometricStep::Kind::Retreat, GeometricStep::Kind::Grasp,    GeometricStep::Kind::Release,
        GeometricStep::Kind::Join};
    const auto known = std::find_if(std::begin(kinds), std::end(kinds),
                                    [&](GeometricStep::Kind k) { return kind == toString(k); });
    if (known == std::end(kinds)) {
      fail(key + ".kind",
           "'" + kind + "' is none of transit, transfer, approach, retreat, grasp, release, join");
    }
    step.kind = *known;
    step.robot = entity(value, key, "robot", NamedEntity::Kind::Robot, "robot");
    const RobotSpec& spec = world_.description().robots[step.robot];
    const std::string tool = string(value, key, "tool");
    const auto named = std::find_if(spec.tools.begin(), spec.tools.end(),
                                    [&](const ToolSpec& t) { return t.name == tool; });
    const bool gripper =
        step.kind == GeometricStep::Kind::Grasp || step.kind == GeometricStep::Kind::Release;
    if (named != spec.tools.end()) {
      step.tool = static_cast<std::size_t>(named - spec.tools.begin());
    } else if (gripper || !tool.empty()) {
      fail(key + ".tool", fmt::format("robot '{}' has no tool '{}'", spec.name, tool));
    }
    if (step.kind == GeometricStep::Kind::Join) {
      const json& objects = array(value, key, "objects");
      if (objects.size() != 2) fail(key + ".objects", "expected the two objects joined");
      std::size_t ids[2];
      for (std::size_t i = 0; i < 2; ++i) {
        const std::string at = fmt::format("{}.objects[{}]", key, i);
        const std::optional<NamedEntity> found =
            objects[i].is_string() ? world_.find(objects[i].get<std::string>()) : std::nullopt;
        if (!found || found->kind != NamedEntity::Kind::Object ||
            !world_.scene().movable(found->index)) {
          fail(at, "expected the name of a movable object of the scene");
        }
        ids[i] = found->index;
      }
      if (ids[0] == ids[1]) fail(key + ".objects", "an object cannot be joined to itself");
      step.object = ids[0];
      step.joinedTo = ids[1];
      return step;
    }
    if (gripper) {
      step.object = entity(value, key, "object", NamedEntity::Kind::Object, "object");
      if (!world_.scene().movable(step.object)) {
        fail(key + ".object",
             fmt::format("object '{}' is not movable", world_.scene().name(step.object)));
      }
      if (step.kind == GeometricStep::Kind::Grasp) {
        const std::string link = string(value, key, "link");
        if (link != spec.tools[step.tool].link) {
          fail(key + ".link", fmt::format("tool '{}' of robot '{}' is on link '{}', not '{}'", tool,
                                          spec.name, spec.tools[step.tool].link, link));
        }
        step.pose = pose(value, key, "object_in_link");
      } else {
        step.pose = pose(value, key, "object_pose");
      }
      return step;
    }
    const json& waypoints = array(value, key, "waypoints");
    if (waypoints.empty()) fail(key + ".waypoints", "no waypoint");
    const std::vector<std::size_t> robots{step.robot};
    for (std::size_t w = 0; w < waypoints.size(); ++w) {
      const std::string at = fmt::format("{}.waypoints[{}]", key, w);
      step.path.push_back(numbers(waypoints[w], at));
      const std::string error = verify::waypointError(world_, robots, step.path.back());
      if (!error.empty()) throw InputError(locate(file_, at + error));
    }
    return step;
  }

  ActionGeometry geometry(const json& value, const std::string& key) const {
    ActionGeometry action;
    action.procedure = string(value, key, "procedure");
    if (!GeometricAttachments::isGeometricEffect(action.procedure)) {
      fail(key + ".procedure", "'" + action.procedure + "' is no geometric effect");
    }
    const json& arguments = array(value, key, "arguments");
    for (std::size_t i = 0; i < arguments.size(); ++i) {
      if (!arguments[i].is_string()) {
        fail(fmt::format("{}.arguments[{}]", key, i), "expected a string");
      }
      action.arguments.push_back(arguments[i].get<std::string>());
    }
    action.from = index(value, key, "from_state");
    action.to = index(value, key, "to_state");
    const json& steps = array(value, key, "steps");
    for (std::size_t s = 0; s < steps.size(); ++s) {
      action.steps.push_back(step(steps[s], fmt::format("{}.steps[{}]", key, s)));
    }
    return action;
  }

  PlanFileContents read(const json& file) const {
    if (!file.is_object()) fail("(top level)", "expected a JSON object");
    if (string(file, "(top level)", "format") != "kaboum-plan") {
      fail("format", "expected \"kaboum-plan\"");
    }
    if (index(file, "(top level)", "version") != 1) fail("version", "only version 1 is known");
    if (file.contains("initial_state")) checkInitialPlacements(file["initial_state"]);
    const json& nodes = array(file, "(top level)", "nodes");
    PlanFileContents contents;
    contents.plan.nodes.resize(nodes.size());
    contents.geometry.resize(nodes.size());
    const auto reference = [&](const json& object, const std::string& key,
                               const std::string& name) {
      const std::size_t id = index(object, key, name);
      if (id >= nodes.size()) {
        fail(key + "." + name, fmt::format("no node {} (the plan has {})", id, nodes.size()));
      }
      return static_cast<int>(id);
    };
    contents.plan.root = reference(file, "(top level)", "root");
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      const std::string key = fmt::format("nodes[{}]", n);
      const json& value = nodes[n];
      if (index(value, key, "id") != n) fail(key + ".id", fmt::format("expected {}", n));
      PlanTree::Node& node = contents.plan.nodes[n];
      const std::string kind = string(value, key, "kind");
      if (kind == "goal") continue;
      if (kind == "branch") {
        node.kind = PlanTree::Node::Kind::Branch;
        const SExpr test = expression(string(value, key, "test"), key + ".test");
        const SExpr* where = nullptr;
        const std::string error = resolveBranchTest(test, task_, node, where);
        if (!error.empty()) fail(key + ".test", error);
        node.next = reference(value, key, "on_true");
        node.onFalse = reference(value, key, "on_false");
        continue;
      }
      if (kind != "action") fail(key + ".kind", "'" + kind + "' is none of goal, branch, action");
      node.kind = PlanTree::Node::Kind::Action;
      const std::string action = string(value, key, "action");
      node.op = task_.findOperator(toString(expression(action, key + ".action")));
      if (node.op < 0) fail(key + ".action", "unknown or never applicable action " + action);
      if (value.contains("sample")) {
        const std::size_t sample = index(value, key, "sample");
        if (sample > std::numeric_limits<std::uint32_t>::max()) {
          fail(key + ".sample", "expected a sample number below 2^32");
        }
        node.sample = static_cast<std::uint32_t>(sample);
      }
      node.next = reference(value, key, "next");
      const json& geometry = array(value, key, "geometry");
      for (std::size_t g = 0; g < geometry.size(); ++g) {
        contents.geometry[n].push_back(
            this->geometry(geometry[g], fmt::format("{}.geometry[{}]", key, g)));
      }
    }
    return contents;
  }

 private:
  const std::string& file_;
  const KnowledgeTask& task_;
  const World& world_;
};

bool posesClose(const Pose& a, const Pose& b) {
  return (a.translation() - b.translation()).norm() <= kPlanPositionTolerance &&
         Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() <= kPlanAngleTolerance;
}

// The largest difference between two configurations of one robot, and the joint where it is.
std::pair<double, std::size_t> largestDifference(const std::vector<double>& a,
                                                 const std::vector<double>& b) {
  std::pair<double, std::size_t> largest{0.0, 0};
  for (std::size_t j = 0; j < a.size(); ++j) {
    const double difference = std::abs(a[j] - b[j]);
    if (!(difference <= largest.first)) largest = {difference, j};
  }
  return largest;
}

// Whether two replayed states are the same under the plan tolerances.
bool sameState(const GeometricState& a, const GeometricState& b) {
  for (std::size_t r = 0; r < a.robots.size(); ++r) {
    const RobotState& x = a.robots[r];
    const RobotState& y = b.robots[r];
    if (largestDifference(x.configuration, y.configuration).first > kPlanJointTolerance ||
        x.heldObjects != y.heldObjects) {
      return false;
    }
    for (std::size_t h = 0; h < x.held.size(); ++h) {
      if (x.held[h].link != y.held[h].link || !posesClose(x.held[h].inLink, y.held[h].inLink)) {
        return false;
      }
    }
  }
  for (std::size_t slot = 0; slot < a.placements.size(); ++slot) {
    if (a.placements[slot].present != b.placements[slot].present ||
        (a.placements[slot].present &&
         !posesClose(a.placements[slot].pose, b.placements[slot].pose))) {
      return false;
    }
  }
  return true;
}

// A fluent value that is a geometric state identifier.
std::optional<std::size_t> stateId(double value) {
  if (!(value >= 0) || value != std::floor(value) || value > 1e15) return std::nullopt;
  return static_cast<std::size_t>(value);
}

// A geometric effect's call: procedure, arguments, the state it starts from, the sample.
using TransitionKey = std::tuple<std::string, std::vector<std::string>, std::size_t, std::uint32_t>;

// Replays the plan's geometry from the World's initial state along every branch.
class Replay {
 public:
  Replay(const World& world, const KnowledgeTask& task, const PlanCheckOptions& options,
         PlanCheck& check)
      : world_(world), task_(task), options_(options), check_(check), reference_(world) {}

  // The replayed state of every identifier the plan's geometry names.
  std::map<std::size_t, GeometricState> run() {
    const PlanTree& plan = check_.contents.plan;
    states_[0] = world_.initialState();
    std::set<std::pair<int, std::size_t>> visited;
    std::vector<std::pair<int, std::size_t>> open{{plan.root, 0}};
    while (!open.empty()) {
      const auto [n, id] = open.back();
      open.pop_back();
      if (!visited.insert({n, id}).second) continue;
      const PlanTree::Node& node = plan.nodes[static_cast<std::size_t>(n)];
      if (node.kind == PlanTree::Node::Kind::Branch) {
        open.emplace_back(node.next, id);
        open.emplace_back(node.onFalse, id);
      } else if (node.kind == PlanTree::Node::Kind::Action) {
        open.emplace_back(node.next, action(static_cast<std::size_t>(n), id));
      }
    }
    return std::move(states_);
  }

 private:
  // Replays node `n`'s geometry from state `id`; returns the identifier of the state it ends in.
  std::size_t action(std::size_t n, std::size_t id) {
    const std::string name = fmt::format(
        "nodes[{}] ({})", n,
        task_.task().operators[static_cast<std::size_t>(check_.contents.plan.nodes[n].op)].name);
    if (options_.progress && !check_.contents.geometry[n].empty()) options_.progress(name);
    GeometricState current = states_.at(id);
    for (const ActionGeometry& action : check_.contents.geometry[n]) {
      const std::string effect =
          fmt::format("{}: {}({})", name, action.procedure, fmt::join(action.arguments, ", "));
      const auto known = states_.find(action.from);
      if (known != states_.end() && !sameState(known->second, current)) {
        fail(
            fmt::format("{}: starts in geometric state {}, which the plan reaches elsewhere as "
                        "another state",
                        effect, action.from));
      }
      std::vector<GeometricState> states;
      try {
        states = statesAlong(world_, current, action);
      } catch (const std::invalid_argument& error) {
        fail(fmt::format("{}: {}", effect, error.what()));
        return id;
      }
      checkSteps(effect, action, states);
      verifyActionPaths(reference_, n, action, states, options_.verification, check_.verification);
      current = states.back();
      const auto [reached, inserted] = states_.emplace(action.to, current);
      if (!inserted && !sameState(reached->second, current)) {
        fail(
            fmt::format("{}: ends in geometric state {}, which another branch reaches as "
                        "another state",
                        effect, action.to));
      }
      id = action.to;
    }
    return id;
  }

  // Each motion starts where the robot is; grasps and releases are where the object is.
  void checkSteps(const std::string& effect, const ActionGeometry& action,
                  const std::vector<GeometricState>& states) {
    for (std::size_t s = 0; s < action.steps.size(); ++s) {
      const GeometricStep& step = action.steps[s];
      const std::string at = fmt::format("{} step {} ({})", effect, s + 1, toString(step.kind));
      const WorldRobot& robot = world_.robots()[step.robot];
      if (!step.path.empty()) {
        const auto [difference, joint] =
            largestDifference(step.path.front(), states[s].robots[step.robot].configuration);
        if (difference > kPlanJointTolerance) {
          fail(fmt::format("{}: starts {:g} (joint '{}') from where robot '{}' is", at, difference,
                           robot.collision.model().variableJoint(static_cast<int>(joint)).name,
                           robot.name));
        }
        continue;
      }
      if (step.kind == GeometricStep::Kind::Join) continue;
      const std::string object = world_.scene().name(step.object);
      if (step.kind == GeometricStep::Kind::Release) {
        if (!posesClose(objectPose(world_, states[s + 1], step.object), step.pose)) {
          fail(fmt::format("{}: object '{}' is released away from where robot '{}' holds it", at,
                           object, robot.name));
        }
        continue;
      }
      const RobotCollisionModel& model = robot.collision;
      std::vector<Pose> links(model.model().links().size());
      model.model().linkPoses(states[s].robots[step.robot].configuration, links);
      const int link = states[s + 1].robots[step.robot].held.back().link;
      const Pose held = model.basePose() * links[static_cast<std::size_t>(link)] * step.pose;
      if (!posesClose(objectPose(world_, states[s], step.object), held)) {
        fail(fmt::format("{}: robot '{}' grasps object '{}' away from where it is", at, robot.name,
                         object));
      }
    }
  }

  void fail(std::string what) { check_.failures.push_back(std::move(what)); }

  const World& world_;
  const KnowledgeTask& task_;
  const PlanCheckOptions& options_;
  PlanCheck& check_;
  const verify::ReferenceGeometry reference_;
  std::map<std::size_t, GeometricState> states_;
};

}  // namespace

PlanFileContents readPlanFile(const json& file, const std::string& fileName,
                              const KnowledgeTask& task, const World& world) {
  return Reader(fileName, task, world).read(file);
}

PlanCheck verifyPlanFile(const World& world, const ContingentProblem& problem, const json& file,
                         const std::string& fileName, const PlanCheckOptions& options) {
  // The symbolic validation sees the plan's geometry: each geometric effect answers with the
  // plan's recorded transition, each condition checker with the attachments' answer on the
  // replayed state.
  GeometricAttachments attachments(world);
  std::map<TransitionKey, std::size_t> transitions;
  std::map<std::size_t, std::size_t> ids;  // the plan's state identifiers → the attachments'
  ProcedureRegistry geometric;
  attachments.registerProcedures(geometric);
  ProcedureRegistry registry;
  for (const std::string& name : GeometricAttachments::procedureNames()) {
    if (GeometricAttachments::isGeometricEffect(name)) {
      registry.addApplicator(
          name, [&transitions, name](const AttachmentArgs& args, std::span<double> writes) {
            const std::optional<std::size_t> from =
                args.reads.empty() ? std::nullopt : stateId(args.reads[0]);
            if (!from || writes.size() != 1) return false;
            std::vector<std::string> arguments;
            for (std::size_t i = 0; i < args.objects.size(); ++i)
              arguments.emplace_back(args.name(i));
            const auto found = transitions.find({name, arguments, *from, args.sample});
            if (found == transitions.end()) return false;
            writes[0] = static_cast<double>(found->second);
            return true;
          });
      continue;
    }
    registry.addChecker(name,
                        [&ids, checker = *geometric.checker(name)](const AttachmentArgs& args) {
                          const std::optional<std::size_t> id =
                              args.reads.empty() ? std::nullopt : stateId(args.reads[0]);
                          const auto found = id ? ids.find(*id) : ids.end();
                          if (found == ids.end()) return false;
                          std::vector<double> reads(args.reads.begin(), args.reads.end());
                          reads[0] = static_cast<double>(found->second);
                          return checker({args.objects, args.objectNames, reads});
                        });
  }
  KnowledgeTask task(problem, registry);
  PlanCheck check;
  check.contents = readPlanFile(file, fileName, task, world);
  check.verification.pathsChecked = true;
  check.verification.smallestClearance = std::numeric_limits<double>::infinity();
  const auto start = std::chrono::steady_clock::now();
  for (const auto& [id, state] : Replay(world, task, options, check).run()) {
    ids[id] = attachments.intern(state);
  }
  for (std::size_t node = 0; node < check.contents.geometry.size(); ++node) {
    const std::uint32_t sample = check.contents.plan.nodes[node].sample;
    for (const ActionGeometry& action : check.contents.geometry[node]) {
      transitions.emplace(TransitionKey{action.procedure, action.arguments, action.from, sample},
                          action.to);
    }
  }
  check.verification.symbolic = validatePlanTree(task, check.contents.plan, fileName);
  check.verification.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return check;
}

}  // namespace kaboum::tamp
