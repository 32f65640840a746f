// Replays the libFuzzer corpus (tests/symbolic/fuzz/corpus) through the fuzz target's body: every
// input must end in success or an InputError, never a crash (ASan/UBSan builds check memory).
#include <gtest/gtest.h>

#include <filesystem>

#include "fuzz/parse_any_input.hpp"
#include "kaboum/symbolic/sexpr.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

TEST(FuzzCorpus, EveryInputIsHandled) {
  const std::filesystem::path corpus =
      std::filesystem::path(kaboum::testing::sourceFile("tests/symbolic/fuzz/corpus"));
  std::size_t inputs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    EXPECT_NO_THROW(fuzz::parseAnyInput(readTextFile(entry.path().string()))) << entry.path();
    ++inputs;
  }
  EXPECT_GE(inputs, 5u);
}

}  // namespace
}  // namespace kaboum::symbolic
