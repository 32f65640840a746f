// Dense point samples of a mesh surface, the measuring points of the bounding mesh verifier and of
// the Hausdorff figures of Table 4.2 (Eq. 4.1 evaluated on samples).
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// Every vertex used by a triangle (by index), the midpoint of every distinct edge (by vertex pair),
// then `randomCount` uniformly area-weighted random points (deterministic for `seed`, independent
// of platform). Zero-area triangles get no random points; a mesh of zero total area gets none at
// all. Triangle indices must be in range (mesh I/O and TriangleBvh check them).
std::vector<Vec3> sampleSurface(const TriangleMesh& mesh, std::size_t randomCount,
                                std::uint64_t seed);

// The samples of sampleSurface, in the same order, made one at a time: a measurement that stops
// early pays only for the samples it read, and can resume later. The mesh must outlive it.
class SurfaceSampler {
 public:
  SurfaceSampler(const TriangleMesh& mesh, std::size_t randomCount, std::uint64_t seed);
  SurfaceSampler(TriangleMesh&&, std::size_t, std::uint64_t) = delete;  // would outlive it

  // Writes the next sample and returns true, or returns false when all have been made.
  bool next(Vec3& sample);
  // How many samples next() has made so far.
  [[nodiscard]] std::size_t produced() const { return produced_; }

 private:
  enum class Stage { vertices, edges, random, done };
  void beginEdges();
  void beginRandom();

  const TriangleMesh* mesh_;
  std::size_t randomCount_;
  std::uint64_t seed_;
  Stage stage_ = Stage::vertices;
  std::size_t position_ = 0;  // within the current stage
  std::size_t produced_ = 0;
  std::vector<char> used_;              // per vertex: used by a triangle
  std::vector<std::uint64_t> edges_;    // distinct edges, (smaller index << 32) | larger
  std::vector<double> cumulativeArea_;  // per triangle
  std::size_t lastWithArea_ = 0;
  std::optional<std::mt19937_64> engine_;  // seeded when the random points begin
};

}  // namespace kaboum::geometry
