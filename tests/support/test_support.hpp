// Helpers shared by the test executables: a scratch directory and running the `kaboum` CLI.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "kaboum/testing/data_paths.hpp"

namespace kaboum::test {

using namespace kaboum::testing;

// A fresh directory under the system temp directory, removed with everything in it at scope end.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("kaboum-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  // Path of `name` inside the directory.
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Writes `contents` (bytes as given) to `name` and returns its path.
  std::string write(const std::string& name, const std::string& contents) const {
    const std::string path = file(name);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << contents;
    return path;
  }

 private:
  std::filesystem::path path_;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct CliResult {
  int exitCode = -1;
  std::string out, err;
};

// Runs `PROGRAM ARGUMENTS` (arguments are passed to the shell as written), capturing its output in
// `dir`.
inline CliResult runProgram(const std::string& program, const ScratchDir& dir,
                            const std::string& arguments) {
  const std::string command = "'" + program + "' " + arguments + " >'" + dir.file("out.txt") +
                              "' 2>'" + dir.file("err.txt") + "'";
  const int status = std::system(command.c_str());
  CliResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(dir.file("out.txt"));
  result.err = slurp(dir.file("err.txt"));
  return result;
}

// Runs the `kaboum` tool.
inline CliResult runCli(const ScratchDir& dir, const std::string& arguments) {
  return runProgram(KABOUM_CLI, dir, arguments);
}

// " --cache-dir DIR": one decomposition cache in the build directory shared by the CLI tests of
// every test program (robot meshes take seconds to decompose; the cache is safe for concurrent
// runs and keyed by content, so it never serves a stale entry).
inline std::string sharedCacheOption() {
  return " --cache-dir '" +
         (std::filesystem::path(KABOUM_CLI).parent_path() / "test-decomposition-cache").string() +
         "'";
}

// Runs the `kaboum-compare` benchmark program (kaboum against FCL, Bullet and libccd).
inline CliResult runCompare(const ScratchDir& dir, const std::string& arguments) {
  return runProgram(KABOUM_COMPARE, dir, arguments);
}

// Path of a mesh copied into the repo's data/meshes/, single-quoted for a CLI command line.
inline std::string quotedMesh(const std::string& name) {
  return "'" + kaboum::testing::dataFile("meshes/" + name) + "'";
}

// Number of lines in `text` (newline characters).
inline std::size_t lineCount(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace kaboum::test
