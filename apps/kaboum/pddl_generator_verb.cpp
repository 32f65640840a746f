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
};

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) throw InputError(locate(path.string(), "cannot write file"));
}

int runGenerator(const PddlGenerator& generator, const GeneratorOptions& options) {
  const std::string problem = generator.problem(options.n);
  const std::filesystem::path dir(options.outDir);
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  const auto domainPath = dir / (generator.fileStem + "-domain.pddl");
  const auto problemPath = dir / (generator.fileStem + "-" + std::to_string(options.n) + ".pddl");
  writeFile(domainPath, generator.domain());
  writeFile(problemPath, problem);
  if (!options.quiet) std::cout << domainPath.string() << "\n" << problemPath.string() << "\n";
  for (const PddlGenerator::File& file : generator.more) {
    const auto path = dir / file.name(options.n);
    writeFile(path, file.text(options.n));
    if (!options.quiet) std::cout << path.string() << "\n";
  }
  return 0;
}

}  // namespace

VerbRunner setupPddlGeneratorVerb(CLI::App& command, PddlGenerator generator) {
  auto options = std::make_shared<GeneratorOptions>();
  command.add_option("n", options->n, generator.sizeHelp)->required();
  command.add_option("--out-dir", options->outDir, "Directory for the files")
      ->capture_default_str();
  command.add_flag("--quiet", options->quiet, "Do not print the written paths");
  return [options, generator = std::move(generator)] { return runGenerator(generator, *options); };
}

}  // namespace kaboum::cli
