// Pieces shared by the mesh verbs (bound, check, decompose): side flags, loading with orientation
// repair, distance reporting in text.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "kaboum/geometry/bound_side.hpp"
#include "kaboum/geometry/mesh_comparison.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;

// Adds mutually exclusive --outer (default) / --inner flags that set `side`.
void addSideFlags(CLI::App& command, BoundSide& side);

struct LoadedMesh {
  TriangleMesh mesh;
  bool closed = false;
  bool orientationRepaired = false;
  double diagonal = 0.0;  // bounding-box diagonal
};

// Reads a mesh and makes its orientation consistent and outward; InputError naming `path` if the
// mesh cannot be oriented (non-orientable or non-manifold where orientation is ambiguous).
LoadedMesh loadOrientedMesh(const std::string& path);

// An --epsilon value: "0.002" is a distance in the mesh's units, "0.5%" a percentage of
// `diagonal`. InputError for anything but a positive finite number.
double parseEpsilon(const std::string& text, double diagonal);

const char* sideName(BoundSide side);
// "max 1.23e-03 (0.10% of diagonal), mean ..., min ..."
std::string describe(const DistanceStats& stats, double diagonal);

}  // namespace kaboum::cli
