// The triangle mesh every geometry algorithm reads and writes: flat vertex and index arrays.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "kaboum/core/types.hpp"

namespace kaboum::geometry {

using Triangle = std::array<std::uint32_t, 3>;

// Counter-clockwise triangles (seen from outside) index into `vertices`.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;

  [[nodiscard]] std::size_t vertexCount() const { return vertices.size(); }
  [[nodiscard]] std::size_t triangleCount() const { return triangles.size(); }
};

}  // namespace kaboum::geometry
