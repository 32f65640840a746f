#include "pddl_generator_verb.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "kaboum/core/error.hpp"

namespace kaboum::cli {

void writeGeneratedFiles(const std::string& dir, const std::vector<GeneratedFile>& files,
                         bool quiet) {
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  for (const auto& [name, text] : files) {
    const std::filesystem::path path = std::filesystem::path(dir) / name;
    std::ofstream out(path);
    if (!out || !(out << text)) throw InputError(locate(path.string(), "cannot write file"));
  }
  if (quiet) return;
  for (const GeneratedFile& file : files) {
    std::cout << (std::filesystem::path(dir) / file.name).string() << "\n";
  }
}

namespace {

struct GeneratorOptions {
  int n = 0;
  std::string outDir = ".";
  bool quiet = false;
  bool scene = false;
  std::string urdf;
};

int runGenerator(const PddlGenerator& generator, const std::optional<SceneGenerator>& scene,
                 const GeneratorOptions& options) {
  const std::string n = std::to_string(options.n);
  std::vector<GeneratedFile> files;
  if (options.scene) {
    if (!std::filesystem::is_regular_file(options.urdf)) {
      throw InputError("--urdf: no such file '" + options.urdf + "'");
    }
    const std::string urdf = std::filesystem::relative(std::filesystem::absolute(options.urdf),
                                                       std::filesystem::absolute(options.outDir))
                                 .generic_string();
    files = {{scene->fileStem + "-domain.pddl", scene->domain()},
             {scene->fileStem + "-" + n + ".pddl", scene->problem(options.n)},
             {scene->fileStem + "-" + n + ".yaml", scene->scene(options.n, urdf)}};
  } else {
    files = {{generator.fileStem + "-domain.pddl", generator.domain()},
             {generator.fileStem + "-" + n + ".pddl", generator.problem(options.n)}};
    for (const PddlGenerator::File& file : generator.more) {
      files.push_back({file.name(options.n), file.text(options.n)});
    }
  }
  writeGeneratedFiles(options.outDir, files, options.quiet);
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
