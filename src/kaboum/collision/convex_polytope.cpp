#include "kaboum/collision/convex_polytope.hpp"

#include <algorithm>

namespace kaboum::collision {

ConvexPolytope::ConvexPolytope(std::span<const Vec3> points, const std::string& what)
    : ConvexPolytope(convexHull(points, what)) {}

ConvexPolytope::ConvexPolytope(const ConvexHull& hull) : vertices_(hull.mesh.vertices) {
  const auto n = static_cast<std::uint32_t>(vertices_.size());
  // Every hull edge, both ways, sorted by source vertex then deduplicated (each edge is shared by
  // two triangles).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(hull.mesh.triangles.size() * 6);
  for (const Triangle& t : hull.mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(t[k], t[(k + 1) % 3]);
      edges.emplace_back(t[(k + 1) % 3], t[k]);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  neighborBegin_.assign(n + 1, 0);
  neighbors_.reserve(edges.size());
  for (const auto& [from, to] : edges) {
    ++neighborBegin_[from + 1];
    neighbors_.push_back(to);
  }
  for (std::uint32_t i = 0; i < n; ++i) neighborBegin_[i + 1] += neighborBegin_[i];

  center_ = Vec3::Zero();
  box_.setEmpty();
  for (const Vec3& v : vertices_) {
    coordinates_.insert(coordinates_.end(), {v.x(), v.y(), v.z()});
    center_ += v;
    box_.extend(v);
  }
  center_ /= static_cast<double>(n);
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) seeds_.push_back(scan(sign * Vec3::Unit(axis)));
  }
  for (int corner = 0; corner < 8; ++corner) {
    seeds_.push_back(
        scan(Vec3(corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0)));
  }
  std::sort(seeds_.begin(), seeds_.end());
  seeds_.erase(std::unique(seeds_.begin(), seeds_.end()), seeds_.end());
  sphereCenter_ = box_.center();
  for (const Vec3& v : vertices_) {
    sphereRadius_ = std::max(sphereRadius_, (v - sphereCenter_).norm());
  }
}

}  // namespace kaboum::collision
