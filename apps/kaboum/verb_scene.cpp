// `kaboum scene FILE [--json] [--quiet] [--no-cache | --cache-dir DIR] [--threads N]`: reads a
// scene file, builds its World (collision geometry of robots, hands and objects, thesis §6.1.1) and
// reports what was built, the ε each body reaches, the distinct meshes decomposed, what the
// decomposition cache did, and whether the initial state is collision-free (exit code 2 with the
// error line when it is not).
#include <fmt/format.h>

#include <iostream>

#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/world/world.hpp"
#include "scene_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::world;

namespace {

struct BodyCounts {
  std::size_t pieces = 0;
  std::size_t vertices = 0;
};

BodyCounts countsOf(const CollisionBody& body) {
  BodyCounts counts{body.pieceCount(), 0};
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    counts.vertices += body.piece(p).vertices().size();
  }
  return counts;
}

BodyCounts countsOf(const RobotCollisionModel& robot) {
  BodyCounts counts;
  for (std::size_t i = 0; i < robot.partCount(); ++i) {
    const BodyCounts part = countsOf(*robot.part(i).body);
    counts.pieces += part.pieces;
    counts.vertices += part.vertices;
  }
  return counts;
}

std::string epsilonText(const SceneSettings& settings) {
  return settings.epsilonRelative
             ? fmt::format("{:g}% of each body's bounding-box diagonal", 100 * settings.epsilon)
             : fmt::format("{:g} m", settings.epsilon);
}

std::string millimetres(double metres) {
  return fmt::format("{:.3g} mm", 1000 * metres);
}

// "ε 4.27 mm", or "ε 6.1 mm (asked 5 mm: not reached)".
std::string epsilonReached(const BodyEpsilon& epsilon) {
  const std::string reached = "ε " + millimetres(epsilon.reached);
  return epsilon.met() ? reached
                       : reached + " (asked " + millimetres(epsilon.asked) + ": not reached)";
}

nlohmann::json epsilonJson(const BodyEpsilon& epsilon) {
  return {{"asked", epsilon.asked}, {"reached", epsilon.reached}, {"met", epsilon.met()}};
}

std::string cacheText(const std::optional<std::filesystem::path>& directory,
                      const DecompositionCacheReport& report) {
  if (!directory) return "off";
  return fmt::format("{} hit(s), {} miss(es), {} rebuilt ({})", report.hits, report.misses,
                     report.rebuilt, directory->string());
}

nlohmann::json cacheJson(const std::optional<std::filesystem::path>& directory,
                         const DecompositionCacheReport& report) {
  return {{"directory", directory ? nlohmann::json(directory->string()) : nlohmann::json()},
          {"hits", report.hits},
          {"misses", report.misses},
          {"rebuilt", report.rebuilt},
          {"warnings", report.warnings}};
}

const char* regionKind(const LocationSpec& location) {
  return std::holds_alternative<BoxRegion>(location.region) ? "box" : "hull";
}

void printReport(const std::string& file, const World& world,
                 const std::optional<std::filesystem::path>& cacheDirectory) {
  const SceneDescription& scene = world.description();
  fmt::print("scene:         {}\n", file);
  fmt::print("epsilon:       {}\n", epsilonText(scene.settings));
  fmt::print("robots:        {}\n", world.robots().size());
  for (const WorldRobot& robot : world.robots()) {
    const BodyCounts counts = countsOf(robot.collision);
    fmt::print("  {}: {} DOF, {} links with geometry, {} piece(s), {} vertices, {:.3f} s\n",
               robot.name, robot.collision.model().dof(), robot.collision.partCount(),
               counts.pieces, counts.vertices, robot.preprocessingSeconds);
    for (std::size_t i = 0; i < robot.collision.partCount(); ++i) {
      const Attachment& part = robot.collision.part(i);
      fmt::print("    link {}: {} piece(s), {}\n",
                 robot.collision.model().links()[static_cast<std::size_t>(part.link)].name,
                 part.body->pieceCount(), epsilonReached(robot.partEpsilon[i]));
    }
    const std::vector<ToolSpec>& tools = scene.robots[&robot - world.robots().data()].tools;
    for (std::size_t t = 0; t < tools.size(); ++t) {
      for (const double reached : robot.handShapeEpsilon[t]) {
        fmt::print("    hand shape of {}: ε {}\n", tools[t].name, millimetres(reached));
      }
    }
  }
  fmt::print("objects:       {}\n", scene.objects.size());
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const BodyCounts counts = countsOf(world.scene().body(o));
    fmt::print("  {}: {}, {} piece(s), {} vertices, {}, {:.3f} s", scene.objects[o].name,
               scene.objects[o].movable ? "movable" : "static", counts.pieces, counts.vertices,
               epsilonReached(world.objectEpsilon()[o]), world.objectSeconds()[o]);
    if (world.restingLift()[o] > 0) {
      fmt::print(", raised {:g} mm off its support", 1000 * world.restingLift()[o]);
    }
    fmt::print("\n");
  }
  fmt::print("locations:     {}\n", scene.locations.size());
  for (const LocationSpec& location : scene.locations) {
    fmt::print("  {}: {}{}\n", location.name, regionKind(location),
               location.supportSurface ? ", support surface" : "");
  }
  const DecompositionSummary& decompositions = world.decompositions();
  std::size_t shapes = 0;
  for (const MeshDecomposition& mesh : decompositions.meshes) shapes += mesh.shapes;
  fmt::print("meshes:        {} distinct of {} mesh shape(s) decomposed, {} thread(s)\n",
             decompositions.meshes.size(), shapes, decompositions.threads);
  fmt::print("cache:         {}\n", cacheText(cacheDirectory, world.cacheReport()));
  fmt::print("preprocessing: {:.3f} s\n", world.preprocessingSeconds());
}

nlohmann::json reportJson(const std::string& file, const World& world, bool collisionFree,
                          const std::optional<std::filesystem::path>& cacheDirectory) {
  const SceneDescription& scene = world.description();
  nlohmann::json robots = nlohmann::json::array();
  for (const WorldRobot& robot : world.robots()) {
    const BodyCounts counts = countsOf(robot.collision);
    nlohmann::json parts = nlohmann::json::array();
    for (std::size_t i = 0; i < robot.collision.partCount(); ++i) {
      const Attachment& part = robot.collision.part(i);
      parts.push_back(
          {{"link", robot.collision.model().links()[static_cast<std::size_t>(part.link)].name},
           {"pieces", part.body->pieceCount()},
           {"epsilon", epsilonJson(robot.partEpsilon[i])}});
    }
    const std::vector<ToolSpec>& tools = scene.robots[&robot - world.robots().data()].tools;
    nlohmann::json hands = nlohmann::json::array();
    for (std::size_t t = 0; t < tools.size(); ++t) {
      hands.push_back({{"tool", tools[t].name}, {"shapes_epsilon", robot.handShapeEpsilon[t]}});
    }
    robots.push_back({{"name", robot.name},
                      {"dof", robot.collision.model().dof()},
                      {"links_with_geometry", robot.collision.partCount()},
                      {"pieces", counts.pieces},
                      {"vertices", counts.vertices},
                      {"base", toJson(robot.collision.basePose())},
                      {"parts", parts},
                      {"hands", hands},
                      {"seconds", robot.preprocessingSeconds}});
  }
  nlohmann::json objects = nlohmann::json::array();
  const GeometricState initial = world.initialState();
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const BodyCounts counts = countsOf(world.scene().body(o));
    objects.push_back({{"name", scene.objects[o].name},
                       {"movable", scene.objects[o].movable},
                       {"pieces", counts.pieces},
                       {"vertices", counts.vertices},
                       {"epsilon", epsilonJson(world.objectEpsilon()[o])},
                       {"pose", toJson(world.scene().pose(o, initial.placements))},
                       {"resting_lift", world.restingLift()[o]},
                       {"seconds", world.objectSeconds()[o]}});
  }
  nlohmann::json locations = nlohmann::json::array();
  for (const LocationSpec& location : scene.locations) {
    locations.push_back({{"name", location.name},
                         {"region", regionKind(location)},
                         {"support_surface", location.supportSurface}});
  }
  nlohmann::json meshes = nlohmann::json::array();
  for (const MeshDecomposition& mesh : world.decompositions().meshes) {
    meshes.push_back({{"mesh", mesh.mesh},
                      {"triangles", mesh.triangles},
                      {"shapes", mesh.shapes},
                      {"attempts", mesh.attempts},
                      {"seconds", mesh.seconds}});
  }
  return {{"file", file},
          {"epsilon", scene.settings.epsilon},
          {"epsilon_relative", scene.settings.epsilonRelative},
          {"robots", robots},
          {"objects", objects},
          {"locations", locations},
          {"meshes", meshes},
          {"threads", world.decompositions().threads},
          {"cache", cacheJson(cacheDirectory, world.cacheReport())},
          {"preprocessing_seconds", world.preprocessingSeconds()},
          {"initial_state_collision_free", collisionFree}};
}

VerbRunner setupScene(CLI::App& command) {
  struct Options {
    std::string file;
    bool json = false;
    bool quiet = false;
    SceneLoadOptions load;
  };
  auto options = std::make_shared<Options>();
  command.add_option("FILE", options->file, "Scene file (YAML, docs/scene-format.md)")->required();
  command.add_flag("--json", options->json, "Print one JSON object instead of lines");
  command.add_flag("-q,--quiet", options->quiet,
                   "Print only the initial state's verdict (and no cache warnings)");
  addSceneLoadOptions(command, options->load);
  return [options] {
    const World world = loadWorld(options->file, options->load);
    const std::optional<std::filesystem::path> cache = cacheDirectory(options->load);
    if (!options->quiet) {
      for (const std::string& warning : world.cacheReport().warnings) {
        std::cerr << "kaboum: warning: " << warning << '\n';
      }
    }
    const std::optional<Collision> collision = world.firstCollision(world.initialState());
    if (options->json) {
      std::cout << reportJson(options->file, world, !collision, cache).dump() << '\n';
    } else {
      if (!options->quiet) printReport(options->file, world, cache);
      if (!collision) fmt::print("initial state: collision-free\n");
    }
    if (collision) {
      std::cerr << "kaboum: error: " << options->file
                << ": initial state: " << world.describe(*collision) << '\n';
      return 2;
    }
    return 0;
  };
}

const VerbRegistration registration{
    "scene", "Read a scene file, build its collision geometry and check the initial state",
    &setupScene};

}  // namespace

}  // namespace kaboum::cli
