#include "kaboum/tamp/solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <thread>

#include "kaboum/core/error.hpp"
#include "kaboum/core/worker_pool.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::tamp {

using namespace kaboum::symbolic;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Whether module `module` of the domain is bound to one of the geometric attachments.
bool isGeometric(const Module& module) {
  const auto& names = GeometricAttachments::procedureNames();
  return module.library.empty() &&
         std::find(names.begin(), names.end(), module.procedure) != names.end();
}

}  // namespace

std::vector<GeometricState> statesAlong(const World& world, const GeometricState& from,
                                        const ActionGeometry& action) {
  std::vector<GeometricState> states{from};
  for (std::size_t s = 0; s < action.steps.size(); ++s) {
    const GeometricStep& step = action.steps[s];
    GeometricState next = states.back();
    switch (step.kind) {
      case GeometricStep::Kind::Grasp: {
        const auto& spec = world.description().robots[step.robot];
        const int link = world.robots()[step.robot]
                             .collision.model()
                             .findLink(spec.tools[step.tool].link)
                             .value();
        // The receiver of a handover takes the object from the robot holding it.
        if (const std::optional<std::size_t> giver = holderOf(next, step.object)) {
          world.release(next, *giver, step.object);
        }
        world.hold(next, step.robot, link, step.object, step.pose);
        break;
      }
      case GeometricStep::Kind::Release: {
        // The giver of a handover opens its hand after the receiver closed its own.
        const bool handedOver = s > 0 && action.steps[s - 1].kind == GeometricStep::Kind::Grasp &&
                                action.steps[s - 1].object == step.object &&
                                holderOf(states[s - 1], step.object) == step.robot;
        if (!handedOver) world.release(next, step.robot, step.object);
        break;
      }
      case GeometricStep::Kind::Join:
        next.join(step.object, step.joinedTo);
        break;
      default:
        next.robots[step.robot].configuration = step.path.back();
        break;
    }
    states.push_back(std::move(next));
  }
  return states;
}

void verifyActionPaths(const verify::ReferenceGeometry& reference, std::size_t node,
                       const ActionGeometry& action, const std::vector<GeometricState>& states,
                       const verify::VerifyOptions& options, PlanVerification& verification) {
  const World& world = reference.world();
  for (std::size_t s = 0; s < action.steps.size(); ++s) {
    const GeometricStep& step = action.steps[s];
    if (step.path.empty()) continue;
    verify::ScenePath path;
    path.robots = {step.robot};
    path.waypoints = step.path;
    const RobotState& robot = states[s].robots[step.robot];
    for (std::size_t h = 0; h < robot.held.size(); ++h) {
      path.held.push_back({step.robot, robot.heldObjects[h],
                           static_cast<std::size_t>(robot.held[h].link), robot.held[h].inLink});
    }
    path.context = states[s];
    PathCheck check{node,
                    fmt::format("{}({})", action.procedure, fmt::join(action.arguments, ", ")),
                    s,
                    step.kind,
                    world.robots()[step.robot].name,
                    verify::verifyPath(reference, path, options)};
    const verify::PathVerification& checked = check.result;
    ++verification.paths;
    verification.samples += checked.samples;
    if (checked.clearance) {
      verification.smallestClearance =
          std::min(verification.smallestClearance, checked.clearance->distance);
    }
    if (!checked.collisionFree()) {
      ++verification.collidingPaths;
      if (verification.firstCollision.empty()) {
        const verify::PathCollision& hit = checked.collisions.front();
        verification.firstCollision = fmt::format(
            "{} step {} ({}): {} collides with {}", check.action, s + 1, toString(step.kind),
            verify::describe(hit.first), verify::describe(hit.second));
      }
    }
    verification.checks.push_back(std::move(check));
  }
}

Solver::Solver(const World& world, ContingentProblem problem, SolveOptions options)
    : world_(&world), problem_(std::move(problem)), options_(std::move(options)) {
  attachments_ = std::make_unique<GeometricAttachments>(world, options_.geometry);
  ProcedureRegistry registry;
  attachments_->registerProcedures(registry);
  if (options_.registerProcedures) options_.registerProcedures(*attachments_, registry);
  for (const Module& module : problem_.domain.modules) {
    const bool recorded = isRecordedEffect(module);
    if (!isGeometric(module) && !recorded) continue;
    const bool effect = recorded || GeometricAttachments::isGeometricEffect(module.procedure);
    if (effect != (module.kind == Module::Kind::EffectApplicator)) {
      throw InputError(locate(problem_.domain.file,
                              fmt::format("module '{}': '{}' is {}", module.name, module.procedure,
                                          effect ? "an effect" : "a condition checker"),
                              module.pos.line, module.pos.column));
    }
    if (module.reads.empty() || (effect && module.writes.size() != 1)) {
      throw InputError(locate(
          problem_.domain.file,
          fmt::format("module '{}': the geometric attachment '{}' reads the geometric state's "
                      "fluent first{}, e.g. (:modules ({} … (geometry) effect {} :reads "
                      "((geometry))))",
                      module.name, module.procedure, effect ? " and writes it (one fluent)" : "",
                      module.name, module.procedure),
          module.pos.line, module.pos.column));
    }
    if (!recorded && module.paramTypes.size() != GeometricAttachments::arity(module.procedure)) {
      throw InputError(
          locate(problem_.domain.file,
                 fmt::format("module '{}': '{}' takes {} argument(s), not {}", module.name,
                             module.procedure, GeometricAttachments::arity(module.procedure),
                             module.paramTypes.size()),
                 module.pos.line, module.pos.column));
    }
  }
  task_ = std::make_unique<KnowledgeTask>(problem_, registry, options_.maxWorlds);
  checkCalls();
}

Solver::~Solver() = default;

bool Solver::isRecordedEffect(const Module& module) const {
  const std::vector<std::string>& names = options_.geometricEffects;
  return module.library.empty() &&
         std::find(names.begin(), names.end(), module.procedure) != names.end();
}

// Every ground call of a geometric attachment: its arguments name scene entities of the right
// kind; the fluents geometric effects write start at identifier 0 (the world's initial state).
void Solver::checkCalls() {
  const GroundTask& ground = task_->task();
  const std::string& scene = world_->description().settings.source.file;
  for (const GroundModuleCall& call : ground.moduleCalls) {
    const Module& module = problem_.domain.modules[static_cast<std::size_t>(call.module)];
    const bool recorded = isRecordedEffect(module);
    if (!isGeometric(module) && !recorded) continue;
    for (std::size_t i = 0; !recorded && i < call.args.size(); ++i) {
      const std::string& name = ground.objectNames[static_cast<std::size_t>(call.args[i])];
      if (!attachments_->namesSceneEntity(name)) {
        throw InputError(locate(problem_.problem.file,
                                fmt::format("'{}' (argument {} of module '{}', attachment '{}') "
                                            "names no robot, tool, object or location of {}",
                                            name, i + 1, module.name, module.procedure, scene)));
      }
    }
    if (!recorded && !GeometricAttachments::isGeometricEffect(module.procedure)) continue;
    const FluentId fluent = call.writes.front();
    if (std::find(geometricFluents_.begin(), geometricFluents_.end(), fluent) ==
        geometricFluents_.end()) {
      geometricFluents_.push_back(fluent);
    }
  }
  for (const FluentId fluent : geometricFluents_) {
    const double initial = ground.initialFluents[static_cast<std::size_t>(fluent)];
    if (initial != 0) {
      const std::string& name = ground.fluentNames[static_cast<std::size_t>(fluent)];
      throw InputError(locate(problem_.problem.file,
                              fmt::format("the geometric state fluent {} must start at the "
                                          "scene's initial state: add (= {} 0) to :init",
                                          name, name)));
    }
  }
}

SolveResult Solver::solve() {
  const auto start = std::chrono::steady_clock::now();
  SolveResult result;
  const ContingentResult found = solveContingent(*task_, options_.search);
  result.status = found.status;
  result.plan = found.plan;
  result.search = found.statistics;
  result.modules = task_->attachments().statistics();
  result.geometric = attachments_->statistics();
  result.geometricStates = attachments_->map().size();
  double attachmentSeconds = 0;
  for (const ModuleStatistics& module : result.modules) {
    attachmentSeconds += module.seconds;
    const auto declared =
        std::find_if(problem_.domain.modules.begin(), problem_.domain.modules.end(),
                     [&](const Module& m) { return m.name == module.name; });
    if (declared != problem_.domain.modules.end() && isGeometric(*declared)) {
      result.geometricSeconds += module.seconds;
    }
  }
  result.symbolicSeconds = std::max(0.0, found.statistics.seconds - attachmentSeconds);
  if (result.status != PlannerStatus::Solved) {
    result.message = result.status == PlannerStatus::Unsolvable
                         ? "no plan: the search space is exhausted (every branch ends where no "
                           "action applies symbolically or geometrically)"
                         : std::string("no plan: ") + toString(result.status);
    result.seconds = secondsSince(start);
    return result;
  }
  if (!collectGeometry(result)) {
    result.status = PlannerStatus::Unsolvable;
    result.seconds = secondsSince(start);
    return result;
  }
  result.seconds = secondsSince(start);
  verifyPlan(result);
  return result;
}

bool Solver::collectGeometry(SolveResult& result) {
  const PlanTree& plan = result.plan;
  result.geometry.assign(plan.nodes.size(), {});
  std::vector<bool> visited(plan.nodes.size(), false);
  // The value of fluent `fluent` in every world of `belief`; nullopt when they differ.
  const auto common = [&](FluentId fluent, const Belief& belief) -> std::optional<double> {
    std::optional<double> value;
    for (const std::uint32_t world : belief) {
      const double v = task_->world(world).fluent(fluent);
      if (value && *value != v) return std::nullopt;
      value = v;
    }
    return value;
  };
  std::vector<std::pair<int, Belief>> open{{plan.root, task_->initialBelief()}};
  while (!open.empty()) {
    auto [id, belief] = std::move(open.back());
    open.pop_back();
    if (id < 0 || visited[static_cast<std::size_t>(id)]) continue;
    visited[static_cast<std::size_t>(id)] = true;
    const PlanTree::Node& node = plan.nodes[static_cast<std::size_t>(id)];
    if (node.kind == PlanTree::Node::Kind::Branch) {
      Belief onTrue, onFalse;
      if (node.fluent >= 0) {
        task_->splitValue(node.fluent, node.value, belief, onTrue, onFalse);
      } else {
        task_->split(node.atom, belief, onTrue, onFalse);
      }
      open.emplace_back(node.next, std::move(onTrue));
      open.emplace_back(node.onFalse, std::move(onFalse));
      continue;
    }
    if (node.kind != PlanTree::Node::Kind::Action) continue;
    Belief after;
    if (!task_->apply(node.op, belief, after, node.sample)) {
      result.message = "internal: a plan action does not apply on replay";
      return false;
    }
    const std::string& action = task_->task().operators[static_cast<std::size_t>(node.op)].name;
    for (const FluentId fluent : geometricFluents_) {
      const std::optional<double> from = common(fluent, belief);
      const std::optional<double> to = common(fluent, after);
      if (!from || !to) {
        result.message = fmt::format(
            "action ({}) runs in geometric states that differ between the worlds the agent "
            "cannot tell apart: a geometric effect depends on a fact not yet sensed",
            action);
        return false;
      }
      if (*from == *to) continue;
      const ActionGeometry* geometry =
          attachments_->transition(static_cast<std::size_t>(*from), static_cast<std::size_t>(*to));
      if (!geometry) {
        result.message = fmt::format("internal: no recorded geometry for action ({})", action);
        return false;
      }
      result.geometry[static_cast<std::size_t>(id)].push_back(*geometry);
    }
    open.emplace_back(node.next, std::move(after));
  }
  return true;
}

void Solver::verifyPlan(SolveResult& result) {
  const auto start = std::chrono::steady_clock::now();
  PlanVerification& verification = result.verification;
  verification.symbolic = validatePlanTree(*task_, result.plan, problem_.problem.file);
  verification.smallestClearance = std::numeric_limits<double>::infinity();
  if (options_.verify) {
    verification.pathsChecked = true;
    const verify::ReferenceGeometry reference(*world_);
    std::vector<std::pair<std::size_t, const ActionGeometry*>> actions;
    for (std::size_t node = 0; node < result.geometry.size(); ++node) {
      for (const ActionGeometry& action : result.geometry[node])
        actions.emplace_back(node, &action);
    }
    // The actions' paths are independent: checked on every core, merged in plan order.
    std::vector<PlanVerification> checked(actions.size());
    WorkerPool workers(std::thread::hardware_concurrency());
    workers.run(actions.size(), [&](std::size_t i) {
      const ActionGeometry& action = *actions[i].second;
      checked[i].smallestClearance = std::numeric_limits<double>::infinity();
      verifyActionPaths(reference, actions[i].first, action,
                        statesAlong(*world_, attachments_->map().state(action.from), action),
                        options_.verification, checked[i]);
    });
    for (PlanVerification& part : checked) {
      verification.paths += part.paths;
      verification.samples += part.samples;
      verification.collidingPaths += part.collidingPaths;
      verification.smallestClearance =
          std::min(verification.smallestClearance, part.smallestClearance);
      if (verification.firstCollision.empty()) verification.firstCollision = part.firstCollision;
      std::move(part.checks.begin(), part.checks.end(), std::back_inserter(verification.checks));
    }
  }
  verification.seconds = secondsSince(start);
  if (!verification.passed()) {
    result.message =
        !verification.symbolic.valid
            ? "the plan fails symbolic validation: " + verification.symbolic.message
            : "a path of the plan collides on the original meshes: " + verification.firstCollision;
  }
}

}  // namespace kaboum::tamp
