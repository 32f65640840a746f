#include "kaboum/io/scene_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string_view>

#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/message_text.hpp"
#include "kaboum/io/moveit_scene.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"

namespace kaboum::io {

std::string SourceLocation::message(const std::string& what) const {
  return locate(file, key.empty() ? what : key + ": " + what, line, column);
}

void addAllowedPair(std::vector<AllowedPair>& pairs, AllowedPair pair) {
  const bool known = std::any_of(pairs.begin(), pairs.end(), [&](const AllowedPair& other) {
    return (other.first == pair.first && other.second == pair.second) ||
           (other.first == pair.second && other.second == pair.first);
  });
  if (!known) pairs.push_back(std::move(pair));
}

namespace {

namespace fs = std::filesystem;
using Names = std::vector<std::string>;

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return inQuotes(node.Scalar());
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a mapping";
    default:
      return "nothing";
  }
}

// A number as YAML writes it (also .inf, .nan), finite or not; nullopt if `text` is none.
std::optional<double> parseNumber(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const bool negative = !text.empty() && text.front() == '-';
  const std::string special = lowerCase(std::string(text.substr(negative ? 1 : 0)));
  if (special == ".inf") return negative ? -HUGE_VAL : HUGE_VAL;
  if (special == ".nan") return std::nan("");
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (end != text.data() + text.size() || end == text.data()) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    return std::strtod(std::string(text).c_str(), nullptr);
  }
  if (error != std::errc()) return std::nullopt;
  return value;
}

std::string formatLimits(const Joint& joint) {
  return fmt::format("[{:g}, {:g}]", joint.lower, joint.upper);
}

bool withinLimits(const Joint& joint, double value) {
  constexpr double kTolerance = 1e-9;
  return joint.type == JointType::Continuous ||
         (value >= joint.lower - kTolerance && value <= joint.upper + kTolerance);
}

// Whether the points span a volume: a tetrahedron built from farthest points has a height above
// a tiny fraction of their extent.
bool spansVolume(const std::vector<Vec3>& points) {
  const Vec3& a = points.front();
  const auto farthest = [&](const auto& distance) {
    return *std::max_element(points.begin(), points.end(), [&](const Vec3& p, const Vec3& q) {
      return distance(p) < distance(q);
    });
  };
  const Vec3 b = farthest([&](const Vec3& p) { return (p - a).norm(); });
  const double extent = (b - a).norm();
  if (extent == 0) return false;
  const Vec3 direction = (b - a) / extent;
  const Vec3 c = farthest([&](const Vec3& p) { return (p - a).cross(direction).norm(); });
  const Vec3 normal = (c - a).cross(direction);
  if (normal.norm() <= 1e-9 * extent) return false;
  const Vec3 unitNormal = normal.normalized();
  const Vec3 d = farthest([&](const Vec3& p) { return std::abs(unitNormal.dot(p - a)); });
  return std::abs(unitNormal.dot(d - a)) > 1e-9 * extent;
}

// The link whose frame `link` is rigidly attached to: its ancestors up to the first movable joint
// that is not a finger joint.
int rigidAnchor(const RobotModel& model, int link, const std::set<std::string>& fingerJoints) {
  for (;;) {
    const int parentJoint = model.links()[static_cast<std::size_t>(link)].parentJoint;
    if (parentJoint < 0) return link;
    const Joint& joint = model.joints()[static_cast<std::size_t>(parentJoint)];
    if (joint.movable() && !fingerJoints.contains(joint.name)) return link;
    link = joint.parentLink;
  }
}

// A YAML node, the key path that names it in messages ("objects[2].pose") and where messages
// point: the node, or its key when the value is empty (yaml-cpp places an empty value at the
// next token).
struct Entry {
  YAML::Node node;
  std::string key;
  YAML::Mark mark;
};

Entry child(const Entry& parent, const std::string& key, const YAML::Node& keyNode,
            const YAML::Node& node) {
  return {node, parent.key.empty() ? key : parent.key + "." + key,
          node.IsNull() ? keyNode.Mark() : node.Mark()};
}

Entry item(const Entry& parent, std::size_t index, const YAML::Node& node) {
  return {node, parent.key + "[" + std::to_string(index) + "]", node.Mark()};
}

// One key of a mapping: the key's own node (where messages about the key point) and its value.
struct Field {
  std::string name;
  Entry key;
  Entry value;
};

// The fields of a mapping, in file order.
struct Fields {
  Entry entry;
  std::vector<Field> list;

  [[nodiscard]] std::optional<Entry> find(std::string_view name) const {
    for (const Field& field : list) {
      if (field.name == name) return field.value;
    }
    return std::nullopt;
  }
  [[nodiscard]] bool has(std::string_view name) const { return find(name).has_value(); }
};

const Names kSceneKeys{"version", "settings", "robots", "objects", "locations"};
const Names kSettingsKeys{"epsilon",       "joint_step", "tool_step",
                          "sweep_epsilon", "seed",       "placement_seed"};
const Names kRobotKeys{"name",         "urdf",  "base_pose",          "home",
                       "joint_limits", "tools", "allowed_collisions", "srdf"};
const Names kJointLimitKeys{"velocity", "acceleration"};
const Names kToolKeys{"name", "link", "base_link", "tcp", "ik", "hand"};
const Names kIkMethods{"auto", "closed-form", "numeric"};
const Names kHandKeys{"links", "shapes", "fingers"};
const Names kFingerKeys{"open", "closed"};
const Names kObjectKeys{"name",    "geometry", "pose",         "place_in",
                        "movable", "grasps",   "resting_faces"};
const Names kGeometryKeys{"box", "cylinder", "sphere", "mesh", "pose"};
const Names kGeometryKinds{"box", "cylinder", "sphere", "mesh"};
const Names kGraspKeys{"name", "constraints", "pose", "free"};
const Names kConstraintKeys{"constraint", "hand", "object", "value"};
const Names kConstraintTypes{"coincident", "parallel", "perpendicular", "distance"};
const Names kFeatureKinds{"point", "line", "plane"};
const Names kBuiltinFeatures{"origin",   "x-axis",   "y-axis",  "z-axis",
                             "yz-plane", "zx-plane", "xy-plane"};
const Names kFreeMotions{"translate_x", "translate_y", "translate_z",
                         "rotate_x",    "rotate_y",    "rotate_z"};
const Names kPoseKeys{"position", "orientation"};
const Names kOrientationKeys{"quaternion", "rpy"};
const Names kLocationKeys{"name", "region", "support_surface"};
const Names kRegionKeys{"box", "hull", "pose"};
const Names kRegionBoxKeys{"size", "min", "max"};
// The entry of `joint_limits` that names no joint: limits of every joint that neither the file nor
// the URDF limits.
const std::string kDefaultLimits = "default";

class SceneReader {
 public:
  SceneReader(std::string sourceName, fs::path baseDir)
      : sourceName_(std::move(sourceName)), baseDir_(std::move(baseDir)) {}

  SceneDescription read(const YAML::Node& root) {
    if (root.IsNull()) {
      throw InputError(locate(sourceName_,
                              "empty scene: expected a mapping with robots, "
                              "objects, locations and settings"));
    }
    const Fields scene = fields({root, "", root.Mark()}, kSceneKeys);
    if (const auto version = scene.find("version")) {
      if (scalar(*version, "a version") != "1") {
        fail(*version, "unsupported version " + describe(version->node) + " (expected 1)");
      }
    }
    SceneDescription description;
    description.settings.source = where(scene.entry);
    if (const auto settings = scene.find("settings")) {
      description.settings = readSettings(*settings);
    }
    for (const Entry& robot : section(scene, "robots")) {
      description.robots.push_back(readRobot(robot));
    }
    for (const Entry& object : section(scene, "objects")) {
      description.objects.push_back(readObject(object, description.objects.size()));
    }
    for (const Entry& location : section(scene, "locations")) {
      description.locations.push_back(readLocation(location));
    }
    resolvePlaces(description);
    return description;
  }

 private:
  // ---- Locations in the file and messages.

  [[nodiscard]] SourceLocation where(const Entry& at) const {
    if (at.mark.is_null()) return {sourceName_, at.key, 0, 0};
    return {sourceName_, at.key, at.mark.line + 1L, at.mark.column + 1L};
  }

  [[noreturn]] void fail(const Entry& at, const std::string& what) const {
    throw InputError(where(at).message(what));
  }

  // ---- YAML structure.

  // The mapping `entry` with any keys, each a plain name given once.
  [[nodiscard]] Fields mapping(const Entry& entry) const {
    if (!entry.node.IsMap()) fail(entry, "expected a mapping, got " + describe(entry.node));
    Fields result{entry, {}};
    std::set<std::string> seen;
    for (auto it = entry.node.begin(); it != entry.node.end(); ++it) {
      const Entry key{it->first, entry.key, it->first.Mark()};
      if (!it->first.IsScalar()) fail(key, "expected a plain key, got " + describe(it->first));
      const std::string name = it->first.Scalar();
      if (!seen.insert(name).second) fail(key, "duplicate key " + inQuotes(name));
      result.list.push_back({name, key, child(entry, name, it->first, it->second)});
    }
    return result;
  }

  // The mapping `entry`, whose keys must be among `allowed`.
  [[nodiscard]] Fields fields(const Entry& entry, const Names& allowed) const {
    Fields result = mapping(entry);
    for (const Field& field : result.list) {
      if (std::find(allowed.begin(), allowed.end(), field.name) == allowed.end()) {
        fail(field.key, "unknown key " + inQuotes(field.name) + suggestion(field.name, allowed));
      }
    }
    return result;
  }

  [[nodiscard]] Entry required(const Fields& fields, const std::string& name) const {
    const auto found = fields.find(name);
    if (!found) fail(fields.entry, "missing key " + inQuotes(name));
    return *found;
  }

  // The one key of `kinds` that `fields` has.
  [[nodiscard]] std::string oneOf(const Fields& fields, const Names& kinds) const {
    std::vector<std::string> present;
    for (const std::string& kind : kinds) {
      if (fields.has(kind)) present.push_back(kind);
    }
    if (present.size() != 1) {
      std::string list;
      for (const std::string& kind : kinds) list += (list.empty() ? "" : ", ") + kind;
      fail(fields.entry, "expected exactly one of " + list + ", got " +
                             (present.empty() ? "none" : present[0] + " and " + present[1]));
    }
    return present.front();
  }

  [[nodiscard]] std::vector<Entry> sequence(const Entry& entry) const {
    if (!entry.node.IsSequence()) fail(entry, "expected a list, got " + describe(entry.node));
    std::vector<Entry> items;
    for (const YAML::Node& element : entry.node) {
      items.push_back(item(entry, items.size(), element));
    }
    return items;
  }

  // A top-level list; an empty one may be written as nothing.
  [[nodiscard]] std::vector<Entry> section(const Fields& scene, const std::string& name) const {
    const auto found = scene.find(name);
    if (!found || found->node.IsNull()) return {};
    return sequence(*found);
  }

  // ---- Scalars.

  [[nodiscard]] std::string scalar(const Entry& entry, const std::string& expected) const {
    if (!entry.node.IsScalar()) {
      fail(entry, "expected " + expected + ", got " + describe(entry.node));
    }
    return entry.node.Scalar();
  }

  // The finite number `digits` (the scalar of `entry`, or the part before its unit).
  [[nodiscard]] double finite(const Entry& entry, std::string_view digits,
                              const std::string& expected) const {
    const auto value = parseNumber(digits);
    if (!value) fail(entry, "expected " + expected + ", got " + inQuotes(entry.node.Scalar()));
    if (!std::isfinite(*value)) {
      fail(entry, inQuotes(entry.node.Scalar()) + " is not a finite number");
    }
    return *value;
  }

  double requirePositive(const Entry& entry, double value) const {
    if (!(value > 0)) fail(entry, "must be positive, got " + inQuotes(entry.node.Scalar()));
    return value;
  }

  [[nodiscard]] double number(const Entry& entry) const {
    return finite(entry, scalar(entry, "a number"), "a number");
  }

  [[nodiscard]] double positive(const Entry& entry) const {
    return requirePositive(entry, number(entry));
  }

  // Radians, or degrees with the suffix deg ("90deg", "-45 deg").
  [[nodiscard]] double angle(const Entry& entry) const {
    const std::string text = scalar(entry, "an angle");
    std::string_view digits = text;
    const bool degrees = digits.ends_with("deg");
    if (degrees) {
      digits.remove_suffix(3);
      while (!digits.empty() && digits.back() == ' ') digits.remove_suffix(1);
    }
    const double value = finite(entry, digits, "an angle (radians, or degrees as in 90deg)");
    return degrees ? value * std::numbers::pi / 180 : value;
  }

  [[nodiscard]] bool boolean(const Entry& entry) const {
    const std::string text = lowerCase(scalar(entry, "true or false"));
    if (text != "true" && text != "false") {
      fail(entry, "expected true or false, got " + describe(entry.node));
    }
    return text == "true";
  }

  // The index of the value of `entry` among `choices`.
  [[nodiscard]] std::size_t choice(const Entry& entry, const Names& choices) const {
    const std::string text = scalar(entry, "a name");
    const auto found = std::find(choices.begin(), choices.end(), text);
    if (found == choices.end()) {
      fail(entry, "unknown value " + inQuotes(text) + suggestion(text, choices));
    }
    return static_cast<std::size_t>(found - choices.begin());
  }

  // A list of three values, each read by `read`.
  template <typename Read>
  [[nodiscard]] Vec3 triple(const Entry& entry, const Read& read) const {
    const std::vector<Entry> items = sequence(entry);
    if (items.size() != 3) fail(entry, fmt::format("expected 3 numbers, got {}", items.size()));
    return {read(items[0]), read(items[1]), read(items[2])};
  }

  [[nodiscard]] Vec3 vec3(const Entry& entry) const {
    return triple(entry, [&](const Entry& value) { return number(value); });
  }

  [[nodiscard]] Vec3 positiveVec3(const Entry& entry) const {
    return triple(entry, [&](const Entry& value) { return positive(value); });
  }

  // A non-zero vector, normalized.
  [[nodiscard]] Vec3 direction(const Entry& entry) const {
    const Vec3 value = vec3(entry);
    const double length = value.stableNorm();
    if (length == 0) fail(entry, "zero vector");
    return value / length;
  }

  // A file name, resolved against the scene file's folder.
  [[nodiscard]] std::string filePath(const Entry& entry) const {
    const std::string text = scalar(entry, "a file name");
    if (text.empty()) fail(entry, "empty file name");
    const fs::path path(text);
    return (path.is_absolute() ? path : baseDir_ / path).lexically_normal().string();
  }

  // A name in the scene's one name space (robots, tools, objects, locations), compared without
  // case as PDDL does.
  std::string claimName(const Entry& entry) {
    const std::string name = symbol(entry);
    const auto [previous, added] = names_.emplace(lowerCase(name), where(entry));
    if (!added) {
      fail(entry, fmt::format("duplicate name '{}' (also {} at line {})", name,
                              previous->second.key, previous->second.line));
    }
    return name;
  }

  // A name usable as a PDDL symbol.
  [[nodiscard]] std::string symbol(const Entry& entry) const {
    const std::string name = scalar(entry, "a name");
    const bool valid = !name.empty() && std::isalpha(static_cast<unsigned char>(name.front())) &&
                       std::all_of(name.begin(), name.end(), [](unsigned char c) {
                         return std::isalnum(c) || c == '-' || c == '_';
                       });
    if (!valid) {
      fail(entry, "name " + inQuotes(name) +
                      " must start with a letter and hold only letters, digits, '-' and '_'");
    }
    return name;
  }

  // ---- Poses.

  [[nodiscard]] Pose pose(const Entry& entry) const {
    const Fields f = fields(entry, kPoseKeys);
    Pose result = Pose::Identity();
    if (const auto position = f.find("position")) result.translation() = vec3(*position);
    if (const auto orientation = f.find("orientation")) result.linear() = rotation(*orientation);
    return result;
  }

  [[nodiscard]] Eigen::Matrix3d rotation(const Entry& entry) const {
    const Fields f = fields(entry, kOrientationKeys);
    if (oneOf(f, kOrientationKeys) == "quaternion") {
      const Entry values = required(f, "quaternion");
      const std::vector<Entry> items = sequence(values);
      if (items.size() != 4) {
        fail(values, fmt::format("expected 4 numbers [w, x, y, z], got {}", items.size()));
      }
      const Eigen::Quaterniond q(number(items[0]), number(items[1]), number(items[2]),
                                 number(items[3]));
      const double norm = q.coeffs().stableNorm();  // no overflow for huge components
      if (norm == 0) fail(entry, "zero quaternion");
      return Eigen::Quaterniond(q.coeffs() / norm).toRotationMatrix();
    }
    const Entry values = required(f, "rpy");
    const std::vector<Entry> items = sequence(values);
    if (items.size() != 3) {
      fail(values, fmt::format("expected 3 angles [roll, pitch, yaw], got {}", items.size()));
    }
    return (Eigen::AngleAxisd(angle(items[2]), Vec3::UnitZ()) *
            Eigen::AngleAxisd(angle(items[1]), Vec3::UnitY()) *
            Eigen::AngleAxisd(angle(items[0]), Vec3::UnitX()))
        .toRotationMatrix();
  }

  // ---- Geometry.

  [[nodiscard]] Geometry geometry(const Entry& entry) const {
    const Fields f = fields(entry, kGeometryKeys);
    Geometry result{{}, where(entry)};
    CollisionShape& shape = result.shape;
    if (const auto placement = f.find("pose")) shape.origin = pose(*placement);
    const std::string kind = oneOf(f, kGeometryKinds);
    const Entry parameters = required(f, kind);
    if (kind == "box") {
      shape.kind = CollisionShape::Kind::Box;
      shape.size = positiveVec3(required(fields(parameters, {"size"}), "size"));
    } else if (kind == "cylinder") {
      const Fields cylinder = fields(parameters, {"radius", "length"});
      shape.kind = CollisionShape::Kind::Cylinder;
      shape.radius = positive(required(cylinder, "radius"));
      shape.length = positive(required(cylinder, "length"));
    } else if (kind == "sphere") {
      shape.kind = CollisionShape::Kind::Sphere;
      shape.radius = positive(required(fields(parameters, {"radius"}), "radius"));
    } else {
      const Fields mesh = fields(parameters, {"file", "scale"});
      shape.kind = CollisionShape::Kind::Mesh;
      const Entry file = required(mesh, "file");
      shape.meshPath = filePath(file);
      shape.size = Vec3::Ones();
      if (const auto scale = mesh.find("scale")) {
        shape.size =
            scale->node.IsScalar() ? Vec3::Constant(positive(*scale)) : positiveVec3(*scale);
      }
      try {
        readMesh(shape.meshPath);
      } catch (const InputError& e) {
        fail(file, e.what());
      }
    }
    return result;
  }

  // ---- Settings.

  [[nodiscard]] SceneSettings readSettings(const Entry& entry) const {
    const Fields f = fields(entry, kSettingsKeys);
    SceneSettings settings;
    settings.source = where(entry);
    if (const auto epsilon = f.find("epsilon")) {
      const std::string text = scalar(*epsilon, "a distance or a percentage");
      settings.epsilonRelative = text.ends_with('%');
      const std::string_view digits(text.data(), text.size() - (settings.epsilonRelative ? 1 : 0));
      const double value = requirePositive(
          *epsilon, finite(*epsilon, digits, "a distance (0.01) or a percentage (1%)"));
      if (settings.epsilonRelative && value > 100) {
        fail(*epsilon, "a relative epsilon must be at most 100%, got " + inQuotes(text));
      }
      settings.epsilon = settings.epsilonRelative ? value / 100 : value;
    }
    if (const auto step = f.find("joint_step")) {
      settings.jointStep = requirePositive(*step, angle(*step));
    }
    if (const auto step = f.find("tool_step")) settings.toolStep = positive(*step);
    if (const auto bound = f.find("sweep_epsilon")) settings.sweepEpsilon = positive(*bound);
    if (const auto seed = f.find("seed")) settings.seed = seedValue(*seed);
    if (const auto seed = f.find("placement_seed")) settings.placementSeed = seedValue(*seed);
    return settings;
  }

  [[nodiscard]] std::uint64_t seedValue(const Entry& entry) const {
    const std::string text = scalar(entry, "a non-negative integer");
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
      fail(entry, "expected a non-negative integer, got " + inQuotes(text));
    }
    return value;
  }

  // ---- Robots.

  RobotSpec readRobot(const Entry& entry) {
    const Fields f = fields(entry, kRobotKeys);
    RobotSpec robot;
    robot.source = where(entry);
    robot.homeSource = robot.source;
    robot.name = claimName(required(f, "name"));
    const Entry urdf = required(f, "urdf");
    robot.urdf = filePath(urdf);
    const RobotModel model = loadRobot(urdf, robot.urdf);
    if (const auto base = f.find("base_pose")) robot.base = pose(*base);
    for (int variable = 0; variable < model.dof(); ++variable) {
      const Joint& joint = model.variableJoint(variable);
      JointSpec spec{joint.name, 0, std::nullopt, std::nullopt};
      if (joint.maxVelocity > 0) spec.maxVelocity = joint.maxVelocity;
      robot.joints.push_back(spec);
    }
    const auto home = f.find("home");
    if (home) robot.homeSource = where(*home);
    readHome(home.value_or(entry), home.has_value(), model, robot.joints);
    if (const auto limits = f.find("joint_limits")) readJointLimits(*limits, model, robot.joints);
    if (const auto tools = f.find("tools")) {
      for (const Entry& tool : sequence(*tools)) robot.tools.push_back(readTool(tool, model));
    }
    if (const auto pairs = f.find("allowed_collisions")) {
      for (const Entry& pair : sequence(*pairs)) {
        const std::vector<Entry> links = sequence(pair);
        if (links.size() != 2) {
          fail(pair, fmt::format("expected two links [a, b], got {}", links.size()));
        }
        const auto nameOf = [&](const Entry& link) {
          return model.links()[static_cast<std::size_t>(linkNamed(link, model))].name;
        };
        addAllowedPair(robot.allowedCollisions, {nameOf(links[0]), nameOf(links[1])});
      }
    }
    if (const auto srdf = f.find("srdf")) {
      const std::string path = filePath(*srdf);
      std::vector<AllowedPair> pairs;
      try {
        pairs = readSrdfAllowedPairs(path, model);
      } catch (const InputError& e) {
        fail(*srdf, e.what());
      }
      for (AllowedPair& pair : pairs) addAllowedPair(robot.allowedCollisions, std::move(pair));
    }
    return robot;
  }

  [[nodiscard]] RobotModel loadRobot(const Entry& entry, const std::string& path) const {
    try {
      return loadUrdf(path);
    } catch (const InputError& e) {
      fail(entry, e.what());
    }
  }

  // The configuration variable of the joint named by `entry` (a key of a joint mapping).
  [[nodiscard]] int variableNamed(const Entry& entry, const std::string& name,
                                  const RobotModel& model) const {
    Names movable;
    for (int variable = 0; variable < model.dof(); ++variable) {
      if (model.variableJoint(variable).name == name) return variable;
      movable.push_back(model.variableJoint(variable).name);
    }
    const bool fixed = std::any_of(model.joints().begin(), model.joints().end(),
                                   [&](const Joint& joint) { return joint.name == name; });
    if (fixed) fail(entry, "joint " + inQuotes(name) + " is fixed");
    fail(entry, "unknown joint " + inQuotes(name) + suggestion(name, movable));
  }

  [[nodiscard]] int linkNamed(const Entry& entry, const RobotModel& model) const {
    const std::string name = scalar(entry, "a link name");
    if (const auto link = model.findLink(name)) return *link;
    Names links;
    for (const Link& link : model.links()) links.push_back(link.name);
    fail(entry, "unknown link " + inQuotes(name) + suggestion(name, links));
  }

  // A joint position within the joint's limits: an angle for a revolute joint, metres for a
  // prismatic one.
  [[nodiscard]] double jointValue(const Entry& entry, const Joint& joint) const {
    const bool prismatic = joint.type == JointType::Prismatic;
    const double value = prismatic ? number(entry) : angle(entry);
    if (!withinLimits(joint, value)) {
      fail(entry, fmt::format("{:g} is outside the limits {} of joint '{}'", value,
                              formatLimits(joint), joint.name));
    }
    return value;
  }

  // The home configuration from the `home` entry if `given`, else all zeros; `entry` is where
  // messages point.
  void readHome(const Entry& entry, bool given, const RobotModel& model,
                std::vector<JointSpec>& joints) const {
    std::set<int> listed;
    if (given) {
      for (const Field& field : mapping(entry).list) {
        const int variable = variableNamed(field.key, field.name, model);
        joints[static_cast<std::size_t>(variable)].home =
            jointValue(field.value, model.variableJoint(variable));
        listed.insert(variable);
      }
    }
    for (int variable = 0; variable < model.dof(); ++variable) {
      const Joint& joint = model.variableJoint(variable);
      if (!listed.contains(variable) && !withinLimits(joint, 0)) {
        fail(entry, "joint '" + joint.name +
                        "' is not listed in home and 0 is outside its limits " +
                        formatLimits(joint));
      }
    }
  }

  void readJointLimits(const Entry& entry, const RobotModel& model,
                       std::vector<JointSpec>& joints) const {
    struct Limits {
      std::optional<double> velocity, acceleration;
    };
    std::map<int, Limits> named;
    Limits fallback;
    for (const Field& field : mapping(entry).list) {
      const Fields values = fields(field.value, kJointLimitKeys);
      Limits limits;
      if (const auto velocity = values.find("velocity")) limits.velocity = positive(*velocity);
      if (const auto acceleration = values.find("acceleration")) {
        limits.acceleration = positive(*acceleration);
      }
      if (field.name == kDefaultLimits) {
        fallback = limits;
      } else {
        named[variableNamed(field.key, field.name, model)] = limits;
      }
    }
    for (std::size_t variable = 0; variable < joints.size(); ++variable) {
      JointSpec& joint = joints[variable];
      const auto found = named.find(static_cast<int>(variable));
      const Limits own = found == named.end() ? Limits{} : found->second;
      if (own.velocity) joint.maxVelocity = own.velocity;
      if (!joint.maxVelocity) joint.maxVelocity = fallback.velocity;
      joint.maxAcceleration = own.acceleration ? own.acceleration : fallback.acceleration;
    }
  }

  ToolSpec readTool(const Entry& entry, const RobotModel& model) {
    const Fields f = fields(entry, kToolKeys);
    ToolSpec tool;
    tool.source = where(entry);
    tool.name = claimName(required(f, "name"));
    const Entry link = required(f, "link");
    tool.link = model.links()[static_cast<std::size_t>(linkNamed(link, model))].name;
    const auto base = f.find("base_link");
    if (base) tool.baseLink = model.links()[static_cast<std::size_t>(linkNamed(*base, model))].name;
    const KinematicChain chain = toolChain(base ? *base : link, model, tool);
    if (const auto tcp = f.find("tcp")) tool.tcp = pose(*tcp);
    if (const auto ik = f.find("ik")) {
      tool.ik = std::array{IkMethod::Auto, IkMethod::ClosedForm,
                           IkMethod::Numeric}[choice(*ik, kIkMethods)];
      if (tool.ik == IkMethod::ClosedForm && !ArmIk::fit(chain)) {
        fail(*ik, "the chain to '" + tool.link +
                      "' is not a five- or six-axis arm of Appendix A.3; use numeric or auto");
      }
    }
    if (const auto hand = f.find("hand")) tool.hand = readHand(*hand, model, chain, tool.link);
    return tool;
  }

  [[nodiscard]] KinematicChain toolChain(const Entry& entry, const RobotModel& model,
                                         const ToolSpec& tool) const {
    std::optional<KinematicChain> chain;
    try {
      chain.emplace(model, tool.link, tool.baseLink);
    } catch (const InputError&) {
      fail(entry, "link " + inQuotes(tool.baseLink) + " is not an ancestor of the tool link " +
                      inQuotes(tool.link));
    }
    if (chain->dof() == 0) {
      fail(entry, "no movable joint leads to the tool link " + inQuotes(tool.link));
    }
    return *chain;
  }

  [[nodiscard]] HandSpec readHand(const Entry& entry, const RobotModel& model,
                                  const KinematicChain& chain, const std::string& toolLink) const {
    const Fields f = fields(entry, kHandKeys);
    if (!f.has("links") && !f.has("shapes")) fail(entry, "a hand needs links or shapes");
    HandSpec hand;
    std::set<std::string> fingerJoints;
    if (const auto fingers = f.find("fingers")) {
      hand.fingers = readFingers(*fingers, model, chain);
      for (const auto& [joint, value] : hand.fingers->open) fingerJoints.insert(joint);
    }
    if (const auto links = f.find("links")) {
      const int toolAnchor = rigidAnchor(model, *model.findLink(toolLink), fingerJoints);
      for (const Entry& link : sequence(*links)) {
        const int index = linkNamed(link, model);
        const std::string& name = model.links()[static_cast<std::size_t>(index)].name;
        if (std::find(hand.links.begin(), hand.links.end(), name) != hand.links.end()) {
          fail(link, "link " + inQuotes(name) + " is listed twice");
        }
        if (rigidAnchor(model, index, fingerJoints) != toolAnchor) {
          fail(link, "link " + inQuotes(name) + " does not move with the tool link " +
                         inQuotes(toolLink) + " (only finger joints may lie between them)");
        }
        hand.links.push_back(name);
      }
    }
    if (const auto shapes = f.find("shapes")) {
      for (const Entry& shape : sequence(*shapes)) hand.shapes.push_back(geometry(shape));
    }
    return hand;
  }

  [[nodiscard]] FingerStates readFingers(const Entry& entry, const RobotModel& model,
                                         const KinematicChain& chain) const {
    const Fields f = fields(entry, kFingerKeys);
    const auto positionsOf = [&](const Entry& values) {
      std::map<std::string, double> positions;
      for (const Field& field : mapping(values).list) {
        const Joint& joint = model.variableJoint(variableNamed(field.key, field.name, model));
        for (int i = 0; i < chain.dof(); ++i) {
          if (chain.joint(i).name == joint.name) {
            fail(field.key, "joint " + inQuotes(joint.name) + " moves the arm, not a finger");
          }
        }
        positions[joint.name] = jointValue(field.value, joint);
      }
      if (positions.empty()) fail(values, "no finger joints");
      return positions;
    };
    const Entry open = required(f, "open");
    const Entry closed = required(f, "closed");
    FingerStates fingers{positionsOf(open), positionsOf(closed)};
    for (const auto& [joint, value] : fingers.open) {
      if (!fingers.closed.contains(joint)) {
        fail(closed, "joint " + inQuotes(joint) + " has no closed value");
      }
    }
    for (const auto& [joint, value] : fingers.closed) {
      if (!fingers.open.contains(joint)) {
        fail(open, "joint " + inQuotes(joint) + " has no open value");
      }
    }
    return fingers;
  }

  // ---- Objects.

  ObjectSpec readObject(const Entry& entry, std::size_t index) {
    const Fields f = fields(entry, kObjectKeys);
    ObjectSpec object;
    object.source = where(entry);
    object.poseSource = object.source;
    object.name = claimName(required(f, "name"));
    object.geometry = geometry(required(f, "geometry"));
    if (const auto placement = f.find("pose")) {
      object.pose = pose(*placement);
      object.poseSource = where(*placement);
    }
    if (const auto place = f.find("place_in")) {
      if (f.has("pose")) fail(*place, "an object has a pose or place_in, not both");
      placesIn_.push_back({index, symbol(*place), *place});
      object.poseSource = where(*place);
    }
    if (const auto movable = f.find("movable")) object.movable = boolean(*movable);
    for (const char* key : {"grasps", "resting_faces", "place_in"}) {
      if (const auto found = f.find(key); found && !object.movable) {
        fail(*found, "only a movable object has " + std::string(key) + " (set movable: true)");
      }
    }
    if (const auto grasps = f.find("grasps")) {
      std::set<std::string> names;
      for (const Entry& grasp : sequence(*grasps)) {
        object.grasps.push_back(readGrasp(grasp));
        if (!names.insert(lowerCase(object.grasps.back().name)).second) {
          fail(grasp, "duplicate grasp name " + inQuotes(object.grasps.back().name));
        }
      }
    }
    if (const auto faces = f.find("resting_faces")) object.restingFaces = restingFaces(*faces);
    return object;
  }

  [[nodiscard]] GraspSpec readGrasp(const Entry& entry) const {
    const Fields f = fields(entry, kGraspKeys);
    GraspSpec grasp;
    grasp.source = where(entry);
    grasp.name = symbol(required(f, "name"));
    if (oneOf(f, {"constraints", "pose"}) == "constraints") {
      if (const auto free = f.find("free")) fail(*free, "free motions belong to a grasp pose");
      std::vector<GraspConstraint> constraints;
      const Entry list = required(f, "constraints");
      for (const Entry& constraint : sequence(list)) {
        constraints.push_back(graspConstraint(constraint));
      }
      if (constraints.empty()) fail(list, "no constraints");
      grasp.definition = std::move(constraints);
      return grasp;
    }
    GraspPose graspPose{pose(required(f, "pose")), {}};
    if (const auto free = f.find("free")) {
      for (const Field& field : fields(*free, kFreeMotions).list) {
        const bool rotation = field.name.starts_with("rotate");
        const std::vector<Entry> range = sequence(field.value);
        if (range.size() != 2) {
          fail(field.value, fmt::format("expected [lower, upper], got {} values", range.size()));
        }
        FreeMotion motion{rotation ? FreeMotion::Kind::Rotation : FreeMotion::Kind::Translation,
                          field.name.back() - 'x', rotation ? angle(range[0]) : number(range[0]),
                          rotation ? angle(range[1]) : number(range[1])};
        if (motion.lower > motion.upper) fail(field.value, "lower bound above upper bound");
        graspPose.free.push_back(motion);
      }
    }
    grasp.definition = graspPose;
    return grasp;
  }

  [[nodiscard]] GraspConstraint graspConstraint(const Entry& entry) const {
    const Fields f = fields(entry, kConstraintKeys);
    GraspConstraint constraint;
    constraint.type = std::array{
        ConstraintType::Coincident, ConstraintType::Parallel, ConstraintType::Perpendicular,
        ConstraintType::Distance}[choice(required(f, "constraint"), kConstraintTypes)];
    constraint.hand = feature(required(f, "hand"));
    constraint.object = feature(required(f, "object"));
    try {
      costFunctionFor(constraint.type, constraint.hand.kind, constraint.object.kind);
    } catch (const InputError& e) {
      try {
        costFunctionFor(constraint.type, constraint.object.kind, constraint.hand.kind);
      } catch (const InputError&) {
        fail(entry, e.what());
      }
    }
    const auto value = f.find("value");
    if (constraint.type != ConstraintType::Distance) {
      if (value) fail(*value, "only a distance constraint takes a value");
      return constraint;
    }
    if (!value) fail(entry, "missing key 'value' (the distance in metres)");
    constraint.distance = number(*value);
    if (constraint.distance < 0) {
      fail(*value, "must not be negative, got " + inQuotes(value->node.Scalar()));
    }
    return constraint;
  }

  // A Table 5.1 primitive: a built-in feature of the frame (its origin, axes and coordinate
  // planes) or a point, line or plane given in it.
  [[nodiscard]] PrimitiveShape feature(const Entry& entry) const {
    if (entry.node.IsScalar()) {
      // kBuiltinFeatures: the origin, the x, y, z axes, the planes with normals x, y, z.
      const auto index = static_cast<Eigen::Index>(choice(entry, kBuiltinFeatures));
      if (index == 0) return PrimitiveShape::makePoint(Vec3::Zero());
      if (index <= 3) return PrimitiveShape::makeLine(Vec3::Zero(), Vec3::Unit(index - 1));
      return PrimitiveShape::makePlane(Vec3::Zero(), Vec3::Unit(index - 4));
    }
    const Fields f = fields(entry, kFeatureKinds);
    const std::string kind = oneOf(f, kFeatureKinds);
    if (kind == "point") return PrimitiveShape::makePoint(vec3(required(f, "point")));
    const Fields parameters =
        fields(required(f, kind), {"point", kind == "line" ? "direction" : "normal"});
    const Vec3 point = vec3(required(parameters, "point"));
    if (kind == "line") {
      return PrimitiveShape::makeLine(point, direction(required(parameters, "direction")));
    }
    return PrimitiveShape::makePlane(point, direction(required(parameters, "normal")));
  }

  [[nodiscard]] RestingFaces restingFaces(const Entry& entry) const {
    if (entry.node.IsScalar()) {
      if (entry.node.Scalar() != "auto") {
        fail(entry, "expected auto or a list of face normals, got " + describe(entry.node));
      }
      return {};
    }
    RestingFaces faces{false, {}};
    for (const Entry& normal : sequence(entry)) faces.normals.push_back(direction(normal));
    if (faces.normals.empty()) fail(entry, "no face normals (write auto to find them)");
    return faces;
  }

  // ---- Locations.

  LocationSpec readLocation(const Entry& entry) {
    const Fields f = fields(entry, kLocationKeys);
    LocationSpec location;
    location.source = where(entry);
    location.name = claimName(required(f, "name"));
    location.region = region(required(f, "region"));
    if (const auto support = f.find("support_surface")) location.supportSurface = boolean(*support);
    return location;
  }

  [[nodiscard]] std::variant<BoxRegion, HullRegion> region(const Entry& entry) const {
    const Fields f = fields(entry, kRegionKeys);
    const Pose frame = f.has("pose") ? pose(required(f, "pose")) : Pose::Identity();
    if (oneOf(f, {"box", "hull"}) == "hull") {
      const Entry list = required(f, "hull");
      HullRegion hull{frame, {}};
      for (const Entry& point : sequence(list)) hull.points.push_back(vec3(point));
      if (hull.points.size() < 4 || !spansVolume(hull.points)) {
        fail(list, "the points span no volume (at least four points, not all in one plane)");
      }
      return hull;
    }
    const Fields box = fields(required(f, "box"), kRegionBoxKeys);
    if (box.has("size") == (box.has("min") || box.has("max"))) {
      fail(box.entry, "expected size, or min and max");
    }
    if (const auto size = box.find("size")) {
      const Vec3 extent = positiveVec3(*size);
      return BoxRegion{frame, -extent / 2, extent / 2};
    }
    const Entry min = required(box, "min");
    const Entry max = required(box, "max");
    BoxRegion result{frame, vec3(min), vec3(max)};
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      if (!(result.lower[axis] < result.upper[axis])) {
        fail(max, fmt::format("must exceed min in every coordinate ({} is not above {})",
                              result.upper[axis], result.lower[axis]));
      }
    }
    return result;
  }

  // Each object's `place_in`, once the locations are read: the index of the location it names.
  void resolvePlaces(SceneDescription& description) const {
    std::vector<std::string> locations;
    for (const LocationSpec& location : description.locations) locations.push_back(location.name);
    for (const PlaceIn& place : placesIn_) {
      const auto found = std::find_if(locations.begin(), locations.end(), [&](const auto& name) {
        return lowerCase(name) == lowerCase(place.location);
      });
      if (found == locations.end()) {
        fail(place.entry, "unknown location " + inQuotes(place.location) +
                              suggestion(place.location, locations));
      }
      description.objects[place.object].placeIn =
          static_cast<std::size_t>(found - locations.begin());
    }
  }

  // A `place_in` as written (object index, location name), resolved once the locations are read.
  struct PlaceIn {
    std::size_t object = 0;
    std::string location;
    Entry entry;
  };

  std::string sourceName_;
  fs::path baseDir_;
  std::map<std::string, SourceLocation> names_;  // lower-case name → where it was first given
  std::vector<PlaceIn> placesIn_;                // in object order
};

}  // namespace

SceneDescription parseSceneText(const std::string& text, const std::string& sourceName,
                                const std::string& baseDir) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(
        locate(sourceName, "invalid YAML: " + e.msg, e.mark.line + 1L, e.mark.column + 1L));
  }
  return SceneReader(sourceName, baseDir).read(root);
}

std::string epsilonSetting(const SceneSettings& settings) {
  return settings.epsilonRelative ? fmt::format("{:g}%", 100 * settings.epsilon)
                                  : fmt::format("{:g}", settings.epsilon);
}

SceneDescription readSceneFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) throw InputError(locate(path, "cannot open file"));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(locate(path, "cannot read file"));
  return parseSceneText(text, path, fs::path(path).parent_path().string());
}

}  // namespace kaboum::io
