// `kaboum verify-path SCENE PATH [--joint-step DEG] [--tool-step MM] [--json] [--quiet]`: replays
// a path file densely in a scene and checks every sample with FCL on the original meshes, the
// independent reference of the planner's certified motions (thesis §4.5; docs/verify.md). Exit
// code 0 when collision-free, 1 when a collision is found, 2 on bad input.
#include <fmt/format.h>

#include <iostream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/verify/path_verifier.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::verify;

namespace {

struct Options {
  std::string scene;
  std::string path;
  VerifyStepOptions steps;
  bool json = false;
  bool quiet = false;
  SceneLoadOptions load;
};

// Paths of at least this many samples report their progress on stderr.
constexpr std::size_t kSamplesWithProgress = 5000;

std::string placeText(const PathPlace& place) {
  return fmt::format("segment {} at {:.3f}", place.segment, place.fraction);
}

void printReport(const Options& options, const ScenePath& path, const PathVerification& result,
                 const ReferenceGeometry& geometry) {
  fmt::print("scene:      {}\n", options.scene);
  fmt::print("path:       {} ({} waypoints)\n", options.path, path.waypoints.size());
  fmt::print("reference:  FCL, {} mesh triangles, built in {:.3f} s\n", geometry.triangleCount(),
             geometry.buildSeconds());
  fmt::print("samples:    {} (joint step {:g} deg, tool step {:g} mm), {} pairs each\n",
             result.samples, options.steps.jointStepDegrees, options.steps.toolStepMillimetres,
             result.pairs);
  if (result.clearance) {
    const Clearance& clearance = *result.clearance;
    fmt::print("clearance:  {:.2f} mm between {} and {}, {}\n", 1000 * clearance.distance,
               describe(clearance.first), describe(clearance.second), placeText(clearance.where));
  }
  for (const PathCollision& collision : result.collisions) {
    fmt::print("collision:  {} with {}, {} to {} ({} samples)\n", describe(collision.first),
               describe(collision.second), placeText(collision.from), placeText(collision.to),
               collision.samples);
  }
  fmt::print("time:       {:.3f} s\n", result.seconds);
}

int run(const Options& options) {
  VerifyOptions verify = verifyOptions(options.steps);
  const io::PathFile file = io::readPathFile(options.path);
  const World world = loadWorld(options.scene, options.load);
  const ScenePath path = resolvePath(world, file, options.path);
  const ReferenceGeometry geometry(world);

  std::size_t lastTenth = 0;
  if (!options.quiet) {
    verify.progress = [&lastTenth](std::size_t done, std::size_t total) {
      if (total < kSamplesWithProgress || 10 * done / total == lastTenth) return;
      lastTenth = 10 * done / total;
      std::cerr << fmt::format("verify-path: {}% of {} samples\n", 10 * lastTenth, total);
    };
  }
  const PathVerification result = verifyPath(geometry, path, verify);

  if (options.json) {
    nlohmann::json json = toJson(result);
    json["scene"] = options.scene;
    json["path"] = options.path;
    json["joint_step"] = verify.jointStep;
    json["tool_step"] = verify.toolStep;
    std::cout << json.dump() << '\n';
  } else {
    if (!options.quiet) printReport(options, path, result, geometry);
    fmt::print("verdict:    {}\n", result.collisionFree()
                                       ? "collision-free"
                                       : fmt::format("{} collision(s)", result.collisions.size()));
  }
  return result.collisionFree() ? 0 : 1;
}

VerbRunner setupVerifyPath(CLI::App& command) {
  auto options = std::make_shared<Options>();
  command.add_option("SCENE", options->scene, "Scene file (YAML, docs/scene-format.md)")
      ->required();
  command.add_option("PATH", options->path, "Path file (JSON, docs/path-format.md)")->required();
  addVerifyStepOptions(command, options->steps);
  command.add_flag("--json", options->json, "Print one JSON object instead of lines");
  command.add_flag("-q,--quiet", options->quiet, "Print only the verdict; no progress");
  addSceneLoadOptions(command, options->load);
  return [options] { return run(*options); };
}

const VerbRegistration registration{
    "verify-path",
    "Check a path file densely with FCL on the original meshes (exit code 1 on a collision)",
    &setupVerifyPath};

}  // namespace

}  // namespace kaboum::cli
