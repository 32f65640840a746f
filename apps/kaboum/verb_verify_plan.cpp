// `kaboum verify-plan DOMAIN PROBLEM SCENE PLAN`: an independent check of a plan file written by
// `kaboum solve --plan-out` (thesis §6.1.3; docs/verify.md): the symbolic validator over every
// branch, and the geometry replayed from the scene's initial state with every motion checked with
// FCL on the original meshes. Exit code 0 when the plan is valid, 1 when it is not, 2 on bad
// input.
#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/tamp/plan_reader.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

namespace {

struct Options {
  std::string domain;
  std::string problem;
  std::string scene;
  std::string plan;
  VerifyStepOptions steps;
  bool json = false;
  bool quiet = false;
  SceneLoadOptions load;
};

std::string pathName(const tamp::PathCheck& path) {
  return fmt::format("nodes[{}] {} step {} ({})", path.node, path.action, path.step + 1,
                     tamp::toString(path.kind));
}

// Why the plan is invalid, or "" when it is valid.
std::string firstReason(const tamp::PlanCheck& check) {
  const tamp::PlanVerification& verification = check.verification;
  if (!verification.symbolic.valid) return "symbolic: " + verification.symbolic.message;
  if (!check.failures.empty()) return check.failures.front();
  for (const tamp::PathCheck& path : verification.checks) {
    if (path.result.collisionFree()) continue;
    const verify::PathCollision& hit = path.result.collisions.front();
    return fmt::format("collision: {}: {} with {}", pathName(path), verify::describe(hit.first),
                       verify::describe(hit.second));
  }
  return "";
}

nlohmann::json reportJson(const Options& options, const tamp::PlanCheck& check) {
  const tamp::PlanVerification& verification = check.verification;
  nlohmann::json paths = nlohmann::json::array();
  for (const tamp::PathCheck& path : verification.checks) {
    paths.push_back({{"node", path.node},
                     {"action", path.action},
                     {"step", path.step + 1},
                     {"kind", tamp::toString(path.kind)},
                     {"robot", path.robot},
                     {"verification", verify::toJson(path.result)}});
  }
  return {{"domain", options.domain},
          {"problem", options.problem},
          {"scene", options.scene},
          {"plan", options.plan},
          {"valid", check.passed()},
          {"reason", firstReason(check)},
          {"symbolic",
           {{"valid", verification.symbolic.valid}, {"message", verification.symbolic.message}}},
          {"failures", check.failures},
          {"paths", paths},
          {"samples", verification.samples},
          {"colliding_paths", verification.collidingPaths},
          {"smallest_clearance", std::isfinite(verification.smallestClearance)
                                     ? nlohmann::json(verification.smallestClearance)
                                     : nlohmann::json(nullptr)},
          {"seconds", verification.seconds}};
}

void printReport(const tamp::PlanCheck& check) {
  const tamp::PlanVerification& verification = check.verification;
  const symbolic::TreeMetrics& metrics = verification.symbolic.metrics;
  fmt::print("symbolic:   {} ({} action(s), {} leaf/leaves)\n",
             verification.symbolic.valid ? "valid" : "INVALID: " + verification.symbolic.message,
             metrics.actions, metrics.leaves);
  for (const tamp::PathCheck& path : verification.checks) {
    const verify::PathVerification& result = path.result;
    std::string line = fmt::format("path:       {}: {} samples", pathName(path), result.samples);
    if (result.clearance)
      line += fmt::format(", clearance {:.2f} mm", 1000 * result.clearance->distance);
    for (const verify::PathCollision& collision : result.collisions) {
      line += fmt::format("; collision: {} with {} ({} samples)", verify::describe(collision.first),
                          verify::describe(collision.second), collision.samples);
    }
    fmt::print("{}\n", line);
  }
  for (const std::string& failure : check.failures) fmt::print("geometry:   {}\n", failure);
  fmt::print("paths:      {} ({} samples, {} colliding), smallest clearance {}; {:.3f} s\n",
             verification.paths, verification.samples, verification.collidingPaths,
             std::isfinite(verification.smallestClearance)
                 ? fmt::format("{:.2f} mm", 1000 * verification.smallestClearance)
                 : std::string("none"),
             verification.seconds);
}

int run(const Options& options) {
  tamp::PlanCheckOptions check;
  check.verification = verifyOptions(options.steps);
  // The files that are quick to read first: their mistakes show before the scene's preprocessing.
  const symbolic::ContingentProblem problem =
      symbolic::loadContingent(options.domain, options.problem);
  printWarnings(problem.domain.warnings);
  printWarnings(problem.problem.warnings);
  const nlohmann::json plan = io::readJsonFile(options.plan);
  const world::World world = loadPlanWorld(options.scene, options.load, plan, options.plan);
  if (!options.quiet) {
    check.progress = [](const std::string& action) {
      std::cerr << "verify-plan: " << action << "\n";
    };
  }
  const tamp::PlanCheck result = tamp::verifyPlanFile(world, problem, plan, options.plan, check);
  if (options.json) {
    std::cout << reportJson(options, result).dump(2) << '\n';
  } else {
    if (!options.quiet) printReport(result);
    fmt::print("verdict:    {}\n", result.passed() ? "valid" : "INVALID: " + firstReason(result));
  }
  return result.passed() ? 0 : 1;
}

VerbRunner setup(CLI::App& command) {
  auto options = std::make_shared<Options>();
  command.add_option("domain", options->domain, "PDDL domain with geometric attachments")
      ->required();
  command.add_option("problem", options->problem, "PDDL problem")->required();
  command.add_option("scene", options->scene, "Scene file (docs/scene-format.md)")->required();
  command.add_option("plan", options->plan, "Plan file of kaboum solve --plan-out")->required();
  addVerifyStepOptions(command, options->steps);
  addSceneLoadOptions(command, options->load);
  command.add_flag("--json", options->json, "Print one JSON report instead of lines");
  command.add_flag("-q,--quiet", options->quiet, "Print only the verdict; no progress");
  return [options] { return run(*options); };
}

const VerbRegistration registration{
    "verify-plan",
    "Check a plan file of kaboum solve: every branch symbolically, every path on the original "
    "meshes (exit 1 when invalid)",
    setup};

}  // namespace
}  // namespace kaboum::cli
