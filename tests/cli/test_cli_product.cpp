// The shipped `kaboum` tool links only what it uses: Bullet and the comparison verbs live in the
// separate `kaboum-compare` program, and FCL, the independent reference of `kaboum verify-path`,
// is used by the verify module alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../support/test_support.hpp"

namespace kaboum::test {

using namespace kaboum::testing;

namespace {

TEST(CliProduct, LinksNoBullet) {
  const ScratchDir dir;
  const CliResult result = runProgram("ldd", dir, std::string("'") + KABOUM_CLI + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  ASSERT_NE(result.out.find("libc.so"), std::string::npos) << result.out;
  for (const char* library : {"libBullet", "libLinearMath"}) {
    EXPECT_EQ(result.out.find(library), std::string::npos) << library << " in\n" << result.out;
  }
}

// Files under `folder` (recursively) that include an FCL header.
std::vector<std::string> filesIncludingFcl(const std::filesystem::path& folder) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      if (line.find("#include") != std::string::npos &&
          (line.find("<fcl/") != std::string::npos || line.find("\"fcl/") != std::string::npos)) {
        files.push_back(entry.path().string());
        break;
      }
    }
  }
  return files;
}

TEST(CliProduct, OnlyTheVerifyModuleIncludesFcl) {
  const std::filesystem::path library = sourceFile("src/kaboum");
  ASSERT_FALSE(filesIncludingFcl(library / "verify").empty());  // the scan finds includes
  for (const auto& entry : std::filesystem::directory_iterator(library)) {
    if (!entry.is_directory() || entry.path().filename() == "verify") continue;
    EXPECT_EQ(filesIncludingFcl(entry.path()), std::vector<std::string>{});
  }
  EXPECT_EQ(filesIncludingFcl(sourceFile("apps/kaboum")), std::vector<std::string>{});
}

TEST(CliProduct, ComparisonVerbsAreInTheComparisonProgram) {
  const ScratchDir dir;
  for (const char* verb : {"bench", "verify-collision"}) {
    const CliResult result = runCli(dir, verb);
    EXPECT_EQ(result.exitCode, 2) << verb;
    EXPECT_EQ(result.err, "kaboum: error: unknown verb '" + std::string(verb) + "' (see --help)\n");
  }
  for (const char* verb : {"collision", "verify-collision"}) {
    EXPECT_EQ(runCompare(dir, std::string(verb) + " --help").exitCode, 0) << verb;
  }
}

}  // namespace
}  // namespace kaboum::test
