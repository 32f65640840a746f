// `kaboum view PLAN -o PAGE.html`: a plan file of `kaboum solve --plan-out` as one self-contained
// web page (docs/viewer.md; thesis §6.1.3): the scene in 3-D, the plan's trajectories timed as
// `kaboum execute` times them, its actions and a choice at every sensing branch, the original
// meshes or the planner's convex pieces. The domain, problem and scene are the files the plan
// names unless given. Exit code 0, or 2 on bad input.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <sstream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "page_cli.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

namespace {

struct Options {
  std::string plan;
  std::string output;
  std::string domain;
  std::string problem;
  std::string scene;
  std::string linkPosesAt;
  bool json = false;
  bool quiet = false;
  SceneLoadOptions load;
};

// The file `key` of the plan file unless `given`; it must exist from the working directory.
std::string sourceFile(const nlohmann::json& plan, const std::string& planFile,
                       const std::string& key, const std::string& given) {
  if (!given.empty()) return given;
  const auto found = plan.find(key);
  if (found == plan.end() || !found->is_string() || found->get<std::string>().empty()) {
    throw InputError(
        fmt::format("{}: {}: expected the {} file's name (or give --{})", planFile, key, key, key));
  }
  const std::string name = found->get<std::string>();
  if (!std::filesystem::exists(name)) {
    throw InputError(fmt::format(
        "{}: {}: '{}' does not exist here (the plan names it as kaboum solve was given it: run "
        "kaboum view from that folder, or give --{})",
        planFile, key, name, key));
  }
  return name;
}

// "0.5,1,2.25" as times in seconds.
std::vector<double> timesOf(const std::string& text) {
  std::vector<double> times;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    std::size_t used = 0;
    double time = 0;
    try {
      time = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !(time >= 0)) {
      throw InputError(fmt::format("--link-poses-at: '{}' is no time in seconds (>= 0)", item));
    }
    times.push_back(time);
  }
  if (times.empty()) throw InputError("--link-poses-at: expected times, e.g. 0,0.5,1.5");
  return times;
}

int run(const Options& options) {
  if (options.output.empty() && options.linkPosesAt.empty()) {
    throw InputError("-o: give the page file to write (or --link-poses-at)");
  }
  const std::vector<double> times =
      options.linkPosesAt.empty() ? std::vector<double>{} : timesOf(options.linkPosesAt);
  const nlohmann::json planJson = io::readJsonFile(options.plan);
  if (!planJson.is_object()) throw InputError(options.plan + ": expected a plan file (an object)");
  const std::string domain = sourceFile(planJson, options.plan, "domain", options.domain);
  const std::string problemFile = sourceFile(planJson, options.plan, "problem", options.problem);
  const std::string scene = sourceFile(planJson, options.plan, "scene", options.scene);
  const symbolic::ContingentProblem problem = symbolic::loadContingent(domain, problemFile);
  printWarnings(problem.domain.warnings);
  printWarnings(problem.problem.warnings);
  const world::World world = loadPlanWorld(scene, options.load, planJson, options.plan);
  tamp::GeometricAttachments attachments(world);
  symbolic::ProcedureRegistry registry;
  attachments.registerProcedures(registry);
  symbolic::KnowledgeTask task(problem, registry);
  const tamp::PlanFileContents plan = tamp::readPlanFile(planJson, options.plan, task, world);
  if (plan.plan.root < 0) throw InputError(options.plan + ": root: the file holds no plan");

  if (!times.empty()) {
    std::cout << web::linkPosesAt(world, task, plan, {}, times).dump(options.json ? -1 : 2) << "\n";
    if (options.output.empty()) return 0;
  }
  const web::PageSummary summary = writePlanPage(options.output, options.plan, world, task, plan);
  if (options.json && times.empty()) {
    std::cout << pageJson(options.output, summary).dump(2) << "\n";
  } else if (!options.quiet && times.empty()) {
    std::cout << pageLine(options.output, summary) << "\n";
  }
  return 0;
}

VerbRunner setup(CLI::App& command) {
  auto options = std::make_shared<Options>();
  command.add_option("plan", options->plan, "Plan file of kaboum solve --plan-out")->required();
  command.add_option("-o,--output", options->output, "The page to write (HTML)");
  command.add_option("--domain", options->domain, "PDDL domain (default: the plan file's)");
  command.add_option("--problem", options->problem, "PDDL problem (default: the plan file's)");
  command.add_option("--scene", options->scene, "Scene file (default: the plan file's)");
  command.add_option("--link-poses-at", options->linkPosesAt,
                     "Print every robot link's world pose at these times (T1,T2,…; seconds) "
                     "along the run the page opens with, as JSON");
  addSceneLoadOptions(command, options->load);
  command.add_flag("--json", options->json, "Print the page's summary as JSON");
  command.add_flag("-q,--quiet", options->quiet, "Print nothing");
  return [options] { return run(*options); };
}

const VerbRegistration registration{
    "view",
    "Write a plan file as one self-contained 3-D web page: the scene, the plan's trajectories, "
    "its actions and sensing branches (docs/viewer.md)",
    setup};

}  // namespace
}  // namespace kaboum::cli
