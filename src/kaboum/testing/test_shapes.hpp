// Procedural closed and open meshes with known geometry, for tests and benchmarks of every module.
// All closed shapes are consistently oriented, counter-clockwise seen from outside.
#pragma once

#include <cstdint>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;

// Icosahedron subdivided `subdivisions` times with vertices on the sphere: 20 * 4^s triangles.
TriangleMesh makeIcosphere(int subdivisions, double radius = 1.0,
                           const Vec3& center = Vec3::Zero());

// Axis-aligned box whose faces are `segments` x `segments` grids of square pairs of triangles.
TriangleMesh makeBox(const Vec3& min, const Vec3& max, int segments = 1);

// The same box without its top (+z) face: an open mesh with one border loop.
TriangleMesh makeOpenBox(const Vec3& min, const Vec3& max, int segments = 1);

// Torus around the z axis: `majorSegments` around the axis times `minorSegments` around the tube.
TriangleMesh makeTorus(double majorRadius, double minorRadius, int majorSegments,
                       int minorSegments);

// Concave prism over the L-shaped polygon (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), z from 0 to
// `height`. Star-shaped with respect to every point of [0,1]^2 x [0,height]. Volume 3 * height.
TriangleMesh makeLPrism(double height = 1.0);

// Two cones on a regular `rimVertices`-gon of circumradius 1 in the plane z = 0, apexes at z = ±1:
// each apex has valence `rimVertices` (the high-valence case of the bounding mesh benchmark).
TriangleMesh makeDoubleCone(int rimVertices);

// A cylinder of radius 1 around the z axis from z = 0 to `height`: `segments` around, the side
// split into `rings` rows, each cap a fan around its centre (of valence `segments`): the triangle
// fans of CAD exports.
TriangleMesh makeFannedCylinder(int segments, int rings, double height = 1.0);

// The points a decomposition cell below the plane z = `height` hulls: the mesh's vertices at or
// below it and the crossings of its edges with it (coplanar up to rounding, as cut faces are).
std::vector<Vec3> pointsBelowCut(const TriangleMesh& mesh, double height);

// Every vertex mapped to center + scale * (v - center) + offset.
TriangleMesh transformMesh(const TriangleMesh& mesh, double scale, const Vec3& center,
                           const Vec3& offset = Vec3::Zero());

// Both meshes in one vertex and triangle list (`second`'s indices shifted).
TriangleMesh mergeMeshes(const TriangleMesh& first, const TriangleMesh& second);

// Every triangle's orientation reversed (outward becomes inward).
TriangleMesh flipMesh(const TriangleMesh& mesh);

}  // namespace kaboum::testing
