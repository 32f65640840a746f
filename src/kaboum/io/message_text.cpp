#include "kaboum/io/message_text.hpp"

#include <algorithm>
#include <cctype>

namespace kaboum::io {

namespace {

// Optimal string alignment distance: insertions, deletions, substitutions and transpositions of
// neighbours each cost one.
std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

std::string inQuotes(std::string_view text) {
  constexpr std::size_t kShown = 40;
  std::string shown(text.substr(0, kShown));
  std::replace_if(
      shown.begin(), shown.end(), [](unsigned char c) { return std::iscntrl(c); }, ' ');
  return "'" + shown + (text.size() > kShown ? "...'" : "'");
}

std::string suggestion(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string* nearest = nullptr;
  std::size_t nearestDistance = 0;
  for (const std::string& candidate : candidates) {
    const std::size_t allowed = std::max<std::size_t>(2, candidate.size() / 3);
    const std::size_t lengthDifference = word.size() > candidate.size()
                                             ? word.size() - candidate.size()
                                             : candidate.size() - word.size();
    if (lengthDifference > allowed) continue;  // the distance is at least this
    const std::size_t distance = editDistance(word, candidate);
    if (distance <= allowed && (!nearest || distance < nearestDistance)) {
      nearest = &candidate;
      nearestDistance = distance;
    }
  }
  if (nearest) return " (did you mean '" + *nearest + "'?)";
  std::string list;
  for (const std::string& candidate : candidates) list += (list.empty() ? "" : ", ") + candidate;
  return " (expected one of: " + list + ")";
}

}  // namespace kaboum::io
