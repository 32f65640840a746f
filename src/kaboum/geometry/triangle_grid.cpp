#include "kaboum/geometry/triangle_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace kaboum::geometry {
namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();
// Two units in the last place, relative: a float moved by this much passes every double that
// rounded to it.
constexpr float kTwoUlps = 2.4e-7f;

// A float not above x.
float floatBelow(double x) {
  const auto f = static_cast<float>(std::clamp(x, -kFloatMax, kFloatMax));
  return f - (std::abs(f) * kTwoUlps + std::numeric_limits<float>::min());
}

// A float not below x.
float floatAbove(double x) {
  const auto f = static_cast<float>(std::clamp(x, -kFloatMax, kFloatMax));
  return f + (std::abs(f) * kTwoUlps + std::numeric_limits<float>::min());
}

}  // namespace

Box3 triangleBox(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  return {{floatBelow(lo.x()), floatBelow(lo.y()), floatBelow(lo.z())},
          {floatAbove(hi.x()), floatAbove(hi.y()), floatAbove(hi.z())}};
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

}  // namespace kaboum::geometry
