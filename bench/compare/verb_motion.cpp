// `kaboum-compare motion`: the MotionBenchMaker benchmark (Panda), and seeded random queries in
// kaboum scene files (the scenes MotionBenchMaker lacks: two arms sharing a workspace, a mobile
// manipulator), kaboum's certified motion planning (thesis §6.1.2, §4.5) against the set-up
// MoveIt users have today (OMPL's RRT-Connect, FCL on the original meshes, motions checked at 1°
// steps, OMPL's path simplifier) on the same queries, every path of both checked by the
// independent verifier (FCL on the original meshes, 0.5° and 1 mm samples).
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_statistics.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/moveit_scene.hpp"
#include "kaboum/motion/motion_planner.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/path_verifier.hpp"
#include "ompl_fcl_baseline.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct MotionBenchOptions {
  std::string problems = testing::dataFile("motionbenchmaker");
  std::size_t every = 1;  // every N-th problem, from the first
  std::size_t limit = 0;  // 0: every problem
  // A kaboum scene file instead of the problems: `queries` random start/goal pairs of `robots`
  // (names; empty: every robot of the scene moving together).
  std::string scene;
  std::size_t queries = 20;
  std::vector<std::string> robots;
  double timeLimit = 10;
  std::uint64_t seed = 1;
  std::optional<double> sweepEpsilon;
  SceneLoadOptions load;
  bool json = false;
  bool quiet = false;
};

io::MoveItRobot panda() {
  return {testing::dataFile("robots/panda/panda.urdf"),
          testing::dataFile("robots/panda/panda.srdf"),
          "panda_arm",
          {"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4", "panda_joint5",
           "panda_joint6", "panda_joint7"}};
}

// One planner on one problem, its path checked by the verifier.
struct PlannerRun {
  std::string status;
  std::string message;  // why it failed
  bool solved = false;
  double seconds = 0;     // wall time of the query: planning and path simplification
  double cpuSeconds = 0;  // CPU time of this thread over the same
  std::size_t plannedWaypoints = 0;
  std::size_t waypoints = 0;
  double plannedLength = 0;
  double length = 0;
  std::size_t stateChecks = 0;
  std::size_t motionChecks = 0;
  // Where the time went: the sampling-based planner, then shortcutting or simplification; and
  // (kaboum) the seconds in state and motion checks, whether the straight segment was taken.
  double planningSeconds = 0;
  double simplifySeconds = 0;
  double stateCheckSeconds = 0;
  double motionCheckSeconds = 0;
  bool straight = false;
  // The verifier's verdict on the returned path; unset unless solved.
  std::optional<bool> collisionFree;
  std::optional<double> clearance;
  std::string collision;  // the first colliding pair, described

  [[nodiscard]] bool valid() const { return solved && collisionFree.value_or(false); }
};

struct ProblemRun {
  std::string name;
  double worldSeconds = 0;  // building the World (not part of planning)
  PlannerRun kaboum;
  PlannerRun ompl;
};

double cpuSecondsSince(double startNanoseconds) {
  return 1e-9 * (threadNanoseconds() - startNanoseconds);
}

void verifyRun(const verify::ReferenceGeometry& geometry, const motion::MotionGroup& group,
               const std::vector<std::vector<double>>& path, PlannerRun& run) {
  const verify::PathVerification verification =
      verify::verifyPath(geometry, verify::ScenePath{group.robots(), path, {}, std::nullopt});
  run.collisionFree = verification.collisionFree();
  if (verification.clearance) run.clearance = verification.clearance->distance;
  if (!verification.collisions.empty()) {
    const verify::PathCollision& first = verification.collisions.front();
    run.collision = verify::describe(first.first) + " with " + verify::describe(first.second) +
                    ", segment " + std::to_string(first.from.segment);
  }
}

// One query: its start and goal, configurations of the motion group.
struct Query {
  std::vector<double> start, goal;
};

PlannerRun runKaboum(const motion::MotionGroup& group, const Query& query,
                     const motion::MotionOptions& options, std::vector<std::vector<double>>& path) {
  const double cpu = threadNanoseconds();
  motion::MotionResult result = motion::planMotion(group, query.start, query.goal, options);
  PlannerRun run;
  run.cpuSeconds = cpuSecondsSince(cpu);
  run.status = toString(result.status);
  run.message = result.message;
  run.solved = result.status == PlannerStatus::Solved;
  const motion::MotionStatistics& statistics = result.statistics;
  run.seconds = statistics.totalSeconds;
  run.plannedWaypoints = statistics.plannedWaypoints;
  run.waypoints = result.path.size();
  run.plannedLength = statistics.plannedLength;
  run.length = statistics.length;
  run.stateChecks = statistics.checks.stateChecks;
  run.motionChecks = statistics.checks.motionChecks;
  run.planningSeconds = statistics.planningSeconds;
  run.simplifySeconds = statistics.shortcutSeconds;
  run.stateCheckSeconds = statistics.checks.stateSeconds;
  run.motionCheckSeconds = statistics.checks.motionSeconds;
  run.straight = statistics.straight;
  path = std::move(result.path);
  return run;
}

PlannerRun runOmplFcl(const motion::MotionGroup& group, FclStateChecker& checker,
                      const Query& query, double timeLimit,
                      std::vector<std::vector<double>>& path) {
  const double cpu = threadNanoseconds();
  OmplFclResult result = planWithOmplFcl(group, checker, query.start, query.goal,
                                         OmplFclOptions{timeLimit, OmplFclOptions{}.resolution});
  PlannerRun run;
  run.cpuSeconds = cpuSecondsSince(cpu);
  run.status = result.solved ? "solved" : result.status;
  run.solved = result.solved;
  if (!result.solved) run.message = "RRT-Connect: " + result.status;
  run.seconds = result.planningSeconds + result.simplifySeconds;
  run.plannedWaypoints = result.plannedWaypoints;
  run.waypoints = result.path.size();
  run.plannedLength = result.plannedLength;
  run.length = result.length;
  run.stateChecks = result.stateChecks;
  run.planningSeconds = result.planningSeconds;
  run.simplifySeconds = result.simplifySeconds;
  path = std::move(result.path);
  return run;
}

std::string millis(double seconds) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(seconds < 0.01 ? 3 : 1) << 1e3 * seconds;
  return out.str();
}

std::string verdict(const PlannerRun& run) {
  if (!run.solved) return run.status;
  std::string text =
      "solved " + millis(run.seconds) + " ms, " + std::to_string(run.waypoints) + " waypoints, ";
  if (!run.collisionFree.value_or(false)) return text + "COLLIDES: " + run.collision;
  std::ostringstream clearance;
  clearance << std::fixed << std::setprecision(2) << 1e3 * run.clearance.value_or(0);
  return text + "verified (clearance " + clearance.str() + " mm)";
}

motion::MotionOptions motionOptions(const MotionBenchOptions& options) {
  motion::MotionOptions motionOptions;
  motionOptions.timeLimit = options.timeLimit;
  motionOptions.seed = options.seed;
  motionOptions.sweepEpsilon = options.sweepEpsilon;
  return motionOptions;
}

// Both planners on one query of `group`, each path checked by the verifier.
void runQuery(const motion::MotionGroup& group, const verify::ReferenceGeometry& geometry,
              const Query& query, const MotionBenchOptions& options, ProblemRun& run) {
  std::vector<std::vector<double>> path;
  run.kaboum = runKaboum(group, query, motionOptions(options), path);
  if (run.kaboum.solved) verifyRun(geometry, group, path, run.kaboum);
  FclStateChecker checker(geometry, group);
  run.ompl = runOmplFcl(group, checker, query, options.timeLimit, path);
  if (run.ompl.solved) verifyRun(geometry, group, path, run.ompl);
}

ProblemRun runProblem(const io::MoveItProblemFiles& files, const MotionBenchOptions& options,
                      double& sweepEpsilon) {
  const io::MotionProblem problem = io::readMoveItProblem(files.scene, files.request, panda());
  ProblemRun run;
  run.name = problem.name;
  world::WorldOptions worldOptions;
  worldOptions.cacheDirectory = cacheDirectory(options.load);
  const Clock::time_point building = Clock::now();
  const world::World world(problem.scene, worldOptions);
  run.worldSeconds = std::chrono::duration<double>(Clock::now() - building).count();
  const auto named = world.find(problem.robot);
  if (!named || named->kind != world::NamedEntity::Kind::Robot) {
    throw InputError(problem.name + ": no robot '" + problem.robot + "' in the World");
  }
  const motion::MotionGroup group(world, world.initialState(), {named->index});
  const verify::ReferenceGeometry geometry(world);
  sweepEpsilon = motion::sweepEpsilonOf(group, motionOptions(options));
  runQuery(group, geometry, {problem.start, problem.goal}, options, run);
  return run;
}

// A random free configuration of `group` (motion::randomFreeConfiguration).
std::vector<double> freeConfiguration(const motion::MotionGroup& group, double clearance,
                                      std::mt19937_64& random) {
  auto q = motion::randomFreeConfiguration(group, clearance, random);
  if (!q) throw InputError("no free configuration in 100000 random draws");
  return std::move(*q);
}

// `options.queries` random queries in the scene file: start and goal drawn by freeConfiguration
// with the scene's seed, both planners on each.
std::vector<ProblemRun> runScene(const MotionBenchOptions& options, double& sweepEpsilon) {
  const Clock::time_point building = Clock::now();
  const world::World world = loadWorld(options.scene, options.load);
  const double worldSeconds = std::chrono::duration<double>(Clock::now() - building).count();
  std::vector<std::size_t> robots;
  for (const std::string& name : options.robots) {
    const auto named = world.find(name);
    if (!named || named->kind != world::NamedEntity::Kind::Robot) {
      throw InputError(options.scene + ": no robot '" + name + "' in the scene");
    }
    robots.push_back(named->index);
  }
  if (robots.empty()) {
    for (std::size_t robot = 0; robot < world.robots().size(); ++robot) robots.push_back(robot);
  }
  if (robots.empty()) throw InputError(options.scene + ": the scene has no robot");
  const motion::MotionGroup group(world, world.initialState(), robots);
  const verify::ReferenceGeometry geometry(world);
  sweepEpsilon = motion::sweepEpsilonOf(group, motionOptions(options));
  std::mt19937_64 random(world.description().settings.seed);
  const std::string stem = fs::path(options.scene).stem().string();
  std::vector<ProblemRun> runs;
  for (std::size_t i = 0; i < options.queries; ++i) {
    Query query;
    query.start = freeConfiguration(group, sweepEpsilon, random);
    query.goal = freeConfiguration(group, sweepEpsilon, random);
    ProblemRun& run = runs.emplace_back();
    std::ostringstream name;
    name << stem << "/query" << std::setw(2) << std::setfill('0') << i;
    run.name = name.str();
    run.worldSeconds = worldSeconds;
    runQuery(group, geometry, query, options, run);
    if (!options.quiet) {
      std::cerr << "[" << i + 1 << "/" << options.queries << "] " << run.name << ": kaboum "
                << verdict(run.kaboum) << "; OMPL+FCL " << verdict(run.ompl) << std::endl;
    }
  }
  return runs;
}

// The figures of one planner over every problem: counts, times of the solved queries, lengths,
// colliding paths, the smallest clearance, and the failures.
nlohmann::json summarize(const std::vector<ProblemRun>& runs, PlannerRun ProblemRun::*planner) {
  std::vector<double> seconds, cpuSeconds, plannedLengths, lengths;
  std::size_t solved = 0, valid = 0, colliding = 0;
  std::optional<double> clearance;
  nlohmann::json failures = nlohmann::json::array();
  nlohmann::json collisions = nlohmann::json::array();
  for (const ProblemRun& problem : runs) {
    const PlannerRun& run = problem.*planner;
    if (!run.solved) {
      failures.push_back(
          {{"problem", problem.name}, {"status", run.status}, {"message", run.message}});
      continue;
    }
    ++solved;
    seconds.push_back(run.seconds);
    cpuSeconds.push_back(run.cpuSeconds);
    plannedLengths.push_back(run.plannedLength);
    lengths.push_back(run.length);
    if (run.valid()) {
      ++valid;
    } else {
      ++colliding;
      collisions.push_back({{"problem", problem.name}, {"collision", run.collision}});
    }
    if (run.clearance) clearance = std::min(clearance.value_or(*run.clearance), *run.clearance);
  }
  const auto timeStats = [](const std::vector<double>& values) -> nlohmann::json {
    if (values.empty()) return nullptr;
    return {{"median", 1e3 * median(values)},
            {"p95", 1e3 * percentile(values, 0.95)},
            {"max", 1e3 * *std::max_element(values.begin(), values.end())}};
  };
  const auto medianOrNull = [](const std::vector<double>& values) -> nlohmann::json {
    if (values.empty()) return nullptr;
    return median(values);
  };
  return {{"solved", solved},
          {"valid", valid},
          {"total", runs.size()},
          {"colliding_paths", colliding},
          {"time_ms", timeStats(seconds)},
          {"cpu_time_ms", timeStats(cpuSeconds)},
          {"length_before_median", medianOrNull(plannedLengths)},
          {"length_after_median", medianOrNull(lengths)},
          {"min_clearance", clearance ? nlohmann::json(*clearance) : nlohmann::json(nullptr)},
          {"failures", failures},
          {"collisions", collisions}};
}

nlohmann::json runJson(const PlannerRun& run) {
  return {{"status", run.status},
          {"message", run.message},
          {"seconds", run.seconds},
          {"cpu_seconds", run.cpuSeconds},
          {"planned_waypoints", run.plannedWaypoints},
          {"waypoints", run.waypoints},
          {"planned_length", run.plannedLength},
          {"length", run.length},
          {"state_checks", run.stateChecks},
          {"motion_checks", run.motionChecks},
          {"planning_seconds", run.planningSeconds},
          {"simplify_seconds", run.simplifySeconds},
          {"state_check_seconds", run.stateCheckSeconds},
          {"motion_check_seconds", run.motionCheckSeconds},
          {"straight", run.straight},
          {"collision_free", run.collisionFree ? nlohmann::json(*run.collisionFree) : nullptr},
          {"clearance", run.clearance ? nlohmann::json(*run.clearance) : nullptr},
          {"collision", run.collision}};
}

// Medians over the problems both planners solved: OMPL+FCL's over kaboum's.
nlohmann::json ratioOfMedians(const std::vector<ProblemRun>& runs, double PlannerRun::*time) {
  std::vector<double> kaboum, ompl;
  for (const ProblemRun& run : runs) {
    if (run.kaboum.solved && run.ompl.solved) {
      kaboum.push_back(run.kaboum.*time);
      ompl.push_back(run.ompl.*time);
    }
  }
  if (kaboum.empty()) return nullptr;
  return median(ompl) / median(kaboum);
}

nlohmann::json figures(const std::vector<ProblemRun>& runs, const MotionBenchOptions& options,
                       double sweepEpsilon) {
  std::vector<double> worldSeconds;
  nlohmann::json problems = nlohmann::json::array();
  for (const ProblemRun& run : runs) {
    worldSeconds.push_back(run.worldSeconds);
    problems.push_back({{"problem", run.name},
                        {"world_seconds", run.worldSeconds},
                        {"kaboum", runJson(run.kaboum)},
                        {"ompl_fcl", runJson(run.ompl)}});
  }
  std::size_t both = 0;
  for (const ProblemRun& run : runs) both += run.kaboum.solved && run.ompl.solved ? 1 : 0;
  return {{"problems", options.scene.empty() ? options.problems : options.scene},
          {"scene", !options.scene.empty()},
          {"every", options.every},
          {"count", runs.size()},
          {"time_limit", options.timeLimit},
          {"seed", options.seed},
          {"sweep_epsilon", sweepEpsilon},
          {"ompl_resolution_deg", 1.0},
          {"world_seconds",
           {{"median", median(worldSeconds)},
            {"max", *std::max_element(worldSeconds.begin(), worldSeconds.end())}}},
          {"kaboum", summarize(runs, &ProblemRun::kaboum)},
          {"ompl_fcl", summarize(runs, &ProblemRun::ompl)},
          {"both_solved", both},
          {"ratio_of_medians", ratioOfMedians(runs, &PlannerRun::seconds)},
          {"cpu_ratio_of_medians", ratioOfMedians(runs, &PlannerRun::cpuSeconds)},
          {"runs", problems}};
}

// `value` times `scale` with `precision` decimals; "-" for null.
std::string number(const nlohmann::json& value, int precision, double scale = 1) {
  if (value.is_null()) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << scale * value.get<double>();
  return out.str();
}

void printTable(const nlohmann::json& f, std::ostream& out) {
  if (f["scene"].get<bool>()) {
    out << "Scene " << f["problems"].get<std::string>() << ": " << f["count"]
        << " random queries, time limit ";
  } else {
    out << "MotionBenchMaker: " << f["count"] << " problems of " << f["problems"].get<std::string>()
        << (f["every"] == 1 ? "" : " (every " + f["every"].dump() + "th)") << ", time limit ";
  }
  out << f["time_limit"] << " s, seed " << f["seed"] << ", sweep epsilon "
      << 1e3 * f["sweep_epsilon"].get<double>() << " mm, OMPL+FCL motions at 1 deg\n"
      << "World build: median " << number(f["world_seconds"]["median"], 3) << " s, max "
      << number(f["world_seconds"]["max"], 3) << " s (not part of planning)\n\n";
  const auto row = [&](const std::string& name, const nlohmann::json& s) {
    const auto ms = [&](const char* stat, const char* key) {
      return s[stat].is_null() ? std::string("-") : number(s[stat][key], 3);
    };
    const std::string counts =
        s["solved"].dump() + " / " + s["valid"].dump() + " / " + s["total"].dump();
    out << std::left << std::setw(10) << name << std::right << std::setw(18) << counts
        << std::setw(11) << ms("time_ms", "median") << std::setw(11) << ms("time_ms", "p95")
        << std::setw(11) << ms("time_ms", "max") << std::setw(11) << ms("cpu_time_ms", "median")
        << std::setw(9) << number(s["length_before_median"], 2) << std::setw(8)
        << number(s["length_after_median"], 2) << std::setw(10) << s["colliding_paths"] << "\n";
  };
  out << "planner   solved/valid/total  median ms     p95 ms     max ms cpu med ms  length "
         "before/after  colliding\n";
  row("kaboum", f["kaboum"]);
  row("OMPL+FCL", f["ompl_fcl"]);
  out << "\nratio of medians (OMPL+FCL / kaboum, " << f["both_solved"]
      << " problems both solved): wall " << number(f["ratio_of_medians"], 1) << ", cpu "
      << number(f["cpu_ratio_of_medians"], 1) << "\n";
  out << "smallest verified clearance: kaboum " << number(f["kaboum"]["min_clearance"], 2, 1e3)
      << " mm, OMPL+FCL " << number(f["ompl_fcl"]["min_clearance"], 2, 1e3) << " mm\n";
  for (const auto& [key, name] :
       {std::pair{"kaboum", "kaboum"}, std::pair{"ompl_fcl", "OMPL+FCL"}}) {
    for (const auto& failure : f[key]["failures"]) {
      out << name << " failed " << failure["problem"].get<std::string>() << ": "
          << failure["status"].get<std::string>() << " (" << failure["message"].get<std::string>()
          << ")\n";
    }
    for (const auto& collision : f[key]["collisions"]) {
      out << name << " path collides " << collision["problem"].get<std::string>() << ": "
          << collision["collision"].get<std::string>() << "\n";
    }
  }
}

// Prints the figures (a table, or JSON); exit code 1 when a kaboum path collides.
int report(const std::vector<ProblemRun>& runs, const MotionBenchOptions& options,
           double sweepEpsilon) {
  const nlohmann::json f = figures(runs, options, sweepEpsilon);
  if (options.json) {
    std::cout << f.dump(2) << "\n";
  } else {
    printTable(f, std::cout);
  }
  return f["kaboum"]["colliding_paths"].get<std::size_t>() == 0 ? 0 : 1;
}

int runMotionBench(const MotionBenchOptions& options) {
  if (options.timeLimit <= 0) throw InputError("--time-limit must be positive");
  if (options.sweepEpsilon && *options.sweepEpsilon <= 0) {
    throw InputError("--sweep-epsilon must be positive");
  }
  // Before any OMPL generator exists: the same seed and problems give the same OMPL+FCL run.
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(options.seed));
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  double sweepEpsilon = 0;
  if (!options.scene.empty()) {
    if (options.queries == 0) throw InputError("--queries must be positive");
    const std::vector<ProblemRun> runs = runScene(options, sweepEpsilon);
    return report(runs, options, sweepEpsilon);
  }
  std::vector<io::MoveItProblemFiles> files = io::listMoveItProblems(options.problems);
  if (options.every == 0) throw InputError("--every must be positive");
  std::vector<io::MoveItProblemFiles> chosen;
  for (std::size_t i = 0; i < files.size(); i += options.every) chosen.push_back(files[i]);
  files = std::move(chosen);
  if (options.limit > 0 && files.size() > options.limit) files.resize(options.limit);
  std::vector<ProblemRun> runs;
  for (std::size_t i = 0; i < files.size(); ++i) {
    runs.push_back(runProblem(files[i], options, sweepEpsilon));
    if (!options.quiet) {
      const ProblemRun& run = runs.back();
      std::cerr << "[" << i + 1 << "/" << files.size() << "] " << run.name << ": World "
                << std::fixed << std::setprecision(2) << run.worldSeconds << " s; kaboum "
                << verdict(run.kaboum) << "; OMPL+FCL " << verdict(run.ompl) << std::endl;
    }
  }
  return report(runs, options, sweepEpsilon);
}

VerbRunner setupMotionBench(CLI::App& command) {
  auto options = std::make_shared<MotionBenchOptions>();
  CLI::Option* problems =
      command
          .add_option("--problems", options->problems,
                      "Folder of MotionBenchMaker problems (sceneNNNN.yaml, requestNNNN.yaml), "
                      "searched recursively")
          ->capture_default_str();
  command
      .add_option("--scene", options->scene,
                  "A kaboum scene file instead: random start/goal queries (free configurations "
                  "drawn with the scene's seed)")
      ->excludes(problems);
  command.add_option("--queries", options->queries, "Random queries in the --scene file")
      ->capture_default_str();
  command.add_option("--robot", options->robots,
                     "A robot of the --scene file that moves (repeat for several; default: every "
                     "robot, all moving together)");
  command
      .add_option("--every", options->every,
                  "Only every N-th problem in path order, from the first (all scenarios with "
                  "fewer problems)")
      ->capture_default_str();
  command.add_option("--limit", options->limit, "Only the first N problems (0: all)")
      ->capture_default_str();
  command.add_option("--time-limit", options->timeLimit, "Seconds per query, for each planner")
      ->capture_default_str();
  command.add_option("--seed", options->seed, "Random seed of both planners")
      ->capture_default_str();
  command.add_option("--sweep-epsilon", options->sweepEpsilon,
                     "kaboum's sweep epsilon in metres (default: the scene's, 5 mm)");
  addSceneLoadOptions(command, options->load);
  command.add_flag("--json", options->json, "Print the figures and every run as JSON");
  command.add_flag("--quiet", options->quiet, "No progress line per problem on stderr");
  return [options] { return runMotionBench(*options); };
}

const VerbRegistration registration{
    "motion",
    "MotionBenchMaker (Panda) or random queries in a scene file: kaboum's certified motion "
    "planning vs OMPL RRT-Connect with FCL on the original meshes, every path checked by the "
    "independent verifier; exit code 1 when a kaboum path collides",
    setupMotionBench};

}  // namespace

}  // namespace kaboum::cli
