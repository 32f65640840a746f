// Small text helpers shared by the readers: ASCII case folding for names compared without case
// (file extensions, scene names, as PDDL compares symbols).
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace kaboum {

// `text` with ASCII letters in lower case.
inline std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace kaboum
