// `kaboum solve DOMAIN PROBLEM SCENE`: the integrated planner (thesis Chapter 6) — a plan that
// branches on sensing, every action with its certified geometry, checked by the symbolic validator
// and the independent path verifier; printed as a tree with statistics, or as the plan file.
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/heuristic.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "kaboum/verify/exact_predicates.hpp"
#include "page_cli.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

namespace {

struct Options {
  tamp::PlanSources files;
  SceneLoadOptions load;
  tamp::SolveOptions solve;
  double motionTimeLimit = 2;
  double memoryLimitMegabytes = 8000;
  std::string placement = "random";
  std::string geometry = "bounded";
  std::string planOut;
  std::string html;
  bool json = false;
  bool quiet = false;
};

// The values of --placement.
const std::map<std::string, world::SearchStrategy>& placementStrategies() {
  static const std::map<std::string, world::SearchStrategy> strategies{
      {"random", world::SearchStrategy::Random},
      {"quadtree", world::SearchStrategy::Quadtree},
      {"linear", world::SearchStrategy::Linear}};
  return strategies;
}

// The values of --geometry: the collision predicates of the World's state queries.
const std::vector<std::string>& geometryModes() {
  static const std::vector<std::string> modes{"bounded", "exact"};
  return modes;
}

void printSummary(const world::World& world, const tamp::SolveResult& result) {
  const tamp::GeometricStatistics& geometric = result.geometric;
  const motion::CheckStatistics& checks = geometric.checks;
  const symbolic::TreeMetrics metrics = symbolic::measure(result.plan);
  std::cerr << "kaboum solve: " << toString(result.status);
  if (result.status == PlannerStatus::Solved) {
    std::cerr << fmt::format(", {} action(s), {} leaf/leaves", metrics.actions, metrics.leaves);
  }
  std::cerr << fmt::format(
      "; {:.3f} s (symbolic {:.3f} s, geometric {:.3f} s: {} IK sample(s) {:.3f} s, {} motion "
      "query(ies) {:.3f} s, {} state and {} motion check(s) {:.3f} s, {} positive); {} geometric "
      "state(s), {} expanded; {} predicates, epsilon {}\n",
      result.seconds, result.symbolicSeconds, result.geometricSeconds, geometric.ikCalls,
      geometric.ikSeconds, geometric.motionQueries, geometric.motionSeconds, checks.stateChecks,
      checks.motionChecks, checks.stateSeconds + checks.motionSeconds,
      checks.statePositives + checks.motionPositives, result.geometricStates,
      result.search.expanded, world.predicates() != nullptr ? "exact" : "bounded",
      io::epsilonSetting(world.description().settings));
  if (result.search.refinedSymbolicPlan) {
    std::cerr << "kaboum solve: the symbolic plan refined with geometry at every step\n";
  } else if (result.search.refinementFailed) {
    std::cerr << "kaboum solve: the symbolic plan did not refine ("
              << result.search.refinementFailure << "); searched with geometry\n";
  }
  const tamp::PlanVerification& verification = result.verification;
  if (result.status == PlannerStatus::Solved) {
    std::cerr << fmt::format("verification: symbolic {}",
                             verification.symbolic.valid ? "valid" : "INVALID");
    if (verification.pathsChecked) {
      std::cerr << fmt::format(
          "; {} path(s), {} sample(s) on the original meshes, {} colliding, smallest clearance "
          "{:.1f} mm ({:.2f} s)",
          verification.paths, verification.samples, verification.collidingPaths,
          1000 * verification.smallestClearance, verification.seconds);
    }
    std::cerr << "\n";
  }
  if (!result.message.empty()) std::cerr << "kaboum solve: " << result.message << "\n";
  if (result.status != PlannerStatus::Solved && !geometric.recentFailures.empty()) {
    std::cerr << "kaboum solve: the latest geometric failures:\n";
    for (const std::string& failure : geometric.recentFailures) {
      std::cerr << "  " << failure << "\n";
    }
  }
}

int run(Options& options) {
  options.solve.geometry.motion.timeLimit = options.motionTimeLimit;
  options.solve.geometry.placementStrategy = placementStrategies().at(options.placement);
  // The PDDL first: its mistakes show before the scene's preprocessing.
  symbolic::ContingentProblem problem =
      symbolic::loadContingent(options.files.domain, options.files.problem);
  printWarnings(problem.domain.warnings);
  printWarnings(problem.problem.warnings);
  world::World world = loadWorld(options.files.scene, options.load);
  std::unique_ptr<verify::ExactPredicates> exact;
  if (options.geometry == "exact") {
    exact = std::make_unique<verify::ExactPredicates>(world);
    world.usePredicates(exact.get());
  }
  const tamp::Solver* progressOf = nullptr;  // set once the solver exists
  if (!options.quiet) {
    options.solve.search.progress = [&progressOf](const symbolic::ContingentStatistics& search) {
      const tamp::GeometricStatistics& geometric = progressOf->attachments().statistics();
      std::cerr << fmt::format(
          "kaboum solve: {:.0f} s, {} expanded, {} geometric state(s), {} motion query(ies), {} "
          "failed geometric call(s)\n",
          search.seconds, search.expanded, progressOf->attachments().map().size(),
          geometric.motionQueries, geometric.failures);
    };
    options.solve.search.progressPeriod = 5;
  }
  options.solve.search.limits.memoryBytes =
      static_cast<std::size_t>(options.memoryLimitMegabytes * 1e6);
  tamp::Solver solver(world, std::move(problem), options.solve);
  progressOf = &solver;
  const tamp::SolveResult result = solver.solve();
  const bool solved = result.status == PlannerStatus::Solved && result.verification.passed();
  const nlohmann::json plan = tamp::planFileJson(solver, result, options.files);
  if (solved && !options.planOut.empty()) {
    std::ofstream out(options.planOut);
    if (!out || !(out << plan.dump(1) << "\n")) {
      throw InputError(locate(options.planOut, "cannot write the plan file"));
    }
  }
  if (solved && !options.html.empty()) {
    const tamp::PlanFileContents contents =
        tamp::readPlanFile(plan, options.files.problem, solver.task(), world);
    const std::string name = options.planOut.empty() ? options.files.problem : options.planOut;
    const web::PageSummary page = writePlanPage(options.html, name, world, solver.task(), contents);
    if (!options.quiet) std::cerr << pageLine(options.html, page) << "\n";
  }
  if (options.json) {
    std::cout << plan.dump(2) << "\n";
  } else if (result.status == PlannerStatus::Solved) {
    const std::string tree = symbolic::formatPlanTree(solver.task(), result.plan);
    std::cout << tree << (tree.ends_with('\n') ? "" : "\n");
  }
  if (!options.quiet || !solved) printSummary(world, result);
  return solved ? 0 : 1;
}

VerbRunner setup(CLI::App& command) {
  auto options = std::make_shared<Options>();
  command.add_option("domain", options->files.domain, "PDDL domain with geometric attachments")
      ->required();
  command.add_option("problem", options->files.problem, "PDDL problem")->required();
  command.add_option("scene", options->files.scene, "Scene file (docs/scene-format.md)")
      ->required();
  command
      .add_option("--search", options->solve.search.mode,
                  "Search between branch points: gbfs (greedy best-first), astar, bfs, dfs, ids "
                  "(iterative deepening)")
      ->check(CLI::IsMember(symbolic::contingentSearchModes()))
      ->capture_default_str();
  command
      .add_option("--heuristic", options->solve.search.heuristic,
                  "Heuristic of gbfs and astar, evaluated in every world (maximum)")
      ->check(CLI::IsMember(symbolic::heuristicNames()))
      ->capture_default_str();
  options->solve.search.limits.seconds = 60;
  command
      .add_option("--time-limit", options->solve.search.limits.seconds,
                  "Search time limit (s): geometric state spaces are unbounded (every move or "
                  "placement may lead to a new state)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--node-limit", options->solve.search.limits.expansions,
                  "Maximum number of expanded knowledge states")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--memory-limit", options->memoryLimitMegabytes,
                  "Memory limit of the search's knowledge states (MB)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--max-worlds", options->solve.maxWorlds,
                  "Maximum number of possible initial worlds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--seed", options->solve.geometry.seed,
                  "Seed of the geometric sampling (grasps, placements, configurations, paths)")
      ->capture_default_str();
  command
      .add_option("--motion-time-limit", options->motionTimeLimit,
                  "Time limit of each motion query (s)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--planner", options->solve.geometry.motion.planner,
                  "Motion planner when a straight segment collides")
      ->check(CLI::IsMember(motion::motionPlannerNames()))
      ->capture_default_str();
  command
      .add_option("--placement", options->placement,
                  "How putDown samples a location for a placement (seed 003 Fig. 2): random, "
                  "quadtree (the centre first: the same placement in the same state) or linear")
      ->check(CLI::IsMember(placementStrategies()))
      ->capture_default_str();
  command
      .add_option("--geometry", options->geometry,
                  "Collision predicates: bounded (on the bounding convex decomposition, motions "
                  "certified by swept volumes) or exact (FCL on the original meshes, motions "
                  "checked at the scene's joint_step; thesis Proposition 4)")
      ->check(CLI::IsMember(geometryModes()))
      ->capture_default_str();
  command
      .add_option("--grasp-samples", options->solve.geometry.graspSamples,
                  "Grasps tried per pickUp call")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--samples", options->solve.search.samples,
                  "Geometric samples per (state, action): successors of an action with "
                  "geometric effects (1: the thesis's branching factor of one)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  command.add_flag(
      "--integrated", [options](std::int64_t) { options->solve.search.symbolicFirst = false; },
      "Search with geometry from the start, without first refining symbolic plans");
  command.add_flag(
      "--no-verify", [options](std::int64_t) { options->solve.verify = false; },
      "Skip replaying the paths on the original meshes (the symbolic validation "
      "still runs)");
  addSceneLoadOptions(command, options->load);
  command.add_option("--plan-out", options->planOut, "Write the plan file (JSON) to FILE");
  command.add_option("--html", options->html,
                     "Write the plan as a self-contained 3-D web page to FILE (docs/viewer.md)");
  command.add_flag("--json", options->json, "Print the plan file (JSON) on stdout");
  command.add_flag("--quiet", options->quiet, "No progress or summary on stderr");
  return [options] { return run(*options); };
}

const VerbRegistration registration{
    "solve",
    "Solve a task-and-motion problem: a verified plan with certified paths (exit 0 solved, 1 "
    "not)",
    setup};

}  // namespace
}  // namespace kaboum::cli
