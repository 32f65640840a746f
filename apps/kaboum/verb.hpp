// Self-registration of CLI verbs: each verb_*.cpp adds its subcommand without touching main.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace kaboum::cli {

// Declares the verb's options on `command` and returns what runs it (its exit code).
using VerbRunner = std::function<int()>;
using VerbSetup = VerbRunner (*)(CLI::App& command);

struct VerbInfo {
  std::string name;
  std::string description;
  VerbSetup setup;
};

std::vector<VerbInfo>& verbRegistry();

struct VerbRegistration {
  VerbRegistration(std::string name, std::string description, VerbSetup setup) {
    verbRegistry().push_back({std::move(name), std::move(description), setup});
  }
};

}  // namespace kaboum::cli
