// Summary statistics shared by the `kaboum-compare collision` sections.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace kaboum::cli {

// The median of `values` (the upper one of an even count); `values` must not be empty.
inline double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace kaboum::cli
