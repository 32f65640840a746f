#include "kaboum/tamp/plan_file.hpp"

#include <cmath>

#include "kaboum/io/json_kinematics.hpp"

namespace kaboum::tamp {

using namespace kaboum::symbolic;

namespace {

nlohmann::json robotsJson(const World& world) {
  nlohmann::json robots = nlohmann::json::array();
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    nlohmann::json joints = nlohmann::json::array();
    for (const JointSpec& joint : world.description().robots[r].joints)
      joints.push_back(joint.name);
    nlohmann::json tools = nlohmann::json::array();
    for (const ToolSpec& tool : world.description().robots[r].tools) tools.push_back(tool.name);
    robots.push_back({{"name", world.robots()[r].name},
                      {"urdf", world.description().robots[r].urdf},
                      {"joints", joints},
                      {"tools", tools}});
  }
  return robots;
}

nlohmann::json stateJson(const World& world, const GeometricState& state) {
  nlohmann::json robots = nlohmann::json::object();
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    robots[world.robots()[r].name] = state.robots[r].configuration;
  }
  nlohmann::json objects = nlohmann::json::object();
  for (std::size_t o = 0; o < world.scene().size(); ++o) {
    const bool movable = world.scene().movable(o);
    if (movable && !state.placements[world.scene().slot(o)].present) continue;
    objects[world.scene().name(o)] = io::toJson(world.scene().pose(o, state.placements));
  }
  return {{"robots", robots}, {"objects", objects}};
}

nlohmann::json stepJson(const World& world, const GeometricStep& step) {
  const auto& spec = world.description().robots[step.robot];
  nlohmann::json json = {{"kind", toString(step.kind)},
                         {"robot", spec.name},
                         {"tool", spec.tools.empty() ? "" : spec.tools[step.tool].name}};
  switch (step.kind) {
    case GeometricStep::Kind::Grasp:
      json["object"] = world.scene().name(step.object);
      json["link"] = spec.tools[step.tool].link;
      json["object_in_link"] = io::toJson(step.pose);
      break;
    case GeometricStep::Kind::Release:
      json["object"] = world.scene().name(step.object);
      json["object_pose"] = io::toJson(step.pose);
      break;
    case GeometricStep::Kind::Join:
      json["objects"] = {world.scene().name(step.object), world.scene().name(step.joinedTo)};
      break;
    default:
      json["waypoints"] = step.path;
      break;
  }
  return json;
}

nlohmann::json nodeJson(Solver& solver, const SolveResult& result, std::size_t id) {
  const PlanTree::Node& node = result.plan.nodes[id];
  switch (node.kind) {
    case PlanTree::Node::Kind::Goal:
      return {{"id", id}, {"kind", "goal"}};
    case PlanTree::Node::Kind::Branch:
      return {{"id", id},
              {"kind", "branch"},
              {"test", branchTest(solver.task(), node)},
              {"on_true", node.next},
              {"on_false", node.onFalse}};
    case PlanTree::Node::Kind::Action:
      break;
  }
  nlohmann::json geometry = nlohmann::json::array();
  for (const ActionGeometry& action : result.geometry[id]) {
    nlohmann::json steps = nlohmann::json::array();
    for (const GeometricStep& step : action.steps) steps.push_back(stepJson(solver.world(), step));
    geometry.push_back({{"procedure", action.procedure},
                        {"arguments", action.arguments},
                        {"from_state", action.from},
                        {"to_state", action.to},
                        {"steps", steps}});
  }
  return {{"id", id},
          {"kind", "action"},
          {"action",
           "(" + solver.task().task().operators[static_cast<std::size_t>(node.op)].name + ")"},
          {"sample", node.sample},
          {"next", node.next},
          {"geometry", geometry}};
}

// How the search found the plan (ContingentOptions::symbolicFirst).
std::string foundBy(const symbolic::ContingentStatistics& search) {
  if (search.refinedSymbolicPlan) return "symbolic plan refined";
  if (search.refinementFailed) return "integrated search after a failed refinement";
  return "integrated search";
}

nlohmann::json finiteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json statisticsJson(const World& world, const SolveResult& result) {
  const GeometricStatistics& geometric = result.geometric;
  std::size_t waypoints = 0;
  std::size_t actions = 0;
  for (const auto& node : result.geometry) {
    for (const ActionGeometry& action : node) {
      for (const GeometricStep& step : action.steps) waypoints += step.path.size();
    }
  }
  for (const PlanTree::Node& node : result.plan.nodes) {
    if (node.kind == PlanTree::Node::Kind::Action) ++actions;
  }
  nlohmann::json modules = nlohmann::json::array();
  for (const ModuleStatistics& module : result.modules) {
    modules.push_back({{"name", module.name},
                       {"calls", module.calls},
                       {"cache_hits", module.cacheHits},
                       {"seconds", module.seconds}});
  }
  const motion::CheckStatistics& checks = geometric.checks;
  const std::size_t collisionChecks = checks.stateChecks + checks.motionChecks;
  const std::size_t positives = checks.statePositives + checks.motionPositives;
  return {{"geometry", world.predicates() != nullptr ? "exact" : "bounded"},
          {"epsilon", io::epsilonSetting(world.description().settings)},
          {"total_seconds", result.seconds},
          {"symbolic_seconds", result.symbolicSeconds},
          {"geometric_seconds", result.geometricSeconds},
          {"ik_calls", geometric.ikCalls},
          {"ik_seconds", geometric.ikSeconds},
          {"motion_queries", geometric.motionQueries},
          {"motion_seconds", geometric.motionSeconds},
          {"state_checks", geometric.checks.stateChecks},
          {"state_check_seconds", geometric.checks.stateSeconds},
          {"motion_checks", geometric.checks.motionChecks},
          {"motion_check_seconds", geometric.checks.motionSeconds},
          {"state_check_positives", checks.statePositives},
          {"motion_check_positives", checks.motionPositives},
          {"collision_checks", collisionChecks},
          {"collision_check_seconds", checks.stateSeconds + checks.motionSeconds},
          {"positive_share", collisionChecks == 0 ? 0.0
                                                  : static_cast<double>(positives) /
                                                        static_cast<double>(collisionChecks)},
          {"geometric_calls", geometric.calls},
          {"geometric_failures", geometric.failures},
          {"geometric_states", result.geometricStates},
          {"expanded", result.search.expanded},
          {"found_by", foundBy(result.search)},
          {"refinements", result.search.refinements},
          {"refinement_failure", result.search.refinementFailure},
          {"knowledge_states", result.search.beliefs},
          {"plan_actions", actions},
          {"plan_waypoints", waypoints},
          {"modules", modules}};
}

nlohmann::json planFileJson(Solver& solver, const SolveResult& result, const PlanSources& sources) {
  nlohmann::json nodes = nlohmann::json::array();
  for (std::size_t id = 0; id < result.plan.nodes.size(); ++id) {
    nodes.push_back(nodeJson(solver, result, id));
  }
  const PlanVerification& verification = result.verification;
  return {{"format", "kaboum-plan"},
          {"version", 1},
          {"domain", sources.domain},
          {"problem", sources.problem},
          {"scene", sources.scene},
          {"placement_seed", solver.world().description().settings.placementSeed},
          {"status", toString(result.status)},
          {"robots", robotsJson(solver.world())},
          {"initial_state", stateJson(solver.world(), solver.world().initialState())},
          {"root", result.plan.root},
          {"nodes", nodes},
          {"statistics", statisticsJson(solver.world(), result)},
          {"verification",
           {{"passed", verification.passed()},
            {"symbolic_valid", verification.symbolic.valid},
            {"symbolic_message", verification.symbolic.message},
            {"paths_checked", verification.pathsChecked},
            {"paths", verification.paths},
            {"samples", verification.samples},
            {"colliding_paths", verification.collidingPaths},
            {"smallest_clearance", finiteOrNull(verification.smallestClearance)},
            {"first_collision", verification.firstCollision},
            {"seconds", verification.seconds}}}};
}

}  // namespace kaboum::tamp
