// The shipped `kaboum` tool links only what it uses: the reference collision libraries (FCL,
// Bullet, libccd) and the comparison verbs live in the separate `kaboum-compare` program.
#include <gtest/gtest.h>

#include <string>

#include "../support/test_support.hpp"

namespace kaboum::test {

using namespace kaboum::testing;

namespace {

TEST(CliProduct, LinksNoReferenceCollisionLibrary) {
  const ScratchDir dir;
  const CliResult result = runProgram("ldd", dir, std::string("'") + KABOUM_CLI + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  ASSERT_NE(result.out.find("libc.so"), std::string::npos) << result.out;
  for (const char* library : {"libfcl", "libBullet", "libLinearMath", "libccd"}) {
    EXPECT_EQ(result.out.find(library), std::string::npos) << library << " in\n" << result.out;
  }
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
