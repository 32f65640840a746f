#include "mesh_cli.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/mesh_io.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::io;

void addSideFlags(CLI::App& command, BoundSide& side) {
  auto* outer = command.add_flag_callback(
      "--outer", [&side] { side = BoundSide::Outer; },
      "Outer bound: the result encloses the input (default)");
  auto* inner = command.add_flag_callback(
      "--inner", [&side] { side = BoundSide::Inner; },
      "Inner bound: the input encloses the result");
  outer->excludes(inner);
}

LoadedMesh loadOrientedMesh(const std::string& path) {
  LoadedMesh loaded;
  loaded.mesh = readMesh(path);
  if (!orientOutward(loaded.mesh, loaded.orientationRepaired)) {
    throw InputError(locate(path,
                            "cannot be oriented consistently (non-orientable or "
                            "non-manifold surface)"));
  }
  const MeshAnalysis analysis = analyzeMesh(loaded.mesh);
  loaded.closed = analysis.closed;
  loaded.diagonal = analysis.diagonal;
  return loaded;
}

double parseEpsilon(const std::string& text, double diagonal) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (ec != std::errc() || end != number.data() + number.size() || !(value > 0.0) ||
      !std::isfinite(value)) {
    throw InputError(
        "--epsilon: expected a positive distance or percentage such as 0.002 or "
        "1%, got '" +
        text + "'");
  }
  return percent ? value / 100.0 * diagonal : value;
}

const char* sideName(BoundSide side) {
  return side == BoundSide::Outer ? "outer" : "inner";
}

std::string describe(const DistanceStats& stats, double diagonal) {
  return fmt::format("max {:.4g} ({:.3f}% of diagonal), mean {:.4g}, min {:.4g}", stats.max,
                     100.0 * stats.max / diagonal, stats.mean, stats.min);
}

}  // namespace kaboum::cli
