// `kaboum force-sensing N`: writes the Force Sensing domain and problem (thesis Table 3.1).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/force_sensing.hpp"
#include "verb.hpp"

namespace kaboum::cli {
namespace {

struct ForceSensingOptions {
  int n = 0;
  std::string outDir = ".";
  bool quiet = false;
};

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) throw InputError(locate(path.string(), "cannot write file"));
}

int runForceSensing(const ForceSensingOptions& options) {
  const std::string problem = symbolic::forceSensingProblem(options.n);
  const std::filesystem::path dir(options.outDir);
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  const auto domainPath = dir / "force-sensing-domain.pddl";
  const auto problemPath = dir / ("force-sensing-" + std::to_string(options.n) + ".pddl");
  writeText(domainPath, symbolic::forceSensingDomain());
  writeText(problemPath, problem);
  if (!options.quiet) std::cout << domainPath.string() << "\n" << problemPath.string() << "\n";
  return 0;
}

VerbRunner setupForceSensing(CLI::App& command) {
  auto options = std::make_shared<ForceSensingOptions>();
  command.add_option("n", options->n, "Number of containers (at least 1)")->required();
  command.add_option("--out-dir", options->outDir, "Directory for the PDDL files")
      ->capture_default_str();
  command.add_flag("--quiet", options->quiet, "Do not print the written paths");
  return [options] { return runForceSensing(*options); };
}

const VerbRegistration registration{
    "force-sensing",
    "Write the Force Sensing contingent domain and problem for n containers (thesis Table 3.1)",
    setupForceSensing};

}  // namespace
}  // namespace kaboum::cli
