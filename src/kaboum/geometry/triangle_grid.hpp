// A dynamic spatial hash of triangles by bounding box, for finding the triangles near a moving
// patch while a mesh is being edited. Allocation-free after warm-up (pooled bucket entries).
#pragma once

#include <cstdint>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::geometry {

// An axis-aligned box in single precision, rounded outward so it contains the exact box: half the
// memory of a double box, and overlap tests stay conservative.
struct Box3 {
  Eigen::Vector3f lo, hi;
  [[nodiscard]] bool overlaps(const Box3& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
  // The diagonal squared: at least the longest edge squared of a triangle inside the box.
  [[nodiscard]] double diagonalSquared() const {
    return (hi.cast<double>() - lo.cast<double>()).squaredNorm();
  }
};

// The hash of grid cell (x, y, z) that spatial hashes reduce to a bucket index with a mask.
inline std::uint64_t cellHash(int x, int y, int z) {
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) * 73856093ull ^
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) * 19349663ull ^
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(z)) * 83492791ull;
}

// The box of triangle (a, b, c), rounded outward.
Box3 triangleBox(const Vec3& a, const Vec3& b, const Vec3& c);

class TriangleGrid {
 public:
  // `cellSize` should be about the length of a typical edge; `expectedTriangles` sizes the table.
  TriangleGrid(double cellSize, std::size_t expectedTriangles);

  void insert(std::uint32_t triangle, const Box3& box);
  // `box` must be the box the triangle was inserted with.
  void remove(std::uint32_t triangle, const Box3& box);
  // Re-registers a triangle inserted with `from` under `to`; nothing to do when both boxes touch
  // the same cells.
  void move(std::uint32_t triangle, const Box3& from, const Box3& to);
  // Calls f(triangle) for every inserted triangle registered in a cell `box` touches (a triangle
  // may be reported more than once; callers deduplicate).
  template <class F>
  void forEachNear(const Box3& box, F&& f) const {
    forEachCell(box, [&](std::size_t bucket) {
      for (std::uint32_t e = heads_[bucket]; e != kEnd; e = entries_[e].next)
        f(entries_[e].triangle);
    });
  }
  // False only when no cell `box` touches holds a triangle (hash collisions may make it true).
  [[nodiscard]] bool anyNear(const Box3& box) const {
    const Eigen::Array3i lo = cellOf(box.lo), hi = cellOf(box.hi);
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int z = lo.z(); z <= hi.z(); ++z) {
          if (heads_[bucketOf(x, y, z)] != kEnd) return true;
        }
      }
    }
    return false;
  }
  [[nodiscard]] double cellSize() const { return cellSize_; }

 private:
  static constexpr std::uint32_t kEnd = 0xffffffffu;
  struct Entry {
    std::uint32_t triangle, next;
  };
  [[nodiscard]] Eigen::Array3i cellOf(const Eigen::Vector3f& p) const {
    return (p.cast<double>().array() / cellSize_).floor().cast<int>();
  }
  template <class F>
  void forEachCell(const Box3& box, F&& f) const {
    const Eigen::Array3i lo = cellOf(box.lo), hi = cellOf(box.hi);
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int z = lo.z(); z <= hi.z(); ++z) f(bucketOf(x, y, z));
      }
    }
  }
  [[nodiscard]] std::size_t bucketOf(int x, int y, int z) const {
    return static_cast<std::size_t>(cellHash(x, y, z) & mask_);
  }

  double cellSize_;
  std::uint64_t mask_;
  std::vector<std::uint32_t> heads_;
  std::vector<Entry> entries_;
  std::uint32_t free_ = kEnd;
};

}  // namespace kaboum::geometry
