#include "kaboum/geometry/quick_hull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace kaboum::geometry {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// How far, in tolerances, a hull vertex may be above a face's plane in the result: sliver faces
// between nearly coplanar points tilt by more than the tolerance, a fold by far more.
constexpr double kCheckFactor = 1000.0;

// A hull triangle: corners counter-clockwise seen from outside, the triangle across each edge
// (edge k runs from corner k to corner k+1), its plane, and the points above it (its outside set).
struct Face {
  std::array<std::uint32_t, 3> corners;
  std::array<std::uint32_t, 3> across{kNone, kNone, kNone};
  Vec3 normal;
  double offset = 0.0;
  std::uint32_t outside = kNone;   // first point of the outside set (a list through nextOutside_)
  std::uint32_t farthest = kNone;  // the point of the outside set farthest above the plane
  double farthestDistance = 0.0;
  bool alive = true;
  std::uint64_t seen = 0;  // the addPoint that last tested it against its eye
  bool visible = false;    // what that test found
};

class QuickHull {
 public:
  QuickHull(std::span<const Vec3> points, double tolerance)
      : points_(points), tolerance_(tolerance) {}

  std::optional<TriangleMesh> run() {
    if (points_.size() < 4) return std::nullopt;
    nextOutside_.assign(points_.size(), kNone);
    cornerStamps_.assign(points_.size(), 0);
    faces_.reserve(8 * points_.size());
    if (!startTetrahedron()) return std::nullopt;
    // Faces are appended as points are added; a face gets outside points only when it is made,
    // so one pass over the growing list handles them all.
    for (std::uint32_t f = 0; f < faces_.size(); ++f) {
      if (faces_[f].alive && faces_[f].farthest != kNone && !addPoint(f)) return std::nullopt;
    }
    if (!convex()) return std::nullopt;
    return mesh();
  }

 private:
  [[nodiscard]] double height(const Face& face, std::uint32_t point) const {
    return face.normal.dot(points_[point]) - face.offset;
  }

  // A face over corners a, b, c (outward when counter-clockwise seen from outside); false when
  // they are collinear.
  bool addFace(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    Face face;
    face.corners = {a, b, c};
    const Vec3 n = (points_[b] - points_[a]).cross(points_[c] - points_[a]);
    const double length = n.norm();
    if (!(length > 0.0)) return false;
    face.normal = n / length;
    face.offset = face.normal.dot(points_[a]);
    faces_.push_back(std::move(face));
    return true;
  }

  // Puts the point in the outside set of the first of `candidates` it is above (by more than
  // the tolerance); a point above none is inside the hull for good.
  void assign(std::uint32_t point, std::span<const std::uint32_t> candidates) {
    for (const std::uint32_t f : candidates) {
      Face& face = faces_[f];
      const double h = height(face, point);
      if (h > tolerance_) {
        nextOutside_[point] = face.outside;
        face.outside = point;
        if (h > face.farthestDistance) {
          face.farthestDistance = h;
          face.farthest = point;
        }
        return;
      }
    }
  }

  // The tetrahedron of two far-apart extreme points, the point farthest from their line and the
  // point farthest from the plane of those three; false when the points span no volume.
  bool startTetrahedron() {
    std::array<std::uint32_t, 6> extremes{};
    for (std::uint32_t i = 0; i < points_.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        if (points_[i][axis] < points_[extremes[2 * axis]][axis]) extremes[2 * axis] = i;
        if (points_[i][axis] > points_[extremes[2 * axis + 1]][axis]) extremes[2 * axis + 1] = i;
      }
    }
    std::uint32_t a = 0, b = 0;
    double widest = -1.0;
    for (const std::uint32_t i : extremes) {
      for (const std::uint32_t j : extremes) {
        if (const double d = (points_[i] - points_[j]).squaredNorm(); d > widest) {
          widest = d;
          a = i;
          b = j;
        }
      }
    }
    if (!(std::sqrt(widest) > tolerance_)) return false;
    const Vec3 line = (points_[b] - points_[a]).normalized();
    std::uint32_t c = kNone;
    double farthest = tolerance_;
    for (std::uint32_t i = 0; i < points_.size(); ++i) {
      const Vec3 offset = points_[i] - points_[a];
      if (const double d = (offset - offset.dot(line) * line).norm(); d > farthest) {
        farthest = d;
        c = i;
      }
    }
    if (c == kNone) return false;
    const Vec3 normal = (points_[b] - points_[a]).cross(points_[c] - points_[a]).normalized();
    std::uint32_t d = kNone;
    farthest = tolerance_;
    for (std::uint32_t i = 0; i < points_.size(); ++i) {
      if (const double h = std::abs(normal.dot(points_[i] - points_[a])); h > farthest) {
        farthest = h;
        d = i;
      }
    }
    if (d == kNone) return false;
    if (normal.dot(points_[d] - points_[a]) > 0.0) std::swap(b, c);  // d below (a, b, c)
    if (!addFace(a, b, c) || !addFace(a, d, b) || !addFace(b, d, c) || !addFace(c, d, a)) {
      return false;
    }
    for (std::uint32_t f = 0; f < 4; ++f) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t from = faces_[f].corners[k], to = faces_[f].corners[(k + 1) % 3];
        for (std::uint32_t g = 0; g < 4; ++g) {
          if (edgeIndex(g, to, from) >= 0) faces_[f].across[k] = g;
        }
      }
    }
    const std::array<std::uint32_t, 4> all{0, 1, 2, 3};
    for (std::uint32_t i = 0; i < points_.size(); ++i) {
      if (i != a && i != b && i != c && i != d) assign(i, all);
    }
    return true;
  }

  // The k with face g's edge k running from `from` to `to`, or -1.
  [[nodiscard]] int edgeIndex(std::uint32_t g, std::uint32_t from, std::uint32_t to) const {
    for (int k = 0; k < 3; ++k) {
      if (faces_[g].corners[k] == from && faces_[g].corners[(k + 1) % 3] == to) return k;
    }
    return -1;
  }

  // Adds the farthest point above face f: the faces it sees (by more than the tolerance, reached
  // from f) go, a cone of faces from it to their horizon replaces them, and their outside points
  // move to the cone. False when the horizon is not one simple loop (a tolerance problem).
  bool addPoint(std::uint32_t f) {
    const std::uint32_t eye = faces_[f].farthest;
    ++stamp_;
    visible_.assign(1, f);
    see(f, true);
    horizon_.clear();
    // Depth first over the visible faces, each face's edges in order starting after the edge it
    // was entered by: the horizon edges come out as one counter-clockwise loop.
    stack_.assign(1, Visit{f, 0, 3});
    while (!stack_.empty()) {
      Visit& top = stack_.back();
      if (top.left == 0) {
        stack_.pop_back();
        continue;
      }
      const std::uint32_t face = top.face;
      const int k = top.edge;
      top.edge = (k + 1) % 3;
      --top.left;
      const std::uint32_t next = faces_[face].across[k];
      if (faces_[next].seen == stamp_) {
        if (!faces_[next].visible) horizon_.push_back({face, k});
        continue;
      }
      if (height(faces_[next], eye) > tolerance_) {
        see(next, true);
        visible_.push_back(next);
        int back = -1;
        for (int j = 0; j < 3; ++j) {
          if (faces_[next].across[j] == face) back = j;
        }
        if (back < 0) return false;
        stack_.push_back({next, (back + 1) % 3, 2});
      } else {
        see(next, false);
        horizon_.push_back({face, k});
      }
    }
    // One simple loop: every edge starts where the previous one ends, no corner twice.
    const std::size_t m = horizon_.size();
    if (m < 3) return false;
    ++stamp_;
    for (std::size_t i = 0; i < m; ++i) {
      const auto [face, k] = horizon_[i];
      const auto [nextFace, nextK] = horizon_[(i + 1) % m];
      const std::uint32_t start = faces_[face].corners[k];
      if (faces_[face].corners[(k + 1) % 3] != faces_[nextFace].corners[nextK]) return false;
      if (cornerStamps_[start] == stamp_) return false;
      cornerStamps_[start] = stamp_;
    }
    // The cone from the eye over the horizon.
    const auto first = static_cast<std::uint32_t>(faces_.size());
    for (std::size_t i = 0; i < m; ++i) {
      const auto [face, k] = horizon_[i];
      const std::uint32_t a = faces_[face].corners[k], b = faces_[face].corners[(k + 1) % 3];
      const std::uint32_t outer = faces_[face].across[k];
      if (!addFace(a, b, eye)) return false;
      const auto made = static_cast<std::uint32_t>(faces_.size() - 1);
      Face& cone = faces_[made];
      cone.across = {outer, first + static_cast<std::uint32_t>((i + 1) % m),
                     first + static_cast<std::uint32_t>((i + m - 1) % m)};
      const int j = edgeIndex(outer, b, a);
      if (j < 0) return false;
      faces_[outer].across[j] = made;
    }
    cone_.resize(m);
    for (std::size_t i = 0; i < m; ++i) cone_[i] = first + static_cast<std::uint32_t>(i);
    for (const std::uint32_t v : visible_) {
      faces_[v].alive = false;
      for (std::uint32_t p = faces_[v].outside; p != kNone;) {
        const std::uint32_t next = nextOutside_[p];
        if (p != eye) assign(p, cone_);
        p = next;
      }
    }
    return true;
  }

  // Every hull vertex is at most kCheckFactor tolerances above the plane of every face, so the
  // surface is convex up to that: nearly coplanar points can fold it (or tilt a sliver face) when
  // the tolerance decides their visibility inconsistently, and then there is no hull.
  [[nodiscard]] bool convex() const {
    std::vector<std::uint32_t> corners;
    for (const Face& face : faces_) {
      if (face.alive) corners.insert(corners.end(), face.corners.begin(), face.corners.end());
    }
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    const double limit = kCheckFactor * tolerance_;
    for (const Face& face : faces_) {
      if (!face.alive) continue;
      for (const std::uint32_t corner : corners) {
        if (height(face, corner) > limit) return false;
      }
    }
    return true;
  }

  void see(std::uint32_t face, bool visible) {
    faces_[face].seen = stamp_;
    faces_[face].visible = visible;
  }

  // The live faces as a mesh over the points they use.
  TriangleMesh mesh() const {
    TriangleMesh result;
    std::vector<std::uint32_t> index(points_.size(), kNone);
    for (const Face& face : faces_) {
      if (!face.alive) continue;
      Triangle t{};
      for (int k = 0; k < 3; ++k) {
        std::uint32_t& i = index[face.corners[k]];
        if (i == kNone) {
          i = static_cast<std::uint32_t>(result.vertices.size());
          result.vertices.push_back(points_[face.corners[k]]);
        }
        t[k] = i;
      }
      result.triangles.push_back(t);
    }
    return result;
  }

  std::span<const Vec3> points_;
  double tolerance_;
  std::vector<Face> faces_;
  std::vector<std::uint32_t> nextOutside_;   // the next point of the same outside set
  std::vector<std::uint64_t> cornerStamps_;  // the addPoint whose horizon last passed the point
  std::uint64_t stamp_ = 0;
  std::vector<std::uint32_t> visible_, cone_;
  std::vector<std::pair<std::uint32_t, int>> horizon_;  // (visible face, edge) in loop order
  // A face of the depth-first search and its edges left to look across.
  struct Visit {
    std::uint32_t face;
    int edge;
    int left;
  };
  std::vector<Visit> stack_;
};

}  // namespace

std::optional<TriangleMesh> quickHull(std::span<const Vec3> points, double tolerance) {
  return QuickHull(points, tolerance).run();
}

}  // namespace kaboum::geometry
