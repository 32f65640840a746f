// Verbs that write a generated PDDL domain and problem for a size n (`stacked`, `force-sensing`,
// `circular-rearrange`): the options, the files and the printed paths are the same for all of
// them (`remove-objects` writes its files with writeGeneratedFiles too). A scenario with geometry
// (`stacked --scene`) writes its domain with geometric attachments, problem and scene.
#pragma once

#include <functional>
#include <optional>
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

// The scenario with geometry, written instead with `--scene`: STEM-domain.pddl, STEM-N.pddl and
// the scene STEM-N.yaml, whose robot URDF is `--urdf` (a path from the working directory, written
// relative to the scene file's folder).
struct SceneGenerator {
  std::string fileStem;
  std::function<std::string()> domain;
  std::function<std::string(int n)> problem;
  std::function<std::string(int n, const std::string& urdf)> scene;
  std::string defaultUrdf;
};

// Declares `n`, `--out-dir` and `--quiet` on `command` (and `--scene`, `--urdf` with a scene
// generator); the runner writes the files.
VerbRunner setupPddlGeneratorVerb(CLI::App& command, PddlGenerator generator,
                                  std::optional<SceneGenerator> scene = std::nullopt);

}  // namespace kaboum::cli
