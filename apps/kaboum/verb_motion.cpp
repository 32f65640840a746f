// `kaboum motion SCENE --robot R [--robot R2] [--from Q] (--to Q | --to-pose P [--tool T])
// [--cartesian] ...`: plans one certified motion of one robot or several moving together (thesis
// §6.1.2, §4.5) and prints its waypoints and statistics, or writes them as a path file.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <iostream>
#include <numbers>

#include "kaboum/core/error.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/motion/cartesian_motion.hpp"
#include "kaboum/motion/motion_planner.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::motion;

namespace {

struct Options {
  std::string scene;
  SceneLoadOptions load;
  std::vector<std::string> robots;
  std::string from = "home";
  std::string to;
  std::string toPose;
  std::string tool;
  bool cartesian = false;
  MotionOptions motion;
  std::string output;
  bool json = false;
  bool quiet = false;
};

// A number with an optional "deg" suffix (then converted to radians).
double parseValue(const std::string& text, const std::string& what) {
  std::string number = text;
  double scale = 1;
  if (number.size() > 3 && number.ends_with("deg")) {
    number.resize(number.size() - 3);
    scale = std::numbers::pi / 180;
  }
  double value = 0;
  const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (error != std::errc() || end != number.data() + number.size() || !std::isfinite(value)) {
    throw InputError(what + ": '" + text + "' is not a number");
  }
  return value * scale;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    std::string item = text.substr(begin, comma - begin);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    items.push_back(item);
    begin = comma + 1;
  }
  return items;
}

// "home"; every coordinate of the group in order ("0.1,20deg,..."); or named joints
// ("joint2=30deg,joint3=-0.5"), the others at home. A joint name is "JOINT" or "ROBOT/JOINT".
std::vector<double> parseConfiguration(const std::string& text, const std::string& option,
                                       const MotionGroup& group) {
  std::vector<double> q = group.configuration(group.context());
  if (text == "home") return q;
  const std::vector<std::string> items = splitList(text);
  if (text.find('=') == std::string::npos) {
    if (items.size() != group.dimension()) {
      throw InputError(
          fmt::format("{}: {} values for {} joints (write 'home', all values, or "
                      "JOINT=VALUE pairs)",
                      option, items.size(), group.dimension()));
    }
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = parseValue(items[i], option);
    return q;
  }
  for (const std::string& item : items) {
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) {
      throw InputError(option + ": '" + item + "' is not JOINT=VALUE");
    }
    const std::string name = item.substr(0, equals);
    std::size_t found = group.dimension();
    for (std::size_t i = 0; i < group.dimension() && found == group.dimension(); ++i) {
      const auto [r, variable] = group.coordinate(i);
      const WorldRobot& robot = group.world().robots()[r];
      const std::string& joint = robot.collision.model().variableJoint(variable).name;
      if (name == joint || name == robot.name + "/" + joint) found = i;
    }
    if (found == group.dimension()) {
      throw InputError(option + ": no joint named '" + name + "' in the moving robots");
    }
    q[found] = parseValue(item.substr(equals + 1), option);
  }
  return q;
}

// "x,y,z" (the start orientation kept) or "x,y,z,roll,pitch,yaw" (radians or deg), world frame.
Pose parsePose(const std::string& text, const Pose& start) {
  const std::vector<std::string> items = splitList(text);
  if (items.size() != 3 && items.size() != 6) {
    throw InputError("--to-pose: '" + text + "' is not x,y,z or x,y,z,roll,pitch,yaw");
  }
  Pose pose = start;
  pose.translation() = Vec3(parseValue(items[0], "--to-pose"), parseValue(items[1], "--to-pose"),
                            parseValue(items[2], "--to-pose"));
  if (items.size() == 6) {
    pose.linear() = (Eigen::AngleAxisd(parseValue(items[5], "--to-pose"), Vec3::UnitZ()) *
                     Eigen::AngleAxisd(parseValue(items[4], "--to-pose"), Vec3::UnitY()) *
                     Eigen::AngleAxisd(parseValue(items[3], "--to-pose"), Vec3::UnitX()))
                        .toRotationMatrix();
  }
  return pose;
}

std::vector<std::size_t> robotIndices(const World& world, const std::vector<std::string>& names) {
  std::vector<std::size_t> indices;
  for (const std::string& name : names) {
    const std::optional<NamedEntity> found = world.find(name);
    if (!found || found->kind != NamedEntity::Kind::Robot) {
      throw InputError("--robot: no robot named '" + name + "' in the scene");
    }
    if (std::find(indices.begin(), indices.end(), found->index) != indices.end()) {
      throw InputError("--robot: '" + name + "' is given twice");
    }
    indices.push_back(found->index);
  }
  return indices;
}

std::size_t toolIndex(const World& world, std::size_t robot, const std::string& name) {
  const std::vector<ToolSpec>& tools = world.description().robots[robot].tools;
  if (tools.empty()) {
    throw InputError("--to-pose: robot '" + world.robots()[robot].name + "' has no tool");
  }
  if (name.empty()) return 0;
  for (std::size_t t = 0; t < tools.size(); ++t) {
    if (tools[t].name == name) return t;
  }
  throw InputError("--tool: robot '" + world.robots()[robot].name + "' has no tool '" + name + "'");
}

// The goal configurations for a tool pose: IK solutions nearest the start first, the first one
// free of collisions.
std::vector<double> goalForPose(const MotionGroup& group, ToolKinematics& tool,
                                const std::vector<double>& start, const Pose& target,
                                const MotionOptions& options) {
  const std::vector<std::vector<double>> solutions = tool.solutions(target, start);
  if (solutions.empty()) throw InputError("--to-pose: no IK solution reaches the pose");
  const double clearance = sweepEpsilonOf(group, options);
  for (const std::vector<double>& q : solutions) {
    if (!configurationProblem(group, q, clearance)) return q;
  }
  throw InputError("--to-pose: no IK solution is free: " +
                   *configurationProblem(group, solutions.front(), clearance));
}

nlohmann::json statisticsJson(const MotionStatistics& s) {
  return {{"straight", s.straight},
          {"sweep_epsilon", s.sweepEpsilon},
          {"total_seconds", s.totalSeconds},
          {"planning_seconds", s.planningSeconds},
          {"shortcut_seconds", s.shortcutSeconds},
          {"state_checks", s.checks.stateChecks},
          {"state_check_seconds", s.checks.stateSeconds},
          {"motion_checks", s.checks.motionChecks},
          {"motion_check_seconds", s.checks.motionSeconds},
          {"planned_waypoints", s.plannedWaypoints},
          {"planned_length", s.plannedLength},
          {"length", s.length}};
}

void printResult(const MotionResult& result, const std::string& planner) {
  const MotionStatistics& s = result.statistics;
  fmt::print("status:    {}\n", toString(result.status));
  if (!result.message.empty()) fmt::print("reason:    {}\n", result.message);
  if (result.status != PlannerStatus::Solved) return;
  fmt::print("planner:   {}\n", s.straight ? "straight segment" : planner);
  fmt::print("sweep ε:   {:g} m\n", s.sweepEpsilon);
  fmt::print("waypoints: {} ({} planned)\n", result.path.size(), s.plannedWaypoints);
  fmt::print("length:    {:.4f} ({:.4f} planned), joint space\n", s.length, s.plannedLength);
  fmt::print("time:      {:.6f} s (planning {:.6f} s, shortcutting {:.6f} s)\n", s.totalSeconds,
             s.planningSeconds, s.shortcutSeconds);
  fmt::print("checks:    {} states ({:.6f} s), {} certified motions ({:.6f} s)\n",
             s.checks.stateChecks, s.checks.stateSeconds, s.checks.motionChecks,
             s.checks.motionSeconds);
  for (const std::vector<double>& q : result.path) fmt::print("  {:.6f}\n", fmt::join(q, " "));
}

int run(const Options& options) {
  if (options.to.empty() == options.toPose.empty()) {
    throw InputError("give exactly one of --to and --to-pose");
  }
  if (options.cartesian && options.toPose.empty()) {
    throw InputError("--cartesian needs --to-pose");
  }
  const World world = loadWorld(options.scene, options.load);
  const std::vector<std::size_t> robots = robotIndices(world, options.robots);
  const MotionGroup group(world, world.initialState(), robots);
  const std::vector<double> start = parseConfiguration(options.from, "--from", group);
  MotionResult result;
  if (options.toPose.empty()) {
    result =
        planMotion(group, start, parseConfiguration(options.to, "--to", group), options.motion);
  } else {
    if (robots.size() != 1) throw InputError("--to-pose moves one robot: give one --robot");
    ToolKinematics tool(world, robots.front(), toolIndex(world, robots.front(), options.tool),
                        options.motion.seed);
    const Pose target = parsePose(options.toPose, tool.tcpPose(start));
    result = options.cartesian
                 ? planCartesian(group, tool, start, target, options.motion)
                 : planMotion(group, start, goalForPose(group, tool, start, target, options.motion),
                              options.motion);
  }
  if (result.status == PlannerStatus::InvalidStart || result.status == PlannerStatus::InvalidGoal) {
    throw InputError(options.scene + ": " + result.message);
  }
  PathFile path{options.scene, options.robots, result.path, {}};
  if (!options.output.empty() && result.status == PlannerStatus::Solved) {
    writePathFile(options.output, path);
  }
  if (options.json) {
    nlohmann::json json = {
        {"status", toString(result.status)},
        {"message", result.message},
        {"planner", result.statistics.straight ? "straight" : options.motion.planner},
        {"path", toJson(path)},
        {"statistics", statisticsJson(result.statistics)}};
    std::cout << json.dump() << '\n';
  } else if (options.quiet) {
    fmt::print("{}\n", toString(result.status));
  } else {
    printResult(result, options.motion.planner);
  }
  return result.status == PlannerStatus::Solved ? 0 : 1;
}

VerbRunner setupMotion(CLI::App& command) {
  auto options = std::make_shared<Options>();
  command.add_option("SCENE", options->scene, "Scene file (YAML, docs/scene-format.md)")
      ->required();
  addSceneLoadOptions(command, options->load);
  command.add_option("--robot", options->robots, "A robot that moves (repeat to move several)")
      ->required();
  command
      .add_option("--from", options->from,
                  "Start: 'home', all joint values in order, or JOINT=VALUE pairs (radians, "
                  "metres, or a 'deg' suffix)")
      ->capture_default_str();
  command.add_option("--to", options->to, "Goal configuration, written as --from");
  command.add_option("--to-pose", options->toPose,
                     "Goal tool pose in the world: x,y,z (start orientation) or "
                     "x,y,z,roll,pitch,yaw");
  command.add_option("--tool", options->tool, "Tool of --to-pose (default: the robot's first)");
  command.add_flag("--cartesian", options->cartesian,
                   "Move the tool on a straight line to --to-pose");
  command
      .add_option("--planner", options->motion.planner,
                  "Sampling-based planner when the "
                  "straight segment collides")
      ->check(CLI::IsMember(motionPlannerNames()))
      ->capture_default_str();
  command.add_option("--time-limit", options->motion.timeLimit, "Seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command.add_option("--seed", options->motion.seed, "Random seed")->capture_default_str();
  command
      .add_option("--sweep-epsilon", options->motion.sweepEpsilon,
                  "Metres: bound of the swept volumes that certify motions (default: the "
                  "scene's sweep_epsilon)")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--range", options->motion.range,
                  "Joint-space length of one tree extension, radians (0: OMPL's default)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command
      .add_option("--shortcuts", options->motion.shortcutAttempts,
                  "Random shortcuts tried on a planned path")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command.add_option("-o,--output", options->output, "Write the path file (docs/path-format.md)");
  command.add_flag("--json", options->json, "Print one JSON object instead of lines");
  command.add_flag("-q,--quiet", options->quiet, "Print only the status");
  return [options] { return run(*options); };
}

const VerbRegistration registration{
    "motion", "Plan one certified motion of one robot or several moving together", &setupMotion};

}  // namespace

}  // namespace kaboum::cli
