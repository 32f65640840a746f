// Verbs that write a generated PDDL domain and problem for a size n (`stacked`, `force-sensing`,
// `circular-rearrange`): the options, the files and the printed paths are the same for all of
// them (`remove-objects` writes its files with writeGeneratedFiles too).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "verb.hpp"

namespace kaboum::cli {

struct PddlGenerator {
  std::string fileStem;                       // "stacked" -> stacked-domain.pddl, stacked-N.pddl
  std::string sizeHelp;                       // help text of the positional n
  std::function<std::string()> domain;        // the domain text
  std::function<std::string(int n)> problem;  // the problem text; throws InputError for bad n
  // Further files written beside them (a scene, a domain variant): name and text for n.
  struct File {
    std::function<std::string(int n)> name;
    std::function<std::string(int n)> text;
  };
  std::vector<File> more = {};
};

struct GeneratedFile {
  std::string name;  // file name inside the output directory
  std::string text;
};

// Writes the files into `dir` (created when missing) and, unless `quiet`, prints their paths;
// InputError naming the file that cannot be written.
void writeGeneratedFiles(const std::string& dir, const std::vector<GeneratedFile>& files,
                         bool quiet);

// Declares `n`, `--out-dir` and `--quiet` on `command`; the runner writes the files.
VerbRunner setupPddlGeneratorVerb(CLI::App& command, PddlGenerator generator);

}  // namespace kaboum::cli
