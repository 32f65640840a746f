// Axis-aligned boxes and a bounding-volume tree over them: the broad phase that sends only nearby
// convex pieces to the narrow phase.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

struct Aabb {
  Vec3 lo{0, 0, 0};
  Vec3 hi{0, 0, 0};

  [[nodiscard]] bool overlaps(const Aabb& other) const {
    return (lo.array() <= other.hi.array()).all() && (other.lo.array() <= hi.array()).all();
  }
  [[nodiscard]] Aabb inflated(double margin) const {
    return {lo.array() - margin, hi.array() + margin};
  }
  [[nodiscard]] Aabb merged(const Aabb& other) const {
    return {lo.cwiseMin(other.lo), hi.cwiseMax(other.hi)};
  }
};

// Box of a local box [lo, hi] after the rigid transform `pose` (tight for the rotated box).
Aabb transformedAabb(const Aabb& local, const Eigen::Isometry3d& pose);

// Binary tree over boxes, built top-down (median split on the longest axis of the centres).
// Queries are const and allocate nothing.
class AabbTree {
 public:
  // Rebuilds over `boxes`; the id of a box is its index. Reuses the tree's storage.
  void build(std::span<const Aabb> boxes);
  [[nodiscard]] bool empty() const { return nodes_.empty(); }

  // Calls visit(id) for every box overlapping `query` until visit returns false; returns false
  // when stopped early.
  [[nodiscard]] bool anyOverlapping(const Aabb& query) const {
    return !forEachOverlapping(query, [](std::uint32_t) { return false; });
  }

  template <class Visit>
  bool forEachOverlapping(const Aabb& query, Visit&& visit) const {
    if (nodes_.empty() || !nodes_[0].box.overlaps(query)) return true;
    std::array<std::uint32_t, kMaxDepth> stack{};
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
          if (boxes_[i].overlaps(query) && !visit(ids_[i])) return false;
        }
        continue;
      }
      const std::uint32_t left = static_cast<std::uint32_t>(&node - nodes_.data()) + 1;
      if (nodes_[node.first].box.overlaps(query)) stack[top++] = node.first;
      if (nodes_[left].box.overlaps(query)) stack[top++] = left;
    }
    return true;
  }

 private:
  static constexpr std::size_t kMaxDepth = 64;  // median splits keep depth ~log2(n)
  static constexpr std::uint32_t kLeafSize = 2;
  struct Node {
    Aabb box;
    std::uint32_t first = 0;  // leaf: first slot; inner node: index of the second child
    std::uint32_t count = 0;  // leaf: number of slots; 0 for an inner node (first child follows)
  };
  void buildNode(std::uint32_t begin, std::uint32_t end);

  std::vector<Node> nodes_;
  std::vector<Aabb> boxes_;  // per slot, in tree order
  std::vector<std::uint32_t> ids_;
  std::vector<Vec3> centres_;  // build scratch, per slot
};

}  // namespace kaboum::collision
