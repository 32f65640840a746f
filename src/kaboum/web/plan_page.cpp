#include "kaboum/web/plan_page.hpp"

#include <fmt/format.h>

#include <map>

#include "kaboum/core/error.hpp"
#include "kaboum/exec/executor.hpp"
#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/web/geometry_pack.hpp"
#include "kaboum/web/viewer_script.hpp"

namespace kaboum::web {

namespace {

using Node = symbolic::PlanTree::Node;
using kaboum::io::toJson;

nlohmann::json vectorJson(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

// The page's geometry: original meshes read once per file and scale, convex pieces.
class SceneGeometry {
 public:
  // A collision shape as the page draws it: a primitive, or an entry of the pack.
  nlohmann::json shape(const kinematics::CollisionShape& shape) {
    nlohmann::json out{{"origin", toJson(shape.origin)}};
    switch (shape.kind) {
      case kinematics::CollisionShape::Kind::Box:
        out["box"] = vectorJson(shape.size);
        break;
      case kinematics::CollisionShape::Kind::Cylinder:
        out["cylinder"] = {shape.radius, shape.length};
        break;
      case kinematics::CollisionShape::Kind::Sphere:
        out["sphere"] = shape.radius;
        break;
      case kinematics::CollisionShape::Kind::Mesh:
        out["mesh"] = meshEntry(shape);
        break;
    }
    return out;
  }

  // Every convex piece of `body`, in its frame: pack entries.
  nlohmann::json pieces(const collision::CollisionBody& body) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t i = 0; i < body.pieceCount(); ++i) {
      out.push_back(pack_.addPoints(body.piece(i).vertices()));
      ++pieceCount_;
    }
    return out;
  }

  [[nodiscard]] std::size_t meshCount() const { return meshEntries_.size(); }
  [[nodiscard]] std::size_t pieceCount() const { return pieceCount_; }
  [[nodiscard]] nlohmann::json json() const { return pack_.json(); }

 private:
  std::size_t meshEntry(const kinematics::CollisionShape& shape) {
    const std::string key =
        fmt::format("{}|{}|{}|{}", shape.meshPath, shape.size.x(), shape.size.y(), shape.size.z());
    const auto found = meshEntries_.find(key);
    if (found != meshEntries_.end()) return found->second;
    if (!files_.contains(shape.meshPath)) {
      files_.emplace(shape.meshPath, io::readMesh(shape.meshPath));
    }
    const std::size_t entry = pack_.addMesh(collision::shapeMesh(shape, files_));
    meshEntries_.emplace(key, entry);
    return entry;
  }

  GeometryPack pack_;
  collision::LinkMeshes files_;
  std::map<std::string, std::size_t> meshEntries_;
  std::size_t pieceCount_ = 0;
};

const char* jointType(kinematics::JointType type) {
  switch (type) {
    case kinematics::JointType::Fixed:
      return "fixed";
    case kinematics::JointType::Prismatic:
      return "prismatic";
    default:
      return "revolute";
  }
}

nlohmann::json robotJson(const world::World& world, std::size_t r,
                         const std::vector<double>& initial, SceneGeometry& geometry) {
  const world::WorldRobot& robot = world.robots()[r];
  const io::RobotSpec& spec = world.description().robots[r];
  const kinematics::RobotModel& model = robot.collision.model();
  nlohmann::json links = nlohmann::json::array();
  for (const kinematics::Link& link : model.links()) {
    nlohmann::json shapes = nlohmann::json::array();
    for (const kinematics::CollisionShape& shape : link.collisions) {
      shapes.push_back(geometry.shape(shape));
    }
    links.push_back({{"name", link.name}, {"shapes", shapes}, {"pieces", nlohmann::json::array()}});
  }
  for (const io::ToolSpec& tool : spec.tools) {
    if (!tool.hand) continue;
    const int link = *model.findLink(tool.link);
    for (const io::Geometry& shape : tool.hand->shapes) {
      links[static_cast<std::size_t>(link)]["shapes"].push_back(geometry.shape(shape.shape));
    }
  }
  for (std::size_t p = 0; p < robot.collision.partCount(); ++p) {
    const collision::Attachment& part = robot.collision.part(p);
    links[static_cast<std::size_t>(part.link)]["pieces"].push_back(
        {{"origin", toJson(part.inLink)}, {"entries", geometry.pieces(*part.body)}});
  }
  nlohmann::json joints = nlohmann::json::array();
  for (const kinematics::Joint& joint : model.joints()) {
    joints.push_back({{"name", joint.name},
                      {"type", jointType(joint.type)},
                      {"parent", joint.parentLink},
                      {"child", joint.childLink},
                      {"origin", toJson(joint.origin)},
                      {"axis", vectorJson(joint.axis)},
                      {"variable", joint.variable}});
  }
  std::vector<std::string> tools;
  for (const io::ToolSpec& tool : spec.tools) tools.push_back(tool.link);
  return {{"name", robot.name}, {"base", toJson(robot.collision.basePose())},
          {"links", links},     {"joints", joints},
          {"initial", initial}, {"tool_links", tools}};
}

nlohmann::json objectJson(const world::World& world, const world::GeometricState& state,
                          std::size_t object, SceneGeometry& geometry) {
  const io::ObjectSpec& spec = world.description().objects[object];
  const collision::CollisionScene& scene = world.scene();
  return {{"name", spec.name},
          {"movable", spec.movable},
          {"pose", toJson(scene.pose(object, state.placements))},
          {"shapes", nlohmann::json::array({geometry.shape(spec.geometry.shape)})},
          {"pieces", geometry.pieces(scene.body(object))}};
}

nlohmann::json locationJson(const io::LocationSpec& location) {
  nlohmann::json out{{"name", location.name}, {"support", location.supportSurface}};
  if (const auto* box = std::get_if<io::BoxRegion>(&location.region)) {
    out["pose"] = toJson(box->pose);
    out["box"] = {vectorJson(box->lower), vectorJson(box->upper)};
  } else {
    const auto& hull = std::get<io::HullRegion>(location.region);
    out["pose"] = toJson(hull.pose);
    nlohmann::json points = nlohmann::json::array();
    for (const Vec3& point : hull.points) points.push_back(vectorJson(point));
    out["hull"] = points;
  }
  return out;
}

// An action node's motions and gripper events timed from the action's start, as
// exec::Schedule::append times them.
nlohmann::json timedActionJson(const world::World& world, std::size_t node,
                               const std::vector<tamp::ActionGeometry>& geometry,
                               const std::vector<std::vector<double>>& initial,
                               const std::vector<exec::JointLimits>& limits) {
  exec::Schedule schedule(initial, limits, exec::Profile::RestToRest);
  schedule.append(node, "", geometry);
  nlohmann::json motions = nlohmann::json::array();
  for (const exec::TimedMotion& motion : schedule.motions()) {
    nlohmann::json waypoints = nlohmann::json::array();
    for (const std::vector<double>& waypoint : motion.path.waypoints()) {
      waypoints.push_back(waypoint);
    }
    motions.push_back({{"robot", motion.robot},
                       {"start", motion.start},
                       {"durations", motion.path.durations()},
                       {"waypoints", waypoints}});
  }
  nlohmann::json events = nlohmann::json::array();
  for (const exec::GripperEvent& event : schedule.events()) {
    const io::ToolSpec& tool = world.description().robots[event.robot].tools[event.tool];
    const int link = *world.robots()[event.robot].collision.model().findLink(tool.link);
    events.push_back({{"time", event.time},
                      {"kind", tamp::toString(event.kind)},
                      {"robot", event.robot},
                      {"link", link},
                      {"object", event.object},
                      {"pose", toJson(event.pose)}});
  }
  return {{"duration", schedule.duration()}, {"motions", motions}, {"events", events}};
}

std::vector<std::vector<double>> initialConfigurations(const world::GeometricState& state) {
  std::vector<std::vector<double>> out;
  for (const world::RobotState& robot : state.robots) out.push_back(robot.configuration);
  return out;
}

nlohmann::json nodesJson(const world::World& world, const symbolic::KnowledgeTask& task,
                         const tamp::PlanFileContents& plan,
                         const std::vector<std::vector<double>>& initial,
                         const std::vector<exec::JointLimits>& limits) {
  nlohmann::json nodes = nlohmann::json::array();
  for (std::size_t n = 0; n < plan.plan.nodes.size(); ++n) {
    const Node& node = plan.plan.nodes[n];
    if (node.kind == Node::Kind::Goal) {
      nodes.push_back({{"kind", "goal"}});
    } else if (node.kind == Node::Kind::Branch) {
      nodes.push_back({{"kind", "branch"},
                       {"test", symbolic::branchTest(task, node)},
                       {"on_true", node.next},
                       {"on_false", node.onFalse}});
    } else {
      nlohmann::json action = timedActionJson(world, n, plan.geometry[n], initial, limits);
      action["kind"] = "action";
      action["action"] = exec::actionName(task, node);
      action["next"] = node.next;
      nodes.push_back(std::move(action));
    }
  }
  return nodes;
}

// The JSON text safe inside a <script> element: "</" never appears in it.
std::string scriptSafe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    out.push_back(json[i]);
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out.push_back('\\');
  }
  return out;
}

std::string htmlEscaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '&') {
      out += "&amp;";
    } else {
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace

PlanPage planPage(const world::World& world, const symbolic::KnowledgeTask& task,
                  const tamp::PlanFileContents& plan, const PageOptions& options) {
  const world::GeometricState state = world.initialState();
  const std::vector<std::vector<double>> initial = initialConfigurations(state);
  const std::vector<exec::JointLimits> limits = exec::jointLimits(world, options.trajectory);
  SceneGeometry geometry;
  nlohmann::json robots = nlohmann::json::array();
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    robots.push_back(robotJson(world, r, initial[r], geometry));
  }
  nlohmann::json objects = nlohmann::json::array();
  for (std::size_t o = 0; o < world.description().objects.size(); ++o) {
    objects.push_back(objectJson(world, state, o, geometry));
  }
  nlohmann::json locations = nlohmann::json::array();
  for (const io::LocationSpec& location : world.description().locations) {
    locations.push_back(locationJson(location));
  }
  const nlohmann::json data{
      {"format", "kaboum-viewer"},  {"version", 1},
      {"title", options.title},     {"robots", robots},
      {"objects", objects},         {"locations", locations},
      {"root", plan.plan.root},     {"nodes", nodesJson(world, task, plan, initial, limits)},
      {"geometry", geometry.json()}};

  PlanPage page;
  page.html = fmt::format(
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>{}</title>\n</head>\n<body>\n"
      "<script type=\"application/json\" id=\"kaboum-data\">{}</script>\n"
      "<script>{}</script>\n</body>\n</html>\n",
      htmlEscaped(options.title), scriptSafe(data.dump()), viewerScript());
  PageSummary& summary = page.summary;
  summary.bytes = page.html.size();
  summary.meshes = geometry.meshCount();
  summary.pieces = geometry.pieceCount();
  for (const Node& node : plan.plan.nodes) {
    summary.actions += node.kind == Node::Kind::Action ? 1 : 0;
    summary.branches += node.kind == Node::Kind::Branch ? 1 : 0;
  }
  for (const exec::BranchTiming& branch :
       exec::branchTimings(plan, task, limits, exec::Profile::RestToRest)) {
    summary.duration = std::max(summary.duration, branch.seconds);
  }
  return page;
}

nlohmann::json linkPosesAt(const world::World& world, const symbolic::KnowledgeTask& task,
                           const tamp::PlanFileContents& plan, const PageOptions& options,
                           std::span<const double> times) {
  exec::ExecutionOptions execution;
  execution.trajectory = options.trajectory;
  execution.trajectory.profile = exec::Profile::RestToRest;
  execution.sensing = [](const exec::SensingQuery&) { return true; };
  const exec::ExecutionResult run = exec::execute(world, task, plan, execution);
  nlohmann::json out = nlohmann::json::array();
  for (const double time : times) {
    nlohmann::json robots = nlohmann::json::object();
    for (std::size_t r = 0; r < world.robots().size(); ++r) {
      const collision::RobotCollisionModel& robot = world.robots()[r].collision;
      const kinematics::RobotModel& model = robot.model();
      std::vector<double> q(run.schedule.dof(r)), qd(q.size()), qdd(q.size());
      run.schedule.sample(time, r, q, qd, qdd);
      std::vector<Pose> poses(model.links().size());
      model.linkPoses(q, poses);
      nlohmann::json links = nlohmann::json::object();
      for (std::size_t l = 0; l < poses.size(); ++l) {
        links[model.links()[l].name] = toJson(robot.basePose() * poses[l]);
      }
      robots[world.robots()[r].name] = links;
    }
    out.push_back({{"time", time}, {"robots", robots}});
  }
  return out;
}

}  // namespace kaboum::web
