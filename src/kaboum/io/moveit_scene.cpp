#include "kaboum/io/moveit_scene.hpp"

#include <fmt/format.h>
#include <tinyxml.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>

#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/io/message_text.hpp"
#include "kaboum/io/urdf_loader.hpp"

namespace kaboum::io {

namespace {

namespace fs = std::filesystem;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) throw InputError(locate(path, "cannot open file"));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(locate(path, "cannot read file"));
  return text;
}

std::vector<std::string> linkNames(const RobotModel& model) {
  std::vector<std::string> names;
  for (const Link& link : model.links()) names.push_back(link.name);
  return names;
}

// A node of a YAML file and the key path that names it in messages ("world.collision_objects[2]").
struct Node {
  YAML::Node node;
  std::string key;
};

// One YAML file of MoveIt's: its nodes by key path, and one-line errors that name the file, the
// node's line and column, and its key. Keys it does not ask for are ignored.
class YamlFile {
 public:
  explicit YamlFile(const fs::path& path) : name_(path.string()) {
    const std::string text = readText(name_);
    try {
      root_ = YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw InputError(
          locate(name_, "invalid YAML: " + e.msg, e.mark.line + 1L, e.mark.column + 1L));
    }
    if (!root_.IsMap()) throw InputError(locate(name_, "expected a mapping at the top level"));
  }

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] Node root() const { return {root_, ""}; }

  [[nodiscard]] SourceLocation where(const Node& at) const {
    const YAML::Mark mark = at.node.Mark();
    if (mark.is_null()) return {name_, at.key, 0, 0};
    return {name_, at.key, mark.line + 1L, mark.column + 1L};
  }

  [[noreturn]] void fail(const Node& at, const std::string& what) const {
    throw InputError(where(at).message(what));
  }

  // The value of `key` in the mapping `parent`, unless it is missing or empty.
  [[nodiscard]] std::optional<Node> find(const Node& parent, const std::string& key) const {
    if (!parent.node.IsMap()) fail(parent, "expected a mapping");
    const YAML::Node value = parent.node[key];
    if (!value || value.IsNull()) return std::nullopt;
    return Node{value, parent.key.empty() ? key : parent.key + "." + key};
  }

  [[nodiscard]] Node at(const Node& parent, const std::string& key) const {
    if (auto found = find(parent, key)) return *found;
    fail(parent, "missing key " + inQuotes(key));
  }

  [[nodiscard]] std::vector<Node> list(const Node& entry) const {
    if (!entry.node.IsSequence()) fail(entry, "expected a list");
    std::vector<Node> items;
    for (const YAML::Node& item : entry.node) {
      items.push_back({item, entry.key + "[" + std::to_string(items.size()) + "]"});
    }
    return items;
  }

  // A list of exactly `count` entries (`what` names them in the message).
  [[nodiscard]] std::vector<Node> listOf(const Node& entry, std::size_t count,
                                         const std::string& what) const {
    std::vector<Node> items = list(entry);
    if (items.size() != count) {
      fail(entry, fmt::format("expected {} {}, got {}", count, what, items.size()));
    }
    return items;
  }

  [[nodiscard]] std::string text(const Node& entry) const {
    if (!entry.node.IsScalar()) fail(entry, "expected a name");
    return entry.node.Scalar();
  }

  [[nodiscard]] double number(const Node& entry) const {
    double value = 0;
    if (!entry.node.IsScalar() || !YAML::convert<double>::decode(entry.node, value)) {
      fail(entry, "expected a number");
    }
    if (!std::isfinite(value))
      fail(entry, inQuotes(entry.node.Scalar()) + " is not a finite number");
    return value;
  }

  [[nodiscard]] bool boolean(const Node& entry) const {
    bool value = false;
    if (!entry.node.IsScalar() || !YAML::convert<bool>::decode(entry.node, value)) {
      fail(entry, "expected true or false");
    }
    return value;
  }

  // A vector written as a list [x, y, z(, w)] or a mapping {x:, y:, z:(, w:)}.
  [[nodiscard]] Eigen::VectorXd components(const Node& entry, std::size_t count) const {
    static const std::vector<std::string> kAxes{"x", "y", "z", "w"};
    Eigen::VectorXd values(static_cast<Eigen::Index>(count));
    const bool listed = entry.node.IsSequence();
    const std::vector<Node> items = listed ? listOf(entry, count, "numbers") : std::vector<Node>{};
    for (std::size_t i = 0; i < count; ++i) {
      values[static_cast<Eigen::Index>(i)] = number(listed ? items[i] : at(entry, kAxes[i]));
    }
    return values;
  }

  // A pose {position, orientation}: the position [x, y, z], the orientation a quaternion
  // [x, y, z, w] (ROS's order), normalized; both optional.
  [[nodiscard]] Pose pose(const Node& entry, const char* positionKey = "position",
                          const char* orientationKey = "orientation") const {
    Pose result = Pose::Identity();
    if (const auto position = find(entry, positionKey)) {
      result.translation() = components(*position, 3);
    }
    if (const auto orientation = find(entry, orientationKey)) {
      const Eigen::VectorXd q = components(*orientation, 4);
      const double norm = q.stableNorm();
      if (norm == 0) fail(*orientation, "zero quaternion");
      result.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
    }
    return result;
  }

 private:
  std::string name_;
  YAML::Node root_;
};

bool isIdentity(const Pose& pose) {
  constexpr double kTolerance = 1e-9;
  return (pose.matrix() - Pose::Identity().matrix()).cwiseAbs().maxCoeff() <= kTolerance;
}

// The robot's joint values by configuration variable, as far as files have set them.
using PartialConfiguration = std::vector<std::optional<double>>;

bool withinLimits(const Joint& joint, double value) {
  constexpr double kTolerance = 1e-9;
  return joint.type == JointType::Continuous ||
         (value >= joint.lower - kTolerance && value <= joint.upper + kTolerance);
}

class ProblemReader {
 public:
  ProblemReader(const MoveItRobot& robot, const fs::path& sceneYaml, const fs::path& requestYaml)
      : robot_(robot),
        model_(loadUrdf(robot.urdf.string())),
        scene_(sceneYaml),
        request_(requestYaml) {
    checkGroup();
  }

  MotionProblem read() {
    MotionProblem problem;
    problem.name = (sceneYaml().parent_path().filename() / sceneYaml().stem()).string();
    problem.robot = model_.name();
    SceneDescription& description = problem.scene;
    description.settings.source = scene_.where(scene_.root());
    RobotSpec spec;
    spec.name = model_.name();
    spec.urdf = robot_.urdf.string();
    spec.source = scene_.where(scene_.root());
    if (!robot_.srdf.empty()) {
      spec.allowedCollisions = readSrdfAllowedPairs(robot_.srdf.string(), model_);
    }
    checkRobotName();
    description.objects = readObjects();
    readAllowedCollisionMatrix(description.objects, spec.allowedCollisions);

    checkGroupName();
    PartialConfiguration configuration(static_cast<std::size_t>(model_.dof()));
    if (const auto state = scene_.find(scene_.root(), "robot_state")) {
      readRobotState(scene_, *state, configuration);
    }
    const Node start = request_.at(request_.root(), "start_state");
    readRobotState(request_, start, configuration);
    spec.homeSource = request_.where(start);
    problem.start = complete(configuration, start);
    problem.goal = readGoal(problem.start);

    for (int variable = 0; variable < model_.dof(); ++variable) {
      const Joint& joint = model_.variableJoint(variable);
      JointSpec jointSpec{joint.name, problem.start[static_cast<std::size_t>(variable)],
                          std::nullopt, std::nullopt};
      if (joint.maxVelocity > 0) jointSpec.maxVelocity = joint.maxVelocity;
      spec.joints.push_back(jointSpec);
    }
    description.robots.push_back(std::move(spec));
    return problem;
  }

 private:
  [[nodiscard]] fs::path sceneYaml() const { return scene_.name(); }

  // ---- The robot.

  // The group's joints are movable joints of the URDF.
  void checkGroup() const {
    for (const std::string& joint : robot_.groupJoints) {
      if (!variableOf(joint)) {
        throw InputError(locate(robot_.urdf.string(), "planning group joint " + inQuotes(joint) +
                                                          " is not a movable joint" +
                                                          suggestion(joint, movableJoints())));
      }
    }
  }

  void checkRobotName() const {
    const auto name = scene_.find(scene_.root(), "robot_model_name");
    if (name && scene_.text(*name) != model_.name()) {
      scene_.fail(*name, "robot " + inQuotes(scene_.text(*name)) + " is not the URDF's robot " +
                             inQuotes(model_.name()));
    }
  }

  void checkGroupName() const {
    if (robot_.group.empty()) return;
    const Node group = request_.at(request_.root(), "group_name");
    if (request_.text(group) != robot_.group) {
      request_.fail(group, "planning group " + inQuotes(request_.text(group)) + " is not " +
                               inQuotes(robot_.group));
    }
  }

  [[nodiscard]] std::optional<int> variableOf(const std::string& joint) const {
    for (int variable = 0; variable < model_.dof(); ++variable) {
      if (model_.variableJoint(variable).name == joint) return variable;
    }
    return std::nullopt;
  }

  [[nodiscard]] std::vector<std::string> movableJoints() const {
    std::vector<std::string> names;
    for (int variable = 0; variable < model_.dof(); ++variable) {
      names.push_back(model_.variableJoint(variable).name);
    }
    return names;
  }

  // The configuration variable of the joint named at `entry`; nullopt for a fixed joint, whose
  // value MoveIt's states list but no configuration holds.
  [[nodiscard]] std::optional<int> jointAt(const YamlFile& file, const Node& entry) const {
    const std::string name = file.text(entry);
    if (const auto variable = variableOf(name)) return variable;
    const bool fixed = std::any_of(model_.joints().begin(), model_.joints().end(),
                                   [&](const Joint& joint) { return joint.name == name; });
    if (!fixed) {
      file.fail(entry, "joint " + inQuotes(name) + " is not in the URDF" +
                           suggestion(name, movableJoints()));
    }
    return std::nullopt;
  }

  // A joint value at `entry` within the limits of `variable`'s joint.
  [[nodiscard]] double jointValue(const YamlFile& file, const Node& entry, int variable) const {
    const double value = file.number(entry);
    const Joint& joint = model_.variableJoint(variable);
    if (!withinLimits(joint, value)) {
      file.fail(entry, fmt::format("{:g} is outside the limits [{:g}, {:g}] of joint '{}'", value,
                                   joint.lower, joint.upper, joint.name));
    }
    return value;
  }

  // A RobotState: joint_state's names and positions into `configuration`; the virtual joint of
  // multi_dof_joint_state must leave the robot base at the planning frame's origin.
  void readRobotState(const YamlFile& file, const Node& state,
                      PartialConfiguration& configuration) const {
    if (const auto multiDof = file.find(state, "multi_dof_joint_state")) {
      if (const auto transforms = file.find(*multiDof, "transforms")) {
        for (const Node& transform : file.list(*transforms)) {
          if (!isIdentity(file.pose(transform, "translation", "rotation"))) {
            file.fail(transform,
                      "the virtual joint must be the identity (the robot base is the planning "
                      "frame)");
          }
        }
      }
    }
    const auto jointState = file.find(state, "joint_state");
    if (!jointState) return;
    const auto names = file.find(*jointState, "name");
    if (!names) return;
    const std::vector<Node> joints = file.list(*names);
    const std::vector<Node> positions =
        file.listOf(file.at(*jointState, "position"), joints.size(), "positions (one per name)");
    for (std::size_t i = 0; i < joints.size(); ++i) {
      if (const auto variable = jointAt(file, joints[i])) {
        configuration[static_cast<std::size_t>(*variable)] =
            jointValue(file, positions[i], *variable);
      }
    }
  }

  [[nodiscard]] std::vector<double> complete(const PartialConfiguration& configuration,
                                             const Node& start) const {
    std::vector<double> values;
    for (std::size_t variable = 0; variable < configuration.size(); ++variable) {
      if (!configuration[variable]) {
        request_.fail(start, "no position for joint " +
                                 inQuotes(model_.variableJoint(static_cast<int>(variable)).name));
      }
      values.push_back(*configuration[variable]);
    }
    return values;
  }

  // The one goal: joint constraints, every group joint set, the other joints as in `start`.
  [[nodiscard]] std::vector<double> readGoal(const std::vector<double>& start) const {
    const std::vector<Node> goals =
        request_.listOf(request_.at(request_.root(), "goal_constraints"), 1, "goal");
    for (const char* other :
         {"position_constraints", "orientation_constraints", "visibility_constraints"}) {
      if (const auto constraints = request_.find(goals[0], other);
          constraints && constraints->node.size() > 0) {
        request_.fail(*constraints, "only joint constraints are supported");
      }
    }
    const Node joints = request_.at(goals[0], "joint_constraints");
    std::vector<double> goal = start;
    std::set<int> given;
    for (const Node& constraint : request_.list(joints)) {
      const Node name = request_.at(constraint, "joint_name");
      const auto variable = jointAt(request_, name);
      const Node position = request_.at(constraint, "position");
      if (!variable) continue;
      if (!given.insert(*variable).second) {
        request_.fail(name, "joint " + inQuotes(request_.text(name)) + " is constrained twice");
      }
      goal[static_cast<std::size_t>(*variable)] = jointValue(request_, position, *variable);
    }
    for (const std::string& joint : robot_.groupJoints) {
      if (!given.contains(*variableOf(joint))) {
        request_.fail(joints, "no position for group joint " + inQuotes(joint));
      }
    }
    return goal;
  }

  // ---- The world.

  // One static object per primitive of each collision object, in the planning frame.
  [[nodiscard]] std::vector<ObjectSpec> readObjects() const {
    std::vector<ObjectSpec> objects;
    const auto world = scene_.find(scene_.root(), "world");
    if (!world) return objects;
    const auto list = scene_.find(*world, "collision_objects");
    if (!list) return objects;
    std::map<std::string, std::string> names{{lowerCase(model_.name()), "the robot"}};
    for (const Node& entry : scene_.list(*list)) {
      const Node idNode = scene_.at(entry, "id");
      const std::string id = scene_.text(idNode);
      if (id.empty()) scene_.fail(idNode, "empty id");
      const auto [previous, added] = names.emplace(lowerCase(id), idNode.key);
      if (!added) {
        scene_.fail(idNode, "id " + inQuotes(id) + " is taken by " + previous->second +
                                " (names are compared without case)");
      }
      checkUnsupported(entry);
      const auto placement = scene_.find(entry, "pose");
      const Pose frame =
          objectFrame(entry) * (placement ? scene_.pose(*placement) : Pose::Identity());
      const auto primitives = scene_.find(entry, "primitives");
      if (!primitives) scene_.fail(entry, "no primitives");
      const std::vector<Node> shapes = scene_.list(*primitives);
      const std::vector<Node> poses = scene_.listOf(scene_.at(entry, "primitive_poses"),
                                                    shapes.size(), "poses (one per primitive)");
      for (std::size_t k = 0; k < shapes.size(); ++k) {
        ObjectSpec object;
        object.name = shapes.size() == 1 ? id : id + "/" + std::to_string(k);
        object.geometry = {primitive(shapes[k]), scene_.where(shapes[k])};
        object.pose = frame * scene_.pose(poses[k]);
        object.source = scene_.where(entry);
        object.poseSource = scene_.where(poses[k]);
        objects.push_back(std::move(object));
      }
    }
    return objects;
  }

  // Parts of a collision object kaboum cannot represent are errors rather than silently dropped.
  void checkUnsupported(const Node& entry) const {
    for (const char* key : {"meshes", "planes"}) {
      if (const auto found = scene_.find(entry, key); found && found->node.size() > 0) {
        scene_.fail(*found, std::string(key) + " are not supported (only primitives)");
      }
    }
    if (const auto operation = scene_.find(entry, "operation")) {
      const std::string text = scene_.text(*operation);
      if (text != "0" && lowerCase(text) != "add") {
        scene_.fail(*operation, "operation " + inQuotes(text) + " is not supported (only ADD)");
      }
    }
  }

  // The frame an object's poses are given in: its header's frame_id must be the planning frame
  // (empty), the URDF root link, or a fixed frame at the identity — the robot base either way.
  [[nodiscard]] Pose objectFrame(const Node& entry) const {
    const auto header = scene_.find(entry, "header");
    if (!header) return Pose::Identity();
    const auto frameId = scene_.find(*header, "frame_id");
    if (!frameId) return Pose::Identity();
    const std::string frame = scene_.text(*frameId);
    const auto root = std::find_if(model_.links().begin(), model_.links().end(),
                                   [](const Link& link) { return link.parentJoint < 0; });
    if (frame == root->name) return Pose::Identity();
    if (const auto fixedFrames = scene_.find(scene_.root(), "fixed_frame_transforms")) {
      for (const Node& fixed : scene_.list(*fixedFrames)) {
        const auto child = scene_.find(fixed, "child_frame_id");
        const auto transform = scene_.find(fixed, "transform");
        if (child && transform && scene_.text(*child) == frame &&
            isIdentity(scene_.pose(*transform, "translation", "rotation"))) {
          return Pose::Identity();
        }
      }
    }
    scene_.fail(*frameId, "frame " + inQuotes(frame) +
                              " is not the robot base frame (the URDF root link or a fixed frame "
                              "at the identity)");
  }

  // A SolidPrimitive: box [x, y, z], cylinder [height, radius] (along z), sphere [radius].
  [[nodiscard]] CollisionShape primitive(const Node& entry) const {
    static const std::vector<std::string> kTypes{"box", "cylinder", "sphere"};
    const Node typeNode = scene_.at(entry, "type");
    const std::string type = lowerCase(scene_.text(typeNode));
    const auto kind = std::find(kTypes.begin(), kTypes.end(), type);
    if (kind == kTypes.end()) {
      scene_.fail(typeNode, "unsupported shape " + inQuotes(type) + " (box, cylinder, sphere)");
    }
    const Node dimensionsNode = scene_.at(entry, "dimensions");
    const std::size_t count = type == "box" ? 3 : type == "cylinder" ? 2 : 1;
    std::vector<double> dimensions;
    for (const Node& value : scene_.listOf(dimensionsNode, count, "dimensions for a " + type)) {
      dimensions.push_back(scene_.number(value));
      if (!(dimensions.back() > 0)) scene_.fail(value, "must be positive");
    }
    CollisionShape shape;
    if (type == "box") {
      shape.kind = CollisionShape::Kind::Box;
      shape.size = {dimensions[0], dimensions[1], dimensions[2]};
    } else if (type == "cylinder") {
      shape.kind = CollisionShape::Kind::Cylinder;
      shape.length = dimensions[0];
      shape.radius = dimensions[1];
    } else {
      shape.kind = CollisionShape::Kind::Sphere;
      shape.radius = dimensions[0];
    }
    return shape;
  }

  // The allowed_collision_matrix: pairs of robot links marked true are added to `pairs`. Pairs of
  // objects are ignored (static objects are never checked against each other); allowing a link
  // to touch an object, and default entries that allow anything, are not supported.
  void readAllowedCollisionMatrix(const std::vector<ObjectSpec>& objects,
                                  std::vector<AllowedPair>& pairs) const {
    const auto matrix = scene_.find(scene_.root(), "allowed_collision_matrix");
    if (!matrix) return;
    if (const auto defaults = scene_.find(*matrix, "default_entry_values")) {
      for (const Node& value : scene_.list(*defaults)) {
        if (scene_.boolean(value)) scene_.fail(value, "default entries are not supported");
      }
    }
    const auto namesNode = scene_.find(*matrix, "entry_names");
    if (!namesNode) return;
    std::vector<std::string> candidates = linkNames(model_);
    std::set<std::string> objectIds;
    for (const ObjectSpec& object : objects) {
      const std::string id = object.name.substr(0, object.name.find('/'));
      if (objectIds.insert(id).second) candidates.push_back(id);
    }
    std::vector<std::string> names;
    for (const Node& name : scene_.list(*namesNode)) {
      names.push_back(scene_.text(name));
      if (std::find(candidates.begin(), candidates.end(), names.back()) == candidates.end()) {
        scene_.fail(name, "unknown link or object " + inQuotes(names.back()) +
                              suggestion(names.back(), candidates));
      }
    }
    const std::vector<Node> rows =
        scene_.listOf(scene_.at(*matrix, "entry_values"), names.size(), "rows (one per name)");
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::vector<Node> row = scene_.listOf(rows[i], names.size(), "values (one per name)");
      for (std::size_t j = 0; j < names.size(); ++j) {
        if (i == j || !scene_.boolean(row[j])) continue;
        const bool firstIsObject = objectIds.contains(names[i]);
        const bool secondIsObject = objectIds.contains(names[j]);
        if (firstIsObject && secondIsObject) continue;
        if (firstIsObject || secondIsObject) {
          scene_.fail(row[j], "allowing link " + inQuotes(firstIsObject ? names[j] : names[i]) +
                                  " to touch object " +
                                  inQuotes(firstIsObject ? names[i] : names[j]) +
                                  " is not supported");
        }
        addAllowedPair(pairs, {names[i], names[j]});
      }
    }
  }

  const MoveItRobot& robot_;
  RobotModel model_;
  YamlFile scene_;
  YamlFile request_;
};

// The digits of "scene0001.yaml" or "request0001.yaml" after `prefix`, if the name is so.
std::optional<std::string> problemNumber(const fs::path& file, const std::string& prefix) {
  const std::string name = file.filename().string();
  const std::string suffix = ".yaml";
  if (!name.starts_with(prefix) || !name.ends_with(suffix)) return std::nullopt;
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  const bool numeric = !digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (!numeric) return std::nullopt;
  return digits;
}

}  // namespace

std::vector<AllowedPair> readSrdfAllowedPairs(const std::string& path, const RobotModel& model) {
  const std::string text = readText(path);
  TiXmlDocument document;
  document.Parse(text.c_str());
  if (document.Error()) {
    throw InputError(locate(path, std::string("invalid XML: ") + document.ErrorDesc(),
                            document.ErrorRow(), document.ErrorCol()));
  }
  const TiXmlElement* robot = document.RootElement();
  if (!robot || std::string(robot->Value()) != "robot") {
    throw InputError(locate(path, "expected a <robot> element"));
  }
  std::vector<AllowedPair> pairs;
  const std::vector<std::string> links = linkNames(model);
  for (const TiXmlElement* element = robot->FirstChildElement("disable_collisions"); element;
       element = element->NextSiblingElement("disable_collisions")) {
    const auto link = [&](const char* attribute) {
      const char* name = element->Attribute(attribute);
      const auto fail = [&](const std::string& what) {
        throw InputError(
            locate(path, "disable_collisions: " + what, element->Row(), element->Column()));
      };
      if (!name) fail(std::string("missing attribute ") + attribute);
      if (!model.findLink(name)) fail("unknown link " + inQuotes(name) + suggestion(name, links));
      return std::string(name);
    };
    addAllowedPair(pairs, {link("link1"), link("link2")});
  }
  return pairs;
}

MotionProblem readMoveItProblem(const std::filesystem::path& sceneYaml,
                                const std::filesystem::path& requestYaml,
                                const MoveItRobot& robot) {
  return ProblemReader(robot, sceneYaml, requestYaml).read();
}

std::vector<MoveItProblemFiles> listMoveItProblems(const std::filesystem::path& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    throw InputError(locate(folder.string(), "not a folder"));
  }
  std::map<fs::path, std::map<std::string, MoveItProblemFiles>> byFolder;
  for (fs::recursive_directory_iterator it(folder, error), end; !error && it != end;
       it.increment(error)) {
    const fs::path& file = it->path();
    if (const auto scene = problemNumber(file, "scene")) {
      byFolder[file.parent_path()][*scene].scene = file;
    } else if (const auto request = problemNumber(file, "request")) {
      byFolder[file.parent_path()][*request].request = file;
    }
  }
  if (error) throw InputError(locate(folder.string(), "cannot read folder: " + error.message()));
  std::vector<MoveItProblemFiles> problems;
  for (const auto& [directory, numbered] : byFolder) {
    for (const auto& [number, files] : numbered) {
      if (files.scene.empty()) {
        throw InputError(locate(files.request.string(), "no scene" + number + ".yaml beside it"));
      }
      if (files.request.empty()) {
        throw InputError(locate(files.scene.string(), "no request" + number + ".yaml beside it"));
      }
      problems.push_back(files);
    }
  }
  if (problems.empty()) {
    throw InputError(locate(folder.string(), "no problems (sceneNNNN.yaml with requestNNNN.yaml)"));
  }
  return problems;
}

}  // namespace kaboum::io
