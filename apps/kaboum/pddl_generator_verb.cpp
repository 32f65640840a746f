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
};

int runGenerator(const PddlGenerator& generator, const GeneratorOptions& options) {
  const std::string problem = generator.problem(options.n);
  std::vector<GeneratedFile> files = {
      {generator.fileStem + "-domain.pddl", generator.domain()},
      {generator.fileStem + "-" + std::to_string(options.n) + ".pddl", problem}};
  for (const PddlGenerator::File& file : generator.more) {
    files.push_back({file.name(options.n), file.text(options.n)});
  }
  writeGeneratedFiles(options.outDir, files, options.quiet);
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
