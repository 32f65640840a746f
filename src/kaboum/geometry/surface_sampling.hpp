// Dense point samples of a mesh surface, the measuring points of the bounding mesh verifier and of
// the Hausdorff figures of Table 4.2 (Eq. 4.1 evaluated on samples).
#pragma once

#include <cstdint>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum {

// Every vertex used by a triangle (by index), the midpoint of every distinct edge (by vertex pair),
// then `randomCount` uniformly area-weighted random points (deterministic for `seed`, independent
// of platform). Zero-area triangles get no random points; a mesh of zero total area gets none at
// all. Triangle indices must be in range (mesh I/O and TriangleBvh check them).
std::vector<Vec3> sampleSurface(const TriangleMesh& mesh, std::size_t randomCount,
                                std::uint64_t seed);

}  // namespace kaboum
