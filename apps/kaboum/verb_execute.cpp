// `kaboum execute DOMAIN PROBLEM SCENE PLAN`: runs a plan file of `kaboum solve --plan-out`
// (thesis §6.1.3; docs/execution.md): every path timed as quintic trajectories, the plan walked
// from its root with each sensing outcome taken from a hidden state (--hidden) or a person
// (--ask), the trajectory written as JSON lines (--json) or per robot files (--out-dir); with
// --world-state, each action's geometric precondition re-checked first. Exit code 0 when the run
// reaches a goal, 1 when a precondition fails, 2 on bad input.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/exec/trajectory_files.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

namespace {

struct Options {
  std::string domain;
  std::string problem;
  std::string scene;
  std::string plan;
  std::string hidden;
  bool ask = false;
  std::string worldState;
  std::string outDirectory;
  double rate = 1000;
  std::string profile = "rest-to-rest";
  bool json = false;
  bool quiet = false;
  SceneLoadOptions load;
};

void writeFiles(const std::filesystem::path& directory, const world::World& world,
                const exec::ExecutionResult& result, double rate) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw InputError(
        fmt::format("--out-dir {}: cannot create it ({})", directory.string(), error.message()));
  }
  const auto open = [&](const std::string& name) {
    std::ofstream file(directory / name);
    if (!file) throw InputError(fmt::format("{}: cannot write it", (directory / name).string()));
    return file;
  };
  for (std::size_t r = 0; r < result.schedule.robotCount(); ++r) {
    const exec::RobotSamples samples = exec::sampleRobot(result.schedule, r, rate);
    const std::string& name = world.description().robots[r].name;
    open(name + ".json") << exec::robotTrajectoryJson(world, result.schedule, samples, rate).dump()
                         << '\n';
    std::ofstream csv = open(name + ".csv");
    exec::writeRobotTrajectoryCsv(csv, world, samples);
  }
  open("execution.json") << exec::executionJson(world, result, rate).dump(2) << '\n';
}

std::string branchText(const exec::BranchTiming& branch) {
  return fmt::format("[{}] {} action(s), {:.3f} s",
                     branch.outcomes.empty() ? std::string("no sensing")
                                             : fmt::format("{}", fmt::join(branch.outcomes, ", ")),
                     branch.actions.size(), branch.seconds);
}

void printLog(const world::World& world, const exec::ExecutionResult& result) {
  const exec::Schedule& schedule = result.schedule;
  for (const exec::LogRecord& record : exec::executionLog(result)) {
    if (record.kind == exec::LogRecord::Kind::Sensing) {
      const exec::SensingOutcome& outcome = result.sensed[record.index];
      fmt::print("sensed:   {:9.3f} s  {} {}\n", outcome.time, outcome.test,
                 outcome.value ? "true" : "false");
    } else if (record.kind == exec::LogRecord::Kind::Action) {
      const exec::TimedAction& action = schedule.actions()[record.index];
      fmt::print("action:   {:9.3f} s  {} ({:.3f} s)\n", action.start, action.name,
                 action.end - action.start);
    } else {
      const exec::GripperEvent& event = schedule.events()[record.index];
      fmt::print("gripper:  {:9.3f} s  {} {} by {}\n", event.time, tamp::toString(event.kind),
                 world.scene().name(event.object), world.description().robots[event.robot].name);
    }
  }
  for (std::size_t b = 0; b < result.branches.size(); ++b) {
    fmt::print("branch {}: {}\n", b + 1, branchText(result.branches[b]));
  }
}

int run(const Options& options) {
  if (options.ask && !options.hidden.empty()) {
    throw InputError("--ask and --hidden: give one sensing source");
  }
  if (!(options.rate > 0) || options.rate > 1e6) {
    throw InputError(fmt::format("--rate {}: expected a rate in (0, 1e6] Hz", options.rate));
  }
  exec::ExecutionOptions execution;
  try {
    execution.trajectory.profile = exec::profileNamed(options.profile);
  } catch (const std::invalid_argument& error) {
    throw InputError(std::string("--profile: ") + error.what());
  }
  const symbolic::ContingentProblem problem =
      symbolic::loadContingent(options.domain, options.problem);
  printWarnings(problem.domain.warnings);
  printWarnings(problem.problem.warnings);
  const nlohmann::json planJson = io::readJsonFile(options.plan);
  const nlohmann::json worldStateJson =
      options.worldState.empty() ? nlohmann::json() : io::readJsonFile(options.worldState);
  const world::World world = loadPlanWorld(options.scene, options.load, planJson, options.plan);
  tamp::GeometricAttachments attachments(world);
  symbolic::ProcedureRegistry registry;
  attachments.registerProcedures(registry);
  symbolic::KnowledgeTask task(problem, registry);
  const tamp::PlanFileContents plan = tamp::readPlanFile(planJson, options.plan, task, world);
  if (plan.plan.root < 0) throw InputError(options.plan + ": root: the file holds no plan");
  exec::WorldObservation observed;
  if (!options.worldState.empty()) {
    observed = exec::readWorldObservation(worldStateJson, options.worldState, world);
    execution.observed = &observed;
  }
  if (!options.hidden.empty()) {
    const std::vector<symbolic::HiddenState> hidden =
        symbolic::parseHidden(symbolic::readTextFile(options.hidden), options.hidden, problem);
    execution.sensing =
        exec::hiddenStateSource(task, task.hiddenWorld(hidden.front(), options.hidden));
  } else if (options.ask) {
    execution.sensing = exec::promptSource(std::cin, std::cerr);
  }
  const exec::ExecutionResult result = exec::execute(world, task, plan, execution);
  if (!options.outDirectory.empty()) writeFiles(options.outDirectory, world, result, options.rate);
  if (options.json) {
    exec::writeExecutionStream(std::cout, world, result, options.rate);
    return result.reachedGoal ? 0 : 1;
  }
  if (!options.quiet) printLog(world, result);
  std::vector<std::string> outcomes;
  for (const exec::SensingOutcome& outcome : result.sensed) {
    outcomes.push_back(outcome.test + (outcome.value ? " true" : " false"));
  }
  const std::string branch =
      outcomes.empty() ? std::string("no sensing") : fmt::format("{}", fmt::join(outcomes, ", "));
  if (result.reachedGoal) {
    fmt::print("execution: goal reached after {} action(s) in {:.3f} s; branch: {}\n",
               result.schedule.actions().size(), result.schedule.duration(), branch);
  } else {
    fmt::print("execution: STOPPED at {:.3f} s: {}\n", result.schedule.duration(),
               result.stopReason);
  }
  return result.reachedGoal ? 0 : 1;
}

VerbRunner setup(CLI::App& command) {
  auto options = std::make_shared<Options>();
  command.add_option("domain", options->domain, "PDDL domain with geometric attachments")
      ->required();
  command.add_option("problem", options->problem, "PDDL problem")->required();
  command.add_option("scene", options->scene, "Scene file (docs/scene-format.md)")->required();
  command.add_option("plan", options->plan, "Plan file of kaboum solve --plan-out")->required();
  command.add_option("--hidden", options->hidden,
                     "Sensing outcomes from the first (:hidden atoms…) true initial state of FILE");
  command.add_flag("--ask", options->ask, "Ask each sensing outcome on the terminal (y/n)");
  command.add_option("--world-state", options->worldState,
                     "Observed object poses (JSON, docs/execution.md): re-check each action's "
                     "geometric precondition against them (exit 1 when one fails)");
  command.add_option("--out-dir", options->outDirectory,
                     "Write ROBOT.csv, ROBOT.json per robot and execution.json into DIR");
  command.add_option("--rate", options->rate, "Samples per second")->capture_default_str();
  command
      .add_option("--profile", options->profile, "rest-to-rest (on the certified path) or blended")
      ->capture_default_str();
  addSceneLoadOptions(command, options->load);
  command.add_flag("--json", options->json,
                   "Print the run as JSON lines (actions, sensing, gripper events, samples, end)");
  command.add_flag("-q,--quiet", options->quiet, "Print only the outcome line");
  return [options] { return run(*options); };
}

const VerbRegistration registration{
    "execute",
    "Run a plan file: time its paths as quintic trajectories, follow its sensing branches "
    "(--hidden or --ask), write the trajectory (exit 1 when a re-checked precondition fails)",
    setup};

}  // namespace
}  // namespace kaboum::cli
