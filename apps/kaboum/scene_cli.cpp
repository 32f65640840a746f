#include "scene_cli.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "kaboum/core/error.hpp"
#include "kaboum/io/scene_file.hpp"

namespace kaboum::cli {

namespace {

// The variable's value, or nullopt when it is unset or empty.
std::optional<std::filesystem::path> environmentPath(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return std::filesystem::path(value);
}

}  // namespace

void addSceneLoadOptions(CLI::App& command, SceneLoadOptions& options) {
  auto* noCache = command.add_flag("--no-cache", options.noCache,
                                   "Decompose every mesh, reading and writing no cache");
  auto* cacheDir =
      command.add_option("--cache-dir", options.cacheDirectory,
                         "Directory of the decomposition cache (default: $KABOUM_CACHE_DIR, else "
                         "$XDG_CACHE_HOME/kaboum, else $HOME/.cache/kaboum)");
  noCache->excludes(cacheDir);
  command.add_option("--threads", options.threads,
                     "Threads decomposing the scene's meshes (default: the hardware's)");
  command.add_option_function<std::string>(
      "--epsilon", [&options](const std::string& text) { options.epsilon = text; },
      "Approximation bound of the bounding convex decomposition, overriding the "
      "scene's: metres (0.005) or a percentage of each body's diagonal (1%)");
  command.add_option_function<std::uint64_t>(
      "--placement-seed", [&options](std::uint64_t seed) { options.placementSeed = seed; },
      "Seed of the objects the scene places at random (place_in), overriding the scene's "
      "placement_seed");
}

void applyEpsilonOption(const std::string& text, io::SceneSettings& settings) {
  const bool relative = text.ends_with('%');
  const std::string_view number(text.data(), text.size() - (relative ? 1 : 0));
  double value = 0;
  const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (error != std::errc() || end != number.data() + number.size() || !std::isfinite(value) ||
      !(value > 0) || (relative && value > 100)) {
    throw InputError(
        "--epsilon: expected a positive distance in metres (0.005) or a percentage of each "
        "body's diagonal above 0 and at most 100% (1%), got '" +
        text + "'");
  }
  settings.epsilonRelative = relative;
  settings.epsilon = relative ? value / 100 : value;
}

std::optional<std::filesystem::path> defaultCacheDirectory() {
  if (auto directory = environmentPath("KABOUM_CACHE_DIR")) return directory;
  if (auto xdg = environmentPath("XDG_CACHE_HOME")) return *xdg / "kaboum";
  if (auto home = environmentPath("HOME")) return *home / ".cache" / "kaboum";
  return std::nullopt;
}

std::optional<std::filesystem::path> cacheDirectory(const SceneLoadOptions& options) {
  if (options.noCache) return std::nullopt;
  if (!options.cacheDirectory.empty()) return std::filesystem::path(options.cacheDirectory);
  return defaultCacheDirectory();
}

world::World loadWorld(const std::string& sceneFile, const SceneLoadOptions& options) {
  world::WorldOptions worldOptions;
  worldOptions.cacheDirectory = cacheDirectory(options);
  worldOptions.threads = options.threads;
  worldOptions.pieces = options.pieces;
  io::SceneDescription scene = io::readSceneFile(sceneFile);
  if (options.epsilon) applyEpsilonOption(*options.epsilon, scene.settings);
  if (options.placementSeed) scene.settings.placementSeed = *options.placementSeed;
  return world::World(std::move(scene), worldOptions);
}

world::World loadPlanWorld(const std::string& sceneFile, SceneLoadOptions options,
                           const nlohmann::json& plan, const std::string& planFile) {
  if (!options.placementSeed && plan.is_object() && plan.contains("placement_seed")) {
    const nlohmann::json& seed = plan["placement_seed"];
    if (!seed.is_number_unsigned()) {
      throw InputError(locate(planFile, "placement_seed: expected a non-negative integer"));
    }
    options.placementSeed = seed.get<std::uint64_t>();
  }
  return loadWorld(sceneFile, options);
}

void addVerifyStepOptions(CLI::App& command, VerifyStepOptions& options) {
  command.add_option("--joint-step", options.jointStepDegrees,
                     "Largest joint motion between samples, degrees (default 0.5)");
  command.add_option("--tool-step", options.toolStepMillimetres,
                     "Largest motion of a link origin or tool point between samples, millimetres "
                     "(default 1)");
}

verify::VerifyOptions verifyOptions(const VerifyStepOptions& options) {
  if (!(options.jointStepDegrees > 0) || !std::isfinite(options.jointStepDegrees)) {
    throw InputError("--joint-step: must be a positive number of degrees");
  }
  if (!(options.toolStepMillimetres > 0) || !std::isfinite(options.toolStepMillimetres)) {
    throw InputError("--tool-step: must be a positive number of millimetres");
  }
  verify::VerifyOptions verify;
  verify.jointStep = options.jointStepDegrees * std::numbers::pi / 180;
  verify.toolStep = options.toolStepMillimetres / 1000;
  return verify;
}

}  // namespace kaboum::cli
