// Reading and writing triangle meshes in the common formats (STL, OBJ, PLY, OFF, DAE, VRML 2.0).
// Meshes enter kaboum here; §3.1 requires them to be closed orientable 2-manifolds, which
// kaboum/geometry/mesh_analysis.hpp checks afterwards.
#pragma once

#include <string>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

// Reads STL (ascii+binary), OBJ (polygons fan-triangulated, never truncated), PLY (ascii/binary,
// incl. triangle strips), OFF, DAE via assimp, and VRML 2.0 .wrl with our own reader. Vertices are
// welded (exactly coincident positions merged; STL shares none), unreferenced vertices dropped, all
// components kept. Throws InputError naming the file (line/col where it applies) for:
// missing/unreadable file, unknown format, parse errors, empty mesh (no faces), NaN/inf
// coordinates, out-of-range indices, zero-area-only mesh.
TriangleMesh readMesh(const std::string& path);

// Writes by extension: .obj .stl (binary) .ply (binary little endian) .off. Text formats and PLY
// (double properties) round-trip coordinates exactly; binary STL stores 32-bit floats. Throws
// InputError for an unknown extension or an unwritable path.
void writeMesh(const TriangleMesh& mesh, const std::string& path);

}  // namespace kaboum::io
