#include "kaboum/geometry/triangle_grid.hpp"

#include <bit>

namespace kaboum {

Box3 triangleBox(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

TriangleGrid::TriangleGrid(double cellSize, std::size_t expectedTriangles)
    : cellSize_(cellSize),
      mask_(std::bit_ceil(std::max<std::size_t>(2 * expectedTriangles, 64)) - 1),
      heads_(mask_ + 1, kEnd) {
  entries_.reserve(4 * expectedTriangles);
}

void TriangleGrid::insert(std::uint32_t triangle, const Box3& box) {
  forEachCell(box, [&](std::size_t bucket) {
    std::uint32_t e = free_;
    if (e != kEnd) {
      free_ = entries_[e].next;
    } else {
      e = static_cast<std::uint32_t>(entries_.size());
      entries_.push_back({});
    }
    entries_[e] = {triangle, heads_[bucket]};
    heads_[bucket] = e;
  });
}

void TriangleGrid::remove(std::uint32_t triangle, const Box3& box) {
  forEachCell(box, [&](std::size_t bucket) {
    for (std::uint32_t* link = &heads_[bucket]; *link != kEnd;) {
      const std::uint32_t e = *link;
      if (entries_[e].triangle == triangle) {
        *link = entries_[e].next;
        entries_[e].next = free_;
        free_ = e;
        return;  // one entry per cell and triangle (hash collisions put others in the same list)
      }
      link = &entries_[e].next;
    }
  });
}

void TriangleGrid::move(std::uint32_t triangle, const Box3& from, const Box3& to) {
  if ((cellOf(from.lo) == cellOf(to.lo)).all() && (cellOf(from.hi) == cellOf(to.hi)).all()) return;
  remove(triangle, from);
  insert(triangle, to);
}

}  // namespace kaboum
