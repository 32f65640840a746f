#include "pddl_generator_verb.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "kaboum/core/error.hpp"

namespace kaboum::cli {
namespace {

struct GeneratorOptions {
  int n = 0;
  std::string outDir = ".";
  bool quiet = false;
  bool scene = false;
  std::string urdf;
};

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) throw InputError(locate(path.string(), "cannot write file"));
}

// The files of one generator: its texts for n by file name, in the order written.
using GeneratedFiles = std::vector<std::pair<std::string, std::string>>;

GeneratedFiles pddlFiles(const std::string& stem, const std::string& domain,
                         const std::string& problem, int n) {
  return {{stem + "-domain.pddl", domain}, {stem + "-" + std::to_string(n) + ".pddl", problem}};
}

int runGenerator(const PddlGenerator& generator, const std::optional<SceneGenerator>& scene,
                 const GeneratorOptions& options) {
  const std::filesystem::path dir(options.outDir);
  GeneratedFiles files;
  if (options.scene) {
    if (!std::filesystem::is_regular_file(options.urdf)) {
      throw InputError("--urdf: no such file '" + options.urdf + "'");
    }
    const std::string n = std::to_string(options.n);
    const std::string urdf = std::filesystem::relative(std::filesystem::absolute(options.urdf),
                                                       std::filesystem::absolute(dir))
                                 .generic_string();
    files = pddlFiles(scene->fileStem, scene->domain(), scene->problem(options.n), options.n);
    files.emplace_back(scene->fileStem + "-" + n + ".yaml", scene->scene(options.n, urdf));
  } else {
    files =
        pddlFiles(generator.fileStem, generator.domain(), generator.problem(options.n), options.n);
  }
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  for (const auto& [name, text] : files) {
    writeFile(dir / name, text);
    if (!options.quiet) std::cout << (dir / name).string() << "\n";
  }
  return 0;
}

}  // namespace

VerbRunner setupPddlGeneratorVerb(CLI::App& command, PddlGenerator generator,
                                  std::optional<SceneGenerator> scene) {
  auto options = std::make_shared<GeneratorOptions>();
  command.add_option("n", options->n, generator.sizeHelp)->required();
  command.add_option("--out-dir", options->outDir, "Directory for the files")
      ->capture_default_str();
  command.add_flag("--quiet", options->quiet, "Do not print the written paths");
  if (scene) {
    options->urdf = scene->defaultUrdf;
    command.add_flag("--scene", options->scene,
                     "Write the scenario with geometry: a domain with geometric attachments, its "
                     "problem and a scene file for `kaboum solve`");
    command.add_option("--urdf", options->urdf, "The robot's URDF (with --scene)")
        ->capture_default_str();
  }
  return [options, generator = std::move(generator), scene = std::move(scene)] {
    return runGenerator(generator, scene, *options);
  };
}

}  // namespace kaboum::cli
