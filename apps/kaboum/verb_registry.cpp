// kaboum command-line entry point: dispatches to the registered verbs and maps errors to exit 2.
#include <algorithm>
#include <iostream>
#include <map>

#include "kaboum/core/error.hpp"
#include "verb.hpp"

namespace kaboum::cli {

std::vector<VerbInfo>& verbRegistry() {
  static std::vector<VerbInfo> registry;
  return registry;
}

}  // namespace kaboum::cli

int main(int argc, char** argv) {
  using namespace kaboum::cli;
  CLI::App app{
      "kaboum: knowledge-level task and motion planning with bounding geometry.\n"
      "Run `kaboum VERB --help` for the options of a verb."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "kaboum 0.1.0");

  auto verbs = verbRegistry();
  std::sort(verbs.begin(), verbs.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  std::map<CLI::App*, VerbRunner> runners;
  for (const auto& verb : verbs) {
    CLI::App* command = app.add_subcommand(verb.name, verb.description);
    runners[command] = verb.setup(*command);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "kaboum: error: " << e.what() << " (see --help)\n";
    return 2;
  }

  try {
    for (auto& [command, run] : runners) {
      if (command->parsed()) return run();
    }
  } catch (const kaboum::InputError& e) {
    std::cerr << "kaboum: error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "kaboum: error: out of memory\n";
    return 2;
  }
  return 2;
}
