#include "kaboum/geometry/triangle_bvh.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "kaboum/core/error.hpp"

namespace kaboum::geometry {

namespace {

constexpr double kSignTolerance = 1e-12;        // relative to the magnitude bound of a determinant
constexpr double kContactTolerance = 1e-12;     // contact distance relative to the longest edge
constexpr double kDegenerateTolerance = 1e-12;  // |normal| relative to longest edge^2
constexpr double kThinTolerance = 1e-8;         // below this, closest points use the edges only
constexpr std::uint32_t kLeafSize = 4;
constexpr int kBins = 16;
constexpr int kMaxSahDepth = 48;  // deeper nodes split at the median: depth stays below 48 + 32

double longestEdgeSquared(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
}

// |normal| <= tolerance * longest edge^2, compared squared.
bool isThin(double normalSquared, double longestSquared, double tolerance) {
  return normalSquared <= tolerance * tolerance * longestSquared * longestSquared;
}

bool isDegenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  return isThin((b - a).cross(c - a).squaredNorm(), longestEdgeSquared(a, b, c),
                kDegenerateTolerance);
}

Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  if (length2 == 0.0) return a;
  return a + std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) * ab;
}

// Sign of `value` when value^2 > kSignTolerance^2 * boundSquared, else 0 (no square roots).
int toleranceSignSquared(double value, double boundSquared) {
  if (value * value <= kSignTolerance * kSignTolerance * boundSquared) return 0;
  return value > 0 ? 1 : -1;
}

// det[a-d, b-d, c-d] = -(d - a) . ((b - a) x (c - a)), positive when d is below the
// counter-clockwise triangle abc, and a bound on the magnitudes of its terms.
struct Determinant {
  double value, bound;
};
Determinant orientationDeterminant(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 ad = a - d, bd = b - d, cd = c - d;
  return {ad.dot(bd.cross(cd)),
          std::abs(ad.x()) * (std::abs(bd.y() * cd.z()) + std::abs(bd.z() * cd.y())) +
              std::abs(ad.y()) * (std::abs(bd.z() * cd.x()) + std::abs(bd.x() * cd.z())) +
              std::abs(ad.z()) * (std::abs(bd.x() * cd.y()) + std::abs(bd.y() * cd.x()))};
}

// Sign of a determinant when it is exact (beyond kSignTolerance of its bound; rounding is ~1e-15
// of it) and beyond sqrt(bandSquared), else 0.
int signBeyond(const Determinant& det, double bandSquared) {
  const double exactBound = kSignTolerance * det.bound;
  if (det.value * det.value <= std::max(exactBound * exactBound, bandSquared)) return 0;
  return det.value > 0.0 ? 1 : -1;
}

bool mixedSigns(int s0, int s1, int s2) {
  return (s0 > 0 || s1 > 0 || s2 > 0) && (s0 < 0 || s1 < 0 || s2 < 0);
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
  if (!isThin(normal.squaredNorm(), longestEdgeSquared(a, b, c), kThinTolerance) &&
      normal.dot((b - a).cross(p - a)) >= 0.0 && normal.dot((c - b).cross(p - b)) >= 0.0 &&
      normal.dot((a - c).cross(p - c)) >= 0.0) {
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

// A triangle with its normal (b - a) x (c - a) and longest edge, as the contact tests use it.
struct ContactTriangle {
  ContactTriangle(const Vec3& a0, const Vec3& b0, const Vec3& c0)
      : a(a0),
        b(b0),
        c(c0),
        normal((b - a).cross(c - a)),
        normalSquared(normal.squaredNorm()),
        longestSquared(longestEdgeSquared(a, b, c)) {}
  [[nodiscard]] bool degenerate() const {
    return isThin(normalSquared, longestSquared, kDegenerateTolerance);
  }
  Vec3 a, b, c, normal;
  double normalSquared, longestSquared;
};

// Contact distance for shapes whose longest edge is sqrt(longestSquared).
double contactTolerance(double longestSquared) {
  return kContactTolerance * std::sqrt(longestSquared);
}

// Side of x relative to the plane of t: +1 or -1 when x is certainly farther than `tolerance`
// from the plane on that side, else 0.
int sideBeyond(const ContactTriangle& t, const Vec3& x, double tolerance) {
  // The determinant is -|normal| * the height of x above the plane.
  return signBeyond(orientationDeterminant(t.a, t.b, t.c, x),
                    tolerance * tolerance * t.normalSquared);
}

// Side of the line pq relative to the line uv, the sign of det[p-v, q-v, u-v], when it is
// exact and the lines are farther apart than `tolerance` (|det| = |(q - p) x (v - u)| * their
// distance), else 0.
int lineSideBeyond(const Vec3& p, const Vec3& q, const Vec3& u, const Vec3& v, double tolerance) {
  return signBeyond(orientationDeterminant(p, q, u, v),
                    tolerance * tolerance * (q - p).cross(v - u).squaredNorm());
}

enum class Crossing { inside, outside, undecided };

// Where segment pq, whose ends lie farther than `tolerance` on opposite sides of t's plane, crosses
// it: inside t, or outside and farther than tolerance from every edge of t (so pq stays farther
// than that from t), as exact signs show however shallow the crossing; else undecided.
Crossing properCrossing(const Vec3& p, const Vec3& q, const ContactTriangle& t, double tolerance) {
  const int ab = lineSideBeyond(p, q, t.a, t.b, tolerance),
            bc = lineSideBeyond(p, q, t.b, t.c, tolerance),
            ca = lineSideBeyond(p, q, t.c, t.a, tolerance);
  if (ab == 0 || bc == 0 || ca == 0) return Crossing::undecided;
  return ab == bc && bc == ca ? Crossing::inside : Crossing::outside;
}

// Segment pq crosses the plane of t at a point inside t, with the crossing point computed in
// floating point (a point of pq within rounding of the plane, however shallow the crossing).
bool crossingPointInside(const Vec3& p, const Vec3& q, const ContactTriangle& t) {
  const double hp = t.normal.dot(p - t.a), hq = t.normal.dot(q - t.a);
  if (!((hp < 0.0 && hq > 0.0) || (hp > 0.0 && hq < 0.0))) return false;
  const Vec3 x = p + (hp / (hp - hq)) * (q - p);
  return t.normal.dot((t.b - t.a).cross(x - t.a)) >= 0.0 &&
         t.normal.dot((t.c - t.b).cross(x - t.b)) >= 0.0 &&
         t.normal.dot((t.a - t.c).cross(x - t.c)) >= 0.0;
}

double pointTriangleDistanceSquared(const Vec3& x, const ContactTriangle& t) {
  return (closestPointOnTriangle(x, t.a, t.b, t.c) - x).squaredNorm();
}

double pointSegmentDistanceSquared(const Vec3& x, const Vec3& u, const Vec3& v) {
  return (closestPointOnSegment(x, u, v) - x).squaredNorm();
}

// Squared distance from segment uv to the point of segment pq nearest the line uv (clamped to
// pq): the segments' distance when it is attained inside both, else an upper bound. Computed
// through (q - p) x (v - u), whose relative error ~1e-16 / angle only slides that point along
// pq by an amount the angle shrinks back, so the result stays accurate for nearly parallel pairs.
double innerSegmentDistanceSquared(const Vec3& p, const Vec3& q, const Vec3& u, const Vec3& v) {
  const Vec3 pq = q - p, uv = v - u, normal = pq.cross(uv);
  const double normal2 = normal.squaredNorm();
  const double s =
      normal2 > 0.0 ? std::clamp((u - p).cross(uv).dot(normal) / normal2, 0.0, 1.0) : 0.0;
  return pointSegmentDistanceSquared(p + s * pq, u, v);
}

// Segment pq comes within `tolerance` of t. Its distance to t is attained at a crossing of the
// inside, at an end of pq, at a corner of t or between pq and an edge of t; every candidate is a
// pair of actual points, so a true answer is never farther than tolerance plus rounding.
bool segmentWithin(const Vec3& p, const Vec3& q, const ContactTriangle& t, double tolerance) {
  const double tolerance2 = tolerance * tolerance;
  if (crossingPointInside(p, q, t)) return true;
  if (pointTriangleDistanceSquared(p, t) <= tolerance2) return true;
  if (pointTriangleDistanceSquared(q, t) <= tolerance2) return true;
  const std::array<const Vec3*, 3> corners{&t.a, &t.b, &t.c};
  for (int k = 0; k < 3; ++k) {
    const Vec3 &u = *corners[k], &v = *corners[(k + 1) % 3];
    if (innerSegmentDistanceSquared(p, q, u, v) <= tolerance2 ||
        pointSegmentDistanceSquared(u, p, q) <= tolerance2) {
      return true;
    }
  }
  return false;
}

// Segment pq touches the non-degenerate triangle t within `tolerance`: exact signs decide clear
// cases (one side of the plane, or a proper crossing); near contacts are decided by distance.
bool segmentTouches(const Vec3& p, const Vec3& q, const ContactTriangle& t, double tolerance) {
  const int sideP = sideBeyond(t, p, tolerance), sideQ = sideBeyond(t, q, tolerance);
  if (sideP * sideQ > 0) return false;
  if (sideP * sideQ < 0) {
    const Crossing crossing = properCrossing(p, q, t, tolerance);
    if (crossing != Crossing::undecided) return crossing == Crossing::inside;
  }
  return segmentWithin(p, q, t, tolerance);
}

// Triangles s and t come within `tolerance`: the crossing of an edge of one through the other,
// a corner of one near the other, or a pair of edges near each other inside both.
bool trianglesWithin(const ContactTriangle& s, const ContactTriangle& t, double tolerance) {
  const double tolerance2 = tolerance * tolerance;
  const std::array<const Vec3*, 3> sCorners{&s.a, &s.b, &s.c}, tCorners{&t.a, &t.b, &t.c};
  for (int k = 0; k < 3; ++k) {
    if (crossingPointInside(*sCorners[k], *sCorners[(k + 1) % 3], t) ||
        crossingPointInside(*tCorners[k], *tCorners[(k + 1) % 3], s)) {
      return true;
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (pointTriangleDistanceSquared(*sCorners[k], t) <= tolerance2 ||
        pointTriangleDistanceSquared(*tCorners[k], s) <= tolerance2) {
      return true;
    }
  }
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      if (innerSegmentDistanceSquared(*sCorners[k], *sCorners[(k + 1) % 3], *tCorners[l],
                                      *tCorners[(l + 1) % 3]) <= tolerance2) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

bool segmentIntersectsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                               const Vec3& c) {
  const ContactTriangle t(a, b, c);
  if (t.degenerate()) return false;
  return segmentTouches(p, q, t,
                        contactTolerance(std::max((q - p).squaredNorm(), t.longestSquared)));
}

bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                        const Vec3& b1, const Vec3& b2) {
  const ContactTriangle a(a0, a1, a2), b(b0, b1, b2);
  if (a.degenerate() || b.degenerate()) return false;
  const double tolerance = contactTolerance(std::max(a.longestSquared, b.longestSquared));
  const std::array<const Vec3*, 3> aCorners{&a0, &a1, &a2}, bCorners{&b0, &b1, &b2};
  // Separated by a plane: every corner of one farther than the tolerance on one side of the other.
  const auto sidesOf = [tolerance](const std::array<const Vec3*, 3>& corners,
                                   const ContactTriangle& other) {
    return std::array<int, 3>{sideBeyond(other, *corners[0], tolerance),
                              sideBeyond(other, *corners[1], tolerance),
                              sideBeyond(other, *corners[2], tolerance)};
  };
  const auto oneSide = [](const std::array<int, 3>& s) {
    return s[0] * s[1] > 0 && s[1] * s[2] > 0;
  };
  const std::array<int, 3> aSides = sidesOf(aCorners, b);
  if (oneSide(aSides)) return false;
  const std::array<int, 3> bSides = sidesOf(bCorners, a);
  if (oneSide(bSides)) return false;
  // Their distance is that of an edge of one to the other. Exact signs show an edge crossing the
  // other's inside, or keep it farther than the tolerance: beyond it on one side of the plane, or
  // crossing outside; only when some edge is left undecided are distances computed.
  const auto edgeCrossing = [tolerance](const std::array<const Vec3*, 3>& corners,
                                        const std::array<int, 3>& sides,
                                        const ContactTriangle& other, int k) {
    const int next = (k + 1) % 3, ends = sides[k] * sides[next];
    if (ends > 0) return Crossing::outside;  // beyond the tolerance on one side
    if (ends == 0) return Crossing::undecided;
    return properCrossing(*corners[k], *corners[next], other, tolerance);
  };
  bool undecided = false;
  for (int k = 0; k < 3; ++k) {
    const Crossing ofA = edgeCrossing(aCorners, aSides, b, k),
                   ofB = edgeCrossing(bCorners, bSides, a, k);
    if (ofA == Crossing::inside || ofB == Crossing::inside) return true;
    undecided = undecided || ofA == Crossing::undecided || ofB == Crossing::undecided;
  }
  return undecided && trianglesWithin(a, b, tolerance);
}

bool trianglesMeetBesideSharedVertex(const Vec3& s, const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                     const Vec3& q2) {
  const ContactTriangle first(s, p1, q1), second(s, p2, q2);
  if (first.degenerate() || second.degenerate()) return false;
  const double longestSquared = std::max(first.longestSquared, second.longestSquared);
  const double tolerance = contactTolerance(longestSquared);
  // Fast certificate, the usual case between neighbours of a mesh: an edge lies clearly (beyond
  // 1e-6 of the longest edge L) on one side of the other triangle's plane. For a triangle with
  // |normal| >= 1e-4 L^2 that height exceeds the contact tolerance (1e-12 L) and the exactness
  // band of sideBeyond's determinant (1e-12 * bound / |normal|, bound <= 14 L^3 since every corner
  // is within 2 L of x, so at most 1.4e-7 L) by far: segmentTouches would find the same two signs
  // and return false.
  const double margin = 1e-6 * std::sqrt(longestSquared);
  const auto clearlyOneSide = [&](const ContactTriangle& t, const Vec3& p, const Vec3& q) {
    const double length = std::sqrt(t.normalSquared);
    if (length < 1e-4 * longestSquared) return false;
    const double hp = t.normal.dot(p - s), hq = t.normal.dot(q - s), band = margin * length;
    return (hp > band && hq > band) || (hp < -band && hq < -band);
  };
  return (!clearlyOneSide(second, p1, q1) && segmentTouches(p1, q1, second, tolerance)) ||
         (!clearlyOneSide(first, p2, q2) && segmentTouches(p2, q2, first, tolerance));
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

bool TriangleBvh::hasTriangleWithin(const Vec3& query, double radius) const {
  // Node boxes are padded by padding_: a triangle within `radius` (up to the rounding of its
  // closest point) lies in boxes that overlap the ball's box and are nearer than `radius` by about
  // padding_, so no rounding of either test can drop it.
  const double radiusSquared = radius * radius;
  const Vec3 reach = Vec3::Constant(radius);
  const Vec3 ballLo = query - reach, ballHi = query + reach;
  const Vec3 lo = ballLo - Vec3::Constant(padding_);
  const Vec3 hi = ballHi + Vec3::Constant(padding_);
  const auto overlaps = [&](std::uint32_t node) {
    return (nodes_[node].lo.array() <= ballHi.array()).all() &&
           (ballLo.array() <= nodes_[node].hi.array()).all();
  };
  const auto nearness = [&](std::uint32_t node) {
    return boxDistanceSquared(nodes_[node].lo, nodes_[node].hi, query);
  };
  // The leaves that can hold such a triangle, the nearer child first where both can: the answer
  // is the same in any order, and a triangle that close is usually in the nearest leaf.
  std::array<std::uint32_t, kMaxDepth> stack;
  std::size_t size = 0;
  std::uint32_t node = 0;
  if (!overlaps(node)) return false;
  while (true) {
    const Node& n = nodes_[node];
    if (n.count == 0) {
      std::uint32_t nearChild = node + 1, farChild = n.first;
      const bool nearIn = overlaps(nearChild), farIn = overlaps(farChild);
      if (nearIn && farIn) {
        double nearDistance2 = nearness(nearChild), farDistance2 = nearness(farChild);
        if (farDistance2 < nearDistance2) {
          std::swap(nearChild, farChild);
          std::swap(nearDistance2, farDistance2);
        }
        if (nearDistance2 <= radiusSquared) {
          if (farDistance2 <= radiusSquared) stack[size++] = farChild;
          node = nearChild;
          continue;
        }
      } else if (nearIn || farIn) {
        node = nearIn ? nearChild : farChild;
        continue;
      }
    } else {
      for (std::uint32_t slot = n.first; slot < n.first + n.count; ++slot) {
        const Triangle& tri = triangles_[slot];
        const Vec3 &a = vertices_[tri[0]], &b = vertices_[tri[1]], &c = vertices_[tri[2]];
        // A triangle whose box misses the padded box around the ball is farther than `radius` by
        // more than any rounding of the closest point: skipping it changes no answer.
        if ((a.array().max(b.array()).max(c.array()) < lo.array()).any() ||
            (a.array().min(b.array()).min(c.array()) > hi.array()).any()) {
          continue;
        }
        const Vec3 point = closestPointOnTriangle(query, a, b, c);
        if (std::sqrt((point - query).squaredNorm()) <= radius) return true;
      }
    }
    if (size == 0) return false;
    node = stack[--size];
  }
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
        // Which side of the planes through the ray origin and each edge the ray passes (two
        // opposite sides already mean a miss).
        const int sideAb = toleranceSignSquared(direction.dot(a.cross(b)), a2 * b2);
        const int sideBc = toleranceSignSquared(direction.dot(bc), b2 * c2);
        if (sideAb * sideBc < 0) continue;
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

bool TriangleBvh::containsInClosedMesh(const Vec3& p) const {
  for (const Vec3& direction : insideTestDirections()) {
    if (const std::optional<int> winding = rayWinding(p, direction)) return *winding != 0;
  }
  return true;
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

}  // namespace kaboum::geometry
