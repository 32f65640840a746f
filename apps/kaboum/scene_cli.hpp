// Loading a scene file's World for the verbs that read scenes (scene, motion, verify-path,
// verify-plan): the options they share (where the decomposition cache of §6.1.1's pre-processing
// lives) and the reading and building itself; and the sample spacing of the verifying verbs.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "kaboum/io/scene_file.hpp"
#include "kaboum/verify/path_verifier.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::cli {

struct SceneLoadOptions {
  bool noCache = false;
  std::string cacheDirectory;          // empty: defaultCacheDirectory()
  unsigned threads = 0;                // decomposing meshes; 0: the hardware's
  std::optional<std::string> epsilon;  // --epsilon as given (metres or N%); none: the scene's
  std::optional<std::uint64_t> placementSeed;  // --placement-seed; none: the scene's
  world::MeshPieces pieces = world::MeshPieces::Decomposition;  // the Python API may ask for hulls
};

// Adds --no-cache, --cache-dir DIR, --threads N, --epsilon E and --placement-seed N to `command`.
void addSceneLoadOptions(CLI::App& command, SceneLoadOptions& options);

// $KABOUM_CACHE_DIR, else $XDG_CACHE_HOME/kaboum, else $HOME/.cache/kaboum (variables that are
// empty count as unset); nullopt when none is set.
std::optional<std::filesystem::path> defaultCacheDirectory();

// The cache directory that `options` choose: none with --no-cache, else --cache-dir, else the
// default.
std::optional<std::filesystem::path> cacheDirectory(const SceneLoadOptions& options);

// Sets the ε of the bounded predicates in `settings` from `text` as the scene file states it: a
// distance in metres ("0.005") or a percentage of each body's bounding-box diagonal ("1%", at
// most 100%). Throws InputError with one line naming --epsilon for anything else (a negative or
// zero value, not a number).
void applyEpsilonOption(const std::string& text, io::SceneSettings& settings);

// Reads the scene file and builds its World with decompositions cached as `options` say, on
// `options.threads` threads (WorldOptions::threads), at the ε of --epsilon when given, the objects
// with place_in placed by --placement-seed when given. Throws
// InputError for a bad file, a failed load-time check or a cache directory that cannot be created.
world::World loadWorld(const std::string& sceneFile, const SceneLoadOptions& options);

// loadWorld for a plan file's scene (verify-plan, view, execute): with the plan's
// `placement_seed`, the layout it was made on, unless --placement-seed gave one. Throws InputError
// naming `planFile` for a placement_seed that is not a non-negative integer.
world::World loadPlanWorld(const std::string& sceneFile, SceneLoadOptions options,
                           const nlohmann::json& plan, const std::string& planFile);

// How densely verify-path and verify-plan sample a path (docs/verify.md), in the user's units.
struct VerifyStepOptions {
  double jointStepDegrees = 0.5;
  double toolStepMillimetres = 1.0;
};

// Adds --joint-step DEG and --tool-step MM to `command`.
void addVerifyStepOptions(CLI::App& command, VerifyStepOptions& options);

// The verifier's steps in radians and metres. Throws InputError for a step that is not a positive
// number.
verify::VerifyOptions verifyOptions(const VerifyStepOptions& options);

}  // namespace kaboum::cli
