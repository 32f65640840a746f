// Self-registration of CLI verbs: each verb_*.cpp adds its subcommand without touching main.cpp;
// runVerbs() dispatches to them (the `kaboum` tool and the `kaboum-compare` benchmark program).
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

// Parses the command line, runs the chosen verb and returns its exit code; bad options and
// InputError give one line on stderr, "PROGRAM: error: ...", and exit code 2.
int runVerbs(int argc, char** argv, const std::string& program, const std::string& description);

// Prints what an input file was read despite, one "kaboum: warning: file:line:col: ..." line each
// on stderr.
void printWarnings(const std::vector<std::string>& warnings);

struct VerbRegistration {
  VerbRegistration(std::string name, std::string description, VerbSetup setup) {
    verbRegistry().push_back({std::move(name), std::move(description), setup});
  }
};

}  // namespace kaboum::cli
