#include "kaboum/geometry/triangle_bvh.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "kaboum/core/error.hpp"

namespace kaboum {

namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kSignTolerance = 1e-12;        // relative to the magnitude bound of a determinant
constexpr double kDegenerateTolerance = 1e-12;  // |normal| relative to longest edge^2
constexpr double kThinTolerance = 1e-8;         // below this, closest points use the edges only
constexpr std::uint32_t kLeafSize = 4;
constexpr int kBins = 16;
constexpr int kMaxSahDepth = 48;  // deeper nodes split at the median: depth stays below 48 + 32

double longestEdgeSquared(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
}

// |n| <= tolerance * longestEdge^2, compared squared.
bool isThin(const Vec3& normal, const Vec3& a, const Vec3& b, const Vec3& c, double tolerance) {
  const double longest = longestEdgeSquared(a, b, c);
  return normal.squaredNorm() <= tolerance * tolerance * longest * longest;
}

bool isDegenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  return isThin((b - a).cross(c - a), a, b, c, kDegenerateTolerance);
}

Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  if (length2 == 0.0) return a;
  return a + std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) * ab;
}

// Sign of `value`, or 0 when |value| <= kSignTolerance * bound.
int toleranceSign(double value, double bound) {
  const double tolerance = kSignTolerance * bound;
  return value > tolerance ? 1 : (value < -tolerance ? -1 : 0);
}

// Sign of `value` when value^2 > kSignTolerance^2 * boundSquared, else 0 (no square roots).
int toleranceSignSquared(double value, double boundSquared) {
  if (value * value <= kSignTolerance * kSignTolerance * boundSquared) return 0;
  return value > 0 ? 1 : -1;
}

// Sign of det[a-d, b-d, c-d] (positive when d is below the counter-clockwise triangle abc).
int orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 ad = a - d, bd = b - d, cd = c - d;
  const double determinant = ad.dot(bd.cross(cd));
  const double bound = std::abs(ad.x()) * (std::abs(bd.y() * cd.z()) + std::abs(bd.z() * cd.y())) +
                       std::abs(ad.y()) * (std::abs(bd.z() * cd.x()) + std::abs(bd.x() * cd.z())) +
                       std::abs(ad.z()) * (std::abs(bd.x() * cd.y()) + std::abs(bd.y() * cd.x()));
  return toleranceSign(determinant, bound);
}

int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ac = a - c, bc = b - c;
  return toleranceSign(ac.x() * bc.y() - ac.y() * bc.x(),
                       std::abs(ac.x() * bc.y()) + std::abs(ac.y() * bc.x()));
}

bool mixedSigns(int s0, int s1, int s2) {
  return (s0 > 0 || s1 > 0 || s2 > 0) && (s0 < 0 || s1 < 0 || s2 < 0);
}

// Projection onto the coordinate plane most parallel to a triangle with normal `normal`.
struct PlaneProjection {
  int u, v;
  explicit PlaneProjection(const Vec3& normal) {
    Eigen::Index dropped = 0;
    normal.cwiseAbs().maxCoeff(&dropped);
    u = static_cast<int>((dropped + 1) % 3);
    v = static_cast<int>((dropped + 2) % 3);
  }
  [[nodiscard]] Vec2 operator()(const Vec3& p) const { return {p[u], p[v]}; }
};

bool pointInTriangle2(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return !mixedSigns(orientation(a, b, p), orientation(b, c, p), orientation(c, a, p));
}

bool segmentsIntersect2(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  const int pqa = orientation(p, q, a), pqb = orientation(p, q, b);
  if (pqa * pqb > 0) return false;
  const int abp = orientation(a, b, p), abq = orientation(a, b, q);
  if (abp * abq > 0) return false;
  if (pqa == 0 && pqb == 0) {  // collinear: compare the intervals along the longer extent
    const Vec2 extent = (p - q).cwiseAbs().cwiseMax((a - b).cwiseAbs());
    const int axis = extent.x() >= extent.y() ? 0 : 1;
    return std::max(std::min(p[axis], q[axis]), std::min(a[axis], b[axis])) <=
           std::min(std::max(p[axis], q[axis]), std::max(a[axis], b[axis]));
  }
  return true;
}

bool segmentIntersectsTriangle2(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b,
                                const Vec2& c) {
  return pointInTriangle2(p, a, b, c) || pointInTriangle2(q, a, b, c) ||
         segmentsIntersect2(p, q, a, b) || segmentsIntersect2(p, q, b, c) ||
         segmentsIntersect2(p, q, c, a);
}

// Coplanar triangles overlap when an edge of one meets the other, or one lies inside the other.
bool coplanarTrianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                const Vec3& b1, const Vec3& b2) {
  const PlaneProjection project((b1 - b0).cross(b2 - b0));
  const Vec2 p0 = project(a0), p1 = project(a1), p2 = project(a2);
  const Vec2 q0 = project(b0), q1 = project(b1), q2 = project(b2);
  return segmentIntersectsTriangle2(p0, p1, q0, q1, q2) ||
         segmentIntersectsTriangle2(p1, p2, q0, q1, q2) ||
         segmentIntersectsTriangle2(p2, p0, q0, q1, q2) || pointInTriangle2(q0, p0, p1, p2);
}

double boxDistanceSquared(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

double surfaceArea(const Vec3& lo, const Vec3& hi) {
  const Vec3 e = hi - lo;
  return 2.0 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a);
  if (!isThin(normal, a, b, c, kThinTolerance) && normal.dot((b - a).cross(p - a)) >= 0.0 &&
      normal.dot((c - b).cross(p - b)) >= 0.0 && normal.dot((a - c).cross(p - c)) >= 0.0) {
    return p - normal * (normal.dot(p - a) / normal.squaredNorm());
  }
  const Vec3 onAb = closestPointOnSegment(p, a, b);
  const Vec3 onBc = closestPointOnSegment(p, b, c);
  const Vec3 onCa = closestPointOnSegment(p, c, a);
  const double dAb = (onAb - p).squaredNorm(), dBc = (onBc - p).squaredNorm(),
               dCa = (onCa - p).squaredNorm();
  if (dAb <= dBc && dAb <= dCa) return onAb;
  return dBc <= dCa ? onBc : onCa;
}

namespace {

// segmentIntersectsTriangle for a triangle already known not to be degenerate.
bool segmentMeetsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                          const Vec3& c) {
  const int sideP = orientation(a, b, c, p), sideQ = orientation(a, b, c, q);
  if (sideP * sideQ > 0) return false;
  if (sideP == 0 && sideQ == 0) {
    const PlaneProjection project((b - a).cross(c - a));
    return segmentIntersectsTriangle2(project(p), project(q), project(a), project(b), project(c));
  }
  // The segment meets the plane; it meets the triangle if its line passes inside all three edges.
  return !mixedSigns(orientation(p, q, a, b), orientation(p, q, b, c), orientation(p, q, c, a));
}

}  // namespace

bool segmentIntersectsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                               const Vec3& c) {
  return !isDegenerate(a, b, c) && segmentMeetsTriangle(p, q, a, b, c);
}

bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                        const Vec3& b1, const Vec3& b2) {
  if (isDegenerate(a0, a1, a2) || isDegenerate(b0, b1, b2)) return false;
  const int a0Side = orientation(b0, b1, b2, a0), a1Side = orientation(b0, b1, b2, a1),
            a2Side = orientation(b0, b1, b2, a2);
  if (a0Side * a1Side > 0 && a1Side * a2Side > 0) return false;
  const int b0Side = orientation(a0, a1, a2, b0), b1Side = orientation(a0, a1, a2, b1),
            b2Side = orientation(a0, a1, a2, b2);
  if (b0Side * b1Side > 0 && b1Side * b2Side > 0) return false;
  if ((a0Side == 0 && a1Side == 0 && a2Side == 0) || (b0Side == 0 && b1Side == 0 && b2Side == 0)) {
    return coplanarTrianglesIntersect(a0, a1, a2, b0, b1, b2);
  }
  // Non-coplanar: the intersection segment, if any, ends on an edge of one of the triangles.
  return segmentMeetsTriangle(a0, a1, b0, b1, b2) || segmentMeetsTriangle(a1, a2, b0, b1, b2) ||
         segmentMeetsTriangle(a2, a0, b0, b1, b2) || segmentMeetsTriangle(b0, b1, a0, a1, a2) ||
         segmentMeetsTriangle(b1, b2, a0, a1, a2) || segmentMeetsTriangle(b2, b0, a0, a1, a2);
}

bool trianglesMeetBesideSharedVertex(const Vec3& s, const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                     const Vec3& q2) {
  if (isDegenerate(s, p1, q1) || isDegenerate(s, p2, q2)) return false;
  return segmentMeetsTriangle(p1, q1, s, p2, q2) || segmentMeetsTriangle(p2, q2, s, p1, q1);
}

bool meshTrianglesIntersect(const std::array<Vec3, 3>& t, const Triangle& tIds,
                            const std::array<Vec3, 3>& u, const Triangle& uIds) {
  int shared = 0;
  int sharedInT = 0, sharedInU = 0;
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      if (tIds[k] == uIds[l]) {
        ++shared;
        sharedInT = k;
        sharedInU = l;
      }
    }
  }
  if (shared == 0) return trianglesIntersect(t[0], t[1], t[2], u[0], u[1], u[2]);
  if (shared > 1) return false;
  const auto at = [](const std::array<Vec3, 3>& x, int start, int k) -> const Vec3& {
    return x[(start + k) % 3];
  };
  return trianglesMeetBesideSharedVertex(at(t, sharedInT, 0), at(t, sharedInT, 1),
                                         at(t, sharedInT, 2), at(u, sharedInU, 1),
                                         at(u, sharedInU, 2));
}

TriangleBvh::TriangleBvh(const TriangleMesh& mesh) : vertices_(mesh.vertices) {
  const std::size_t count = mesh.triangles.size();
  if (count == 0) throw InputError("mesh has no triangles");
  if (count >= std::size_t{0xffffffffu} / 2) {
    throw InputError(fmt::format("mesh has too many triangles ({})", count));
  }
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    if (!vertices_[i].allFinite()) {
      throw InputError(fmt::format("vertex {} has a non-finite coordinate", i));
    }
  }
  std::vector<BuildItem> items(count);
  Vec3 meshLo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 meshHi = -meshLo;
  for (std::size_t t = 0; t < count; ++t) {
    const Triangle& tri = mesh.triangles[t];
    for (const std::uint32_t index : tri) {
      if (index >= vertices_.size()) {
        throw InputError(fmt::format("triangle {} uses vertex {} but the mesh has {} vertices", t,
                                     index, vertices_.size()));
      }
    }
    const Vec3 &a = vertices_[tri[0]], &b = vertices_[tri[1]], &c = vertices_[tri[2]];
    items[t] = {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), (a + b + c) / 3.0,
                static_cast<std::uint32_t>(t)};
    meshLo = meshLo.cwiseMin(items[t].lo);
    meshHi = meshHi.cwiseMax(items[t].hi);
  }
  // Padding keeps boxes conservative under the rounding of slab tests and near-surface queries.
  padding_ = 1e-9 * (meshHi - meshLo).norm() +
             1e-12 * meshLo.cwiseAbs().cwiseMax(meshHi.cwiseAbs()).maxCoeff();
  nodes_.reserve(2 * count / kLeafSize + 1);
  build(items, 0, static_cast<std::uint32_t>(count), 0);
  nodes_.shrink_to_fit();
  triangles_.resize(count);
  triangleIds_.resize(count);
  for (std::size_t slot = 0; slot < count; ++slot) {
    triangleIds_[slot] = items[slot].triangle;
    triangles_[slot] = mesh.triangles[items[slot].triangle];
  }
}

std::uint32_t TriangleBvh::build(std::vector<BuildItem>& items, std::uint32_t begin,
                                 std::uint32_t end, int depth) {
  const Vec3 infinite = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 lo = infinite, hi = -infinite, centroidLo = infinite, centroidHi = -infinite;
  for (std::uint32_t k = begin; k < end; ++k) {
    lo = lo.cwiseMin(items[k].lo);
    hi = hi.cwiseMax(items[k].hi);
    centroidLo = centroidLo.cwiseMin(items[k].centroid);
    centroidHi = centroidHi.cwiseMax(items[k].centroid);
  }
  const auto nodeIndex = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({lo.array() - padding_, hi.array() + padding_, 0, 0});
  const std::uint32_t count = end - begin;
  if (count <= kLeafSize) {
    nodes_[nodeIndex].first = begin;
    nodes_[nodeIndex].count = count;
    return nodeIndex;
  }

  const auto first = items.begin() + begin, last = items.begin() + end;
  const Vec3 centroidExtent = centroidHi - centroidLo;
  const Vec3 binScale =
      (centroidExtent.array() > 0.0).select(kBins / centroidExtent.array(), Eigen::Array3d::Zero());
  const auto binOf = [&](const BuildItem& item, int axis) {
    return std::min(kBins - 1,
                    static_cast<int>((item.centroid[axis] - centroidLo[axis]) * binScale[axis]));
  };
  auto middle = first;
  if (depth < kMaxSahDepth) {
    // Binned surface area heuristic over all three axes at once: cost = area * triangles, summed
    // over both sides of each of the kBins - 1 candidate planes per axis.
    struct Bin {
      Vec3 lo, hi;
      std::uint32_t count;
    };
    std::array<std::array<Bin, kBins>, 3> bins;
    for (auto& axisBins : bins) axisBins.fill({infinite, -infinite, 0});
    for (auto item = first; item != last; ++item) {
      for (int axis = 0; axis < 3; ++axis) {
        Bin& bin = bins[axis][binOf(*item, axis)];
        bin.lo = bin.lo.cwiseMin(item->lo);
        bin.hi = bin.hi.cwiseMax(item->hi);
        ++bin.count;
      }
    }
    double bestCost = std::numeric_limits<double>::infinity();
    int bestAxis = -1, bestSplit = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (binScale[axis] == 0.0) continue;
      const auto& axisBins = bins[axis];
      std::array<double, kBins> leftCost{};  // leftCost[s]: bins [0, s) on the left
      Vec3 sweepLo = infinite, sweepHi = -infinite;
      std::uint32_t sweepCount = 0;
      for (int s = 1; s < kBins; ++s) {
        sweepCount += axisBins[s - 1].count;
        sweepLo = sweepLo.cwiseMin(axisBins[s - 1].lo);
        sweepHi = sweepHi.cwiseMax(axisBins[s - 1].hi);
        leftCost[s] = sweepCount > 0 ? sweepCount * surfaceArea(sweepLo, sweepHi) : 0.0;
      }
      sweepLo = infinite;
      sweepHi = -infinite;
      sweepCount = 0;
      for (int s = kBins - 1; s >= 1; --s) {
        sweepCount += axisBins[s].count;
        sweepLo = sweepLo.cwiseMin(axisBins[s].lo);
        sweepHi = sweepHi.cwiseMax(axisBins[s].hi);
        if (sweepCount == 0 || sweepCount == count) continue;
        const double cost = leftCost[s] + sweepCount * surfaceArea(sweepLo, sweepHi);
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = axis;
          bestSplit = s;
        }
      }
    }
    if (bestAxis >= 0) {
      middle = std::partition(
          first, last, [&](const BuildItem& item) { return binOf(item, bestAxis) < bestSplit; });
    }
  }
  if (middle == first || middle == last) {
    // Median split on the widest centroid axis: guarantees progress and logarithmic depth.
    Eigen::Index axis = 0;
    centroidExtent.maxCoeff(&axis);
    middle = first + count / 2;
    std::nth_element(first, middle, last, [&](const BuildItem& x, const BuildItem& y) {
      return x.centroid[axis] < y.centroid[axis];
    });
  }
  const auto split = static_cast<std::uint32_t>(middle - items.begin());
  build(items, begin, split, depth + 1);
  nodes_[nodeIndex].first = build(items, split, end, depth + 1);
  return nodeIndex;
}

TriangleBvh::Closest TriangleBvh::closest(const Vec3& query) const {
  Closest best{Vec3::Zero(), 0.0, 0};
  double bestDistance2 = std::numeric_limits<double>::infinity();
  std::array<std::pair<std::uint32_t, double>, kMaxDepth> stack;
  std::size_t size = 0;
  std::uint32_t node = 0;
  while (true) {
    const Node& n = nodes_[node];
    if (n.count > 0) {
      for (std::uint32_t slot = n.first; slot < n.first + n.count; ++slot) {
        const Triangle& tri = triangles_[slot];
        const Vec3 point =
            closestPointOnTriangle(query, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
        const double distance2 = (point - query).squaredNorm();
        if (distance2 < bestDistance2) {
          bestDistance2 = distance2;
          best.point = point;
          best.triangle = triangleIds_[slot];
        }
      }
    } else {
      std::uint32_t nearChild = node + 1, farChild = n.first;
      double nearDistance2 = boxDistanceSquared(nodes_[nearChild].lo, nodes_[nearChild].hi, query);
      double farDistance2 = boxDistanceSquared(nodes_[farChild].lo, nodes_[farChild].hi, query);
      if (farDistance2 < nearDistance2) {
        std::swap(nearChild, farChild);
        std::swap(nearDistance2, farDistance2);
      }
      if (farDistance2 < bestDistance2) stack[size++] = {farChild, farDistance2};
      if (nearDistance2 < bestDistance2) {
        node = nearChild;
        continue;
      }
    }
    while (size > 0 && stack[size - 1].second >= bestDistance2) --size;
    if (size == 0) break;
    node = stack[--size].first;
  }
  best.distance = std::sqrt(bestDistance2);
  return best;
}

std::span<const Vec3> TriangleBvh::insideTestDirections() {
  static const std::array<Vec3, 9> directions = [] {
    std::array<Vec3, 9> unit{Vec3(0.6204, 0.3592, 0.6972),   Vec3(-0.3172, 0.8447, -0.4311),
                             Vec3(0.2213, -0.5169, 0.8263),  Vec3(-0.7631, -0.2417, 0.5994),
                             Vec3(0.4456, 0.7218, -0.5296),  Vec3(-0.1938, -0.6623, -0.7238),
                             Vec3(0.8815, -0.2867, -0.3752), Vec3(-0.5541, 0.4309, 0.7122),
                             Vec3(0.3349, 0.2178, -0.9167)};
    for (Vec3& d : unit) d.normalize();
    return unit;
  }();
  return directions;
}

std::optional<int> TriangleBvh::rayWinding(const Vec3& origin, const Vec3& direction) const {
  const Vec3 inverse = direction.cwiseInverse();
  int winding = 0;
  std::array<std::uint32_t, kMaxDepth> stack;
  std::size_t size = 0;
  std::uint32_t node = 0;
  while (true) {
    const Node& n = nodes_[node];
    const Vec3 t0 = (n.lo - origin).cwiseProduct(inverse),
               t1 = (n.hi - origin).cwiseProduct(inverse);
    const double tNear = std::max(t0.cwiseMin(t1).maxCoeff(), 0.0);
    const double tFar = t0.cwiseMax(t1).minCoeff();
    if (tNear <= tFar) {
      if (n.count == 0) {
        stack[size++] = n.first;
        node = node + 1;
        continue;
      }
      for (std::uint32_t slot = n.first; slot < n.first + n.count; ++slot) {
        const Triangle& tri = triangles_[slot];
        const Vec3 a = vertices_[tri[0]] - origin, b = vertices_[tri[1]] - origin,
                   c = vertices_[tri[2]] - origin;
        const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
        const Vec3 bc = b.cross(c);
        // Which side of the planes through the ray origin and each edge the ray passes.
        const int sideAb = toleranceSignSquared(direction.dot(a.cross(b)), a2 * b2);
        const int sideBc = toleranceSignSquared(direction.dot(bc), b2 * c2);
        const int sideCa = toleranceSignSquared(direction.dot(c.cross(a)), c2 * a2);
        if (mixedSigns(sideAb, sideBc, sideCa)) continue;  // the ray's line misses
        if (sideAb == 0 || sideBc == 0 || sideCa == 0) return std::nullopt;  // edge or vertex
        // The line crosses; det[a, b, c] has the crossing's sign when it lies ahead of the origin.
        const int volume = toleranceSignSquared(a.dot(bc), a2 * b2 * c2);
        if (volume == 0) return std::nullopt;  // the origin lies on the triangle
        if (volume == sideAb) winding += sideAb;
      }
    }
    if (size == 0) break;
    node = stack[--size];
  }
  return winding;
}

bool TriangleBvh::contains(const Vec3& p) const {
  int insideVotes = 0, outsideVotes = 0;
  for (const Vec3& direction : insideTestDirections()) {
    const std::optional<int> winding = rayWinding(p, direction);
    if (!winding) continue;
    ++(*winding != 0 ? insideVotes : outsideVotes);
    if (insideVotes == 2 || outsideVotes == 2) break;
  }
  if (insideVotes + outsideVotes == 0) return true;
  return insideVotes > outsideVotes;
}

bool TriangleBvh::intersectsTriangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                     std::span<const std::uint32_t> ignoreVertexIds) const {
  if (isDegenerate(a, b, c)) return false;
  bool found = false;
  forEachSlotOverlapping(
      a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), [&](std::uint32_t slot) {
        const Triangle& tri = triangles_[slot];
        for (const std::uint32_t id : tri) {
          if (std::find(ignoreVertexIds.begin(), ignoreVertexIds.end(), id) !=
              ignoreVertexIds.end()) {
            return true;
          }
        }
        found =
            trianglesIntersect(a, b, c, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
        return !found;
      });
  return found;
}

}  // namespace kaboum
