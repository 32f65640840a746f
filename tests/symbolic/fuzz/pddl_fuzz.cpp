// libFuzzer target for the PDDL and plan parsers (not part of the CMake build; see
// docs/symbolic.md for the clang command and the corpus in tests/symbolic/fuzz/corpus).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "parse_any_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kaboum::symbolic::fuzz::parseAnyInput(
      std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
