#include "kaboum/core/error.hpp"

namespace kaboum {

std::string locate(const std::string& file, const std::string& what, long line, long column) {
  std::string out = file;
  if (line > 0) {
    out += ":" + std::to_string(line);
    if (column > 0) out += ":" + std::to_string(column);
  }
  return out + ": " + what;
}

}  // namespace kaboum
