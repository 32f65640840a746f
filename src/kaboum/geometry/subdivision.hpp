// Loop subdivision: each triangle becomes four and vertices are smoothed, turning a real mesh into
// a larger, still realistic one (used to make 10^5–10^6-vertex benchmark inputs).
#pragma once

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// One step of Loop's scheme (Loop 1987) with Warren's weights. Border edges use the cubic B-spline
// boundary rules, so open meshes stay open with smooth borders.
TriangleMesh subdivideLoop(const TriangleMesh& mesh);

}  // namespace kaboum::geometry
