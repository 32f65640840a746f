// `kaboum remove-objects N`: writes the Remove n Objects domain, problem and scene (seed 003
// Table II) for `kaboum solve`.
#include <memory>

#include "kaboum/scenarios/remove_objects.hpp"
#include "pddl_generator_verb.hpp"

namespace kaboum::cli {
namespace {

struct RemoveObjectsOptions {
  int n = 0;
  std::string layout = "random";
  std::uint64_t seed = 1;
  std::string outDir = ".";
  bool quiet = false;
};

int runRemoveObjects(const RemoveObjectsOptions& options) {
  const scenarios::RemoveObjectsLayout layout = scenarios::parseRemoveObjectsLayout(options.layout);
  const scenarios::RemoveObjectsScenario scenario =
      scenarios::removeObjects(options.n, layout, options.seed);
  const std::string stem =
      "remove-objects-" + scenarios::layoutName(layout) + "-" + std::to_string(options.n);
  writeGeneratedFiles(options.outDir,
                      {{"remove-objects-domain.pddl", scenario.domain},
                       {stem + ".pddl", scenario.problem},
                       {stem + ".yaml", scenario.scene}},
                      options.quiet);
  return 0;
}

VerbRunner setupRemoveObjects(CLI::App& command) {
  auto options = std::make_shared<RemoveObjectsOptions>();
  command.add_option("n", options->n, "Number of objects (1 to 20)")->required();
  command
      .add_option("--layout", options->layout,
                  "random (seeded places on the table) or line (only the nearest can be picked)")
      ->capture_default_str();
  command.add_option("--seed", options->seed, "Seed of the random layout")->capture_default_str();
  command.add_option("--out-dir", options->outDir, "Directory for the written files")
      ->capture_default_str();
  command.add_flag("--quiet", options->quiet, "Do not print the written paths");
  return [options] { return runRemoveObjects(*options); };
}

const VerbRegistration registration{
    "remove-objects",
    "Write the Remove n Objects domain, problem and scene for kaboum solve (seed 003 Table II)",
    setupRemoveObjects};

}  // namespace
}  // namespace kaboum::cli
