// `kaboum stacked N`: writes the Stacked n Objects domain and problem (thesis Table 6.3).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/stacked_objects.hpp"
#include "verb.hpp"

namespace kaboum::cli {
namespace {

struct StackedOptions {
  int n = 0;
  std::string outDir = ".";
  bool quiet = false;
};

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) throw InputError(locate(path.string(), "cannot write file"));
}

int runStacked(const StackedOptions& options) {
  const std::string problem = symbolic::stackedObjectsProblem(options.n);
  const std::filesystem::path dir(options.outDir);
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  const auto domainPath = dir / "stacked-domain.pddl";
  const auto problemPath = dir / ("stacked-" + std::to_string(options.n) + ".pddl");
  writeFile(domainPath, symbolic::stackedObjectsDomain());
  writeFile(problemPath, problem);
  if (!options.quiet) std::cout << domainPath.string() << "\n" << problemPath.string() << "\n";
  return 0;
}

VerbRunner setupStacked(CLI::App& command) {
  auto options = std::make_shared<StackedOptions>();
  command.add_option("n", options->n, "Number of objects (at least 2)")->required();
  command.add_option("--out-dir", options->outDir, "Directory for the PDDL files")
      ->capture_default_str();
  command.add_flag("--quiet", options->quiet, "Do not print the written paths");
  return [options] { return runStacked(*options); };
}

const VerbRegistration registration{
    "stacked", "Write the Stacked n Objects PDDL domain and problem (thesis Table 6.3)",
    setupStacked};

}  // namespace
}  // namespace kaboum::cli
