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

int runVerbs(int argc, char** argv, const std::string& program, const std::string& description) {
  CLI::App app{description + "\nRun `" + program + " VERB --help` for the options of a verb.",
               program};
  app.require_subcommand(1);
  app.set_version_flag("--version", program + " " + KABOUM_VERSION);

  auto verbs = verbRegistry();
  std::sort(verbs.begin(), verbs.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  std::map<CLI::App*, VerbRunner> runners;
  for (const auto& verb : verbs) {
    CLI::App* command = app.add_subcommand(verb.name, verb.description);
    runners[command] = verb.setup(*command);
  }

  if (argc > 1 && argv[1][0] != '-' &&
      std::none_of(verbs.begin(), verbs.end(),
                   [&](const VerbInfo& v) { return v.name == argv[1]; })) {
    std::cerr << program << ": error: unknown verb '" << argv[1] << "' (see --help)\n";
    return 2;
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
    std::cerr << program << ": error: " << e.what() << " (see --help)\n";
    return 2;
  }

  try {
    for (auto& [command, run] : runners) {
      if (command->parsed()) return run();
    }
  } catch (const kaboum::InputError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << program << ": error: out of memory\n";
    return 2;
  }
  return 2;
}

void printWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::cerr << "kaboum: warning: " << warning << "\n";
}

}  // namespace kaboum::cli
