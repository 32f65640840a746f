// Errors a user can act on. The CLI prints them as one line and exits with code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace kaboum {

// Bad input: a file, mesh, domain, scene or option that cannot be used. The message names the
// file (and line/column where it applies) and what is wrong, e.g. "a.obj:12:3: face index 9 out of
// range".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Formats "file: what" or "file:line:col: what" (line/column omitted when 0).
std::string locate(const std::string& file, const std::string& what, long line = 0,
                   long column = 0);

}  // namespace kaboum
