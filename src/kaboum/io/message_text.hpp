// Text of the readers' one-line InputError messages: echoed input in quotes, and the nearest valid
// name for a misspelt one.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace kaboum::io {

// `text` in quotes for a one-line message: control characters as spaces, cut after 40 characters.
std::string inQuotes(std::string_view text);

// " (did you mean 'position'?)" when a candidate is within a few edits of `word`, else the list
// of candidates.
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace kaboum::io
