// The meshes of a viewer page packed small (docs/viewer.md, "Page data"): every set of positions
// quantized to 16 bits per coordinate within its bounding box, triangle indices as 32-bit
// integers, both streams deflated (zlib) and base64-encoded; the page inflates them with the
// browser's DecompressionStream. Convex pieces are packed as their vertices only (the page takes
// their hull), so the bounding pieces the planner used (thesis §4.4) cost little.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "kaboum/core/types.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::web {

class GeometryPack {
 public:
  // Adds a triangle mesh and returns its entry index.
  std::size_t addMesh(const geometry::TriangleMesh& mesh);
  // Adds the vertices of a convex piece and returns its entry index.
  std::size_t addPoints(std::span<const Vec3> points);

  [[nodiscard]] std::size_t entryCount() const { return entries_.size(); }
  // {"entries": [{"min": [x, y, z], "step": [x, y, z], "positions": [first, count],
  // "indices": [first, count]}], "positions": base64 of deflated uint16 triples, "indices":
  // base64 of deflated uint32}; a point set's indices count is 0. Little-endian.
  [[nodiscard]] nlohmann::json json() const;

 private:
  std::size_t addPositions(std::span<const Vec3> points);

  nlohmann::json entries_ = nlohmann::json::array();
  std::vector<std::uint16_t> positions_;
  std::vector<std::uint32_t> indices_;
};

// `bytes` deflated with zlib (its header and checksum: DecompressionStream("deflate")) and
// base64-encoded.
std::string deflateBase64(std::span<const std::uint8_t> bytes);

}  // namespace kaboum::web
