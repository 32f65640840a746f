#include "kaboum/geometry/bounding_mesh.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounded_contraction.hpp"
#include "kaboum/geometry/separation_certificate.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/geometry/triangle_grid.hpp"

namespace kaboum {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// A candidate contraction of edge (a, b) to `position`. It is current while the versions of both
// vertices match; their fan versions tell whether a fresher entry for the edge has been queued
// since. Versions only grow (by at most one per contraction), so each pair is kept as its sum,
// which is unchanged exactly when both are: 48 bytes per heap entry.
struct Candidate {
  double cost;
  Vec3 position;
  std::uint32_t a, b;
  std::uint32_t versions, fanVersions;
  bool operator>(const Candidate& o) const { return cost > o.cost; }
};

class BoundingMeshSimplifier {
 public:
  BoundingMeshSimplifier(const TriangleMesh& input, const BoundingMeshOptions& options)
      : options_(options), positions_(input.vertices), triangles_(input.triangles) {}

  BoundingMeshResult run();

 private:
  void buildAdjacency();
  void classifyEdges(std::vector<std::pair<std::uint32_t, std::uint32_t>>& interiorEdges);
  void lockNonManifoldVertices();
  void updatePlane(std::uint32_t t);
  void initQuadrics();

  template <class F>
  void forEachTriangle(std::uint32_t v, F&& f);
  void gatherFan(std::uint32_t v, std::vector<std::uint32_t>& fan);
  void gatherNeighbours(std::uint32_t v, std::vector<std::uint32_t>& out);
  std::uint32_t versionsOf(std::uint32_t a, std::uint32_t b) const {
    return version_[a] + version_[b];
  }
  std::uint32_t fanVersionsOf(std::uint32_t a, std::uint32_t b) const {
    return fanVersion_[a] + fanVersion_[b];
  }
  bool contains(std::uint32_t t, std::uint32_t v) const {
    return triangles_[t][0] == v || triangles_[t][1] == v || triangles_[t][2] == v;
  }

  bool evaluate(std::uint32_t a, std::uint32_t b, Candidate& out);
  bool evaluateGathered(std::uint32_t a, std::uint32_t b, Candidate& out);
  void addHalfSpace(std::uint32_t t, const Vec3& origin);
  void queue(std::uint32_t a, std::uint32_t b);
  void queueGathered(std::uint32_t a, std::uint32_t b);
  enum class Outcome { Done, Stale, Topology, Geometry, Crossing };
  bool stillAboveFanPlanes(const Candidate& c) const;
  bool newFanCrossesMesh(const Candidate& c);
  void buildGrid(double cellSize);
  Box3 boxOf(std::uint32_t t) const {
    return triangleBox(positions_[triangles_[t][0]], positions_[triangles_[t][1]],
                       positions_[triangles_[t][2]]);
  }
  Outcome contract(const Candidate& c);
  bool revisitParked();
  void purgeHeap();
  TriangleMesh compact() const;

  BoundingMeshOptions options_;
  std::vector<Vec3> positions_;
  std::vector<Triangle> triangles_;
  std::vector<Vec3> normals_;        // unit normal per triangle (zero when degenerate)
  std::vector<double> offsets_;      // normal · point on the triangle
  std::vector<float> crossLengths_;  // |(p1 - p0) × (p2 - p0)|, for the guard's certificate
  std::vector<std::uint8_t> triangleAlive_;
  std::vector<std::uint32_t> firstCorner_, nextCorner_;  // per-vertex linked list of corners 3t+k
  std::vector<std::uint32_t> triangleCount_;
  std::vector<Quadric> quadrics_;
  std::vector<std::uint8_t> vertexAlive_, vertexLocked_;
  std::vector<std::uint32_t> version_, fanVersion_;
  std::vector<std::uint32_t> markA_, markB_;
  std::vector<std::uint32_t> triangleMark_;  // stamps for excluding/deduplicating triangles
  std::vector<Box3> boxes_;                  // each live triangle's box as registered in grid_
  std::unique_ptr<TriangleGrid> grid_;
  std::size_t verticesAtGridBuild_ = 0;
  std::uint32_t stamp_ = 0;
  std::size_t aliveVertices_ = 0;
  double tolerance_ = 0.0;

  std::vector<Candidate> heap_;    // binary min-heap on cost (std::push_heap with std::greater)
  std::vector<Candidate> parked_;  // rejected candidates, retried once their neighbourhood changes
  // Scratch, reused by every call so the main loop does not allocate once warmed up.
  std::vector<std::uint32_t> fanA_, fanB_, neighbours_;
  struct NewTriangle {  // a triangle of the fan a contraction would create
    Triangle ids;
    std::array<Vec3, 3> corners;
    Vec3 unitNormal;
    double crossLength, sizeSquared;
    Box3 box;
  };
  std::vector<NewTriangle> newTriangles_;
  std::vector<PlanedTriangle> newPlaned_;  // views of newTriangles_ for certainlyApart
  std::vector<std::uint32_t> nearby_;
  std::vector<HalfSpace> halfSpaces_;
  BoundingMeshStats stats_;
};

template <class F>
void BoundingMeshSimplifier::forEachTriangle(std::uint32_t v, F&& f) {
  // Walks v's corner list, unlinking corners of dead triangles on the way.
  std::uint32_t previous = kNone;
  for (std::uint32_t c = firstCorner_[v]; c != kNone;) {
    const std::uint32_t next = nextCorner_[c];
    if (!triangleAlive_[c / 3]) {
      (previous == kNone ? firstCorner_[v] : nextCorner_[previous]) = next;
    } else {
      f(c / 3);
      previous = c;
    }
    c = next;
  }
}

void BoundingMeshSimplifier::gatherFan(std::uint32_t v, std::vector<std::uint32_t>& fan) {
  fan.clear();
  forEachTriangle(v, [&](std::uint32_t t) { fan.push_back(t); });
}

void BoundingMeshSimplifier::gatherNeighbours(std::uint32_t v, std::vector<std::uint32_t>& out) {
  out.clear();
  ++stamp_;
  forEachTriangle(v, [&](std::uint32_t t) {
    for (std::uint32_t w : triangles_[t]) {
      if (w != v && markA_[w] != stamp_) {
        markA_[w] = stamp_;
        out.push_back(w);
      }
    }
  });
}

void BoundingMeshSimplifier::buildAdjacency() {
  const std::size_t n = positions_.size();
  firstCorner_.assign(n, kNone);
  nextCorner_.assign(triangles_.size() * 3, kNone);
  triangleCount_.assign(n, 0);
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = triangles_[t][k];
      nextCorner_[3 * t + k] = firstCorner_[v];
      firstCorner_[v] = 3 * t + k;
      ++triangleCount_[v];
    }
  }
}

void BoundingMeshSimplifier::classifyEdges(
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& interiorEdges) {
  struct HalfEdge {
    std::uint64_t key;  // min vertex << 32 | max vertex
    bool forward;       // stored direction is min → max
  };
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(triangles_.size() * 3);
  for (const Triangle& t : triangles_) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = t[k], w = t[(k + 1) % 3];
      const std::uint64_t lo = std::min(u, w), hi = std::max(u, w);
      halfEdges.push_back({lo << 32 | hi, u < w});
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end(),
            [](const HalfEdge& l, const HalfEdge& r) { return l.key < r.key; });
  for (std::size_t i = 0; i < halfEdges.size();) {
    std::size_t j = i;
    int forward = 0;
    while (j < halfEdges.size() && halfEdges[j].key == halfEdges[i].key) {
      forward += halfEdges[j].forward ? 1 : 0;
      ++j;
    }
    const auto lo = static_cast<std::uint32_t>(halfEdges[i].key >> 32);
    const auto hi = static_cast<std::uint32_t>(halfEdges[i].key & 0xffffffffu);
    const std::size_t count = j - i;
    if (count == 2 && forward != 1) {
      throw InputError("triangles are not consistently oriented (edge between vertices " +
                       std::to_string(lo) + " and " + std::to_string(hi) +
                       " is traversed twice in the same direction)");
    }
    if (count == 2) {
      interiorEdges.emplace_back(lo, hi);
    } else {  // border (1) or non-manifold (> 2): keep it exactly as it is
      vertexLocked_[lo] = vertexLocked_[hi] = 1;
    }
    i = j;
  }
}

void BoundingMeshSimplifier::lockNonManifoldVertices() {
  // An interior vertex is manifold when its link edges (a → b for each triangle (v, a, b)) form a
  // single cycle; otherwise (e.g. two cones touching at a tip) it must not move.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> link;
  for (std::uint32_t v = 0; v < positions_.size(); ++v) {
    if (vertexLocked_[v] || triangleCount_[v] == 0) continue;
    link.clear();
    forEachTriangle(v, [&](std::uint32_t t) {
      const Triangle& tri = triangles_[t];
      const int k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
      link.emplace_back(tri[(k + 1) % 3], tri[(k + 2) % 3]);
    });
    std::size_t steps = 0;
    std::uint32_t at = link[0].second;
    while (at != link[0].first && steps < link.size()) {
      const auto next =
          std::find_if(link.begin(), link.end(), [&](const auto& e) { return e.first == at; });
      if (next == link.end()) break;
      at = next->second;
      ++steps;
    }
    if (at != link[0].first || steps + 1 != link.size()) vertexLocked_[v] = 1;
  }
}

void BoundingMeshSimplifier::updatePlane(std::uint32_t t) {
  const Vec3& p0 = positions_[triangles_[t][0]];
  const Vec3& p1 = positions_[triangles_[t][1]];
  const Vec3& p2 = positions_[triangles_[t][2]];
  const Vec3 cross = (p1 - p0).cross(p2 - p0);
  const double longest =
      std::max({(p1 - p0).squaredNorm(), (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm()});
  const double length = cross.norm();
  crossLengths_[t] =
      static_cast<float>(std::min<double>(length, std::numeric_limits<float>::max()));
  if (length <= 1e-12 * longest || length == 0.0) {
    normals_[t] = Vec3::Zero();
    offsets_[t] = 0.0;
    return;
  }
  normals_[t] = cross / length;
  offsets_[t] = normals_[t].dot((p0 + p1 + p2) / 3.0);
}

void BoundingMeshSimplifier::initQuadrics() {
  quadrics_.assign(positions_.size(), Quadric{});
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    const Triangle& tri = triangles_[t];
    const Vec3 centroid = (positions_[tri[0]] + positions_[tri[1]] + positions_[tri[2]]) / 3.0;
    Quadric q;
    if (options_.cost == ContractionCost::Triangles) {
      q = Quadric::point(centroid);
    } else if (normals_[t] != Vec3::Zero()) {
      q = Quadric::plane(normals_[t], centroid);
    } else {
      continue;
    }
    for (std::uint32_t v : tri) quadrics_[v] += q;
  }
}

void BoundingMeshSimplifier::addHalfSpace(std::uint32_t t, const Vec3& origin) {
  const Vec3& n = normals_[t];
  if (n.x() == 0.0 && n.y() == 0.0 && n.z() == 0.0) return;  // degenerate: no plane to stay above
  const double sign = options_.side == BoundSide::Outer ? 1.0 : -1.0;
  halfSpaces_.push_back({sign * n, sign * (offsets_[t] - n.dot(origin))});
}

bool BoundingMeshSimplifier::evaluate(std::uint32_t a, std::uint32_t b, Candidate& out) {
  gatherFan(a, fanA_);
  gatherFan(b, fanB_);
  return evaluateGathered(a, b, out);
}

// As evaluate, with fanA_ and fanB_ already holding the fans of a and b.
bool BoundingMeshSimplifier::evaluateGathered(std::uint32_t a, std::uint32_t b, Candidate& out) {
  // Work in coordinates centred on the edge so large absolute coordinates lose no precision.
  const Vec3 origin = 0.5 * (positions_[a] + positions_[b]);
  halfSpaces_.clear();
  for (std::uint32_t t : fanA_) addHalfSpace(t, origin);
  for (std::uint32_t t : fanB_) {
    if (!contains(t, a)) addHalfSpace(t, origin);
  }
  const Quadric q = (quadrics_[a] + quadrics_[b]).centredAt(origin);
  // A tiny pull towards the edge midpoint makes the problem strictly convex, so flat and
  // cylindrical neighbourhoods (singular quadrics) have a unique, central minimizer.
  Quadric regularized = q;
  regularized.a += (1e-9 * q.a.trace() + 1e-300) * Eigen::Matrix3d::Identity();
  const ContractionPoint point = solveContraction(regularized, halfSpaces_, tolerance_);
  if (!point.feasible) return false;
  out = {std::max(q(point.position), 0.0),
         origin + point.position,
         a,
         b,
         versionsOf(a, b),
         fanVersionsOf(a, b)};
  return true;
}

void BoundingMeshSimplifier::queue(std::uint32_t a, std::uint32_t b) {
  gatherFan(a, fanA_);
  gatherFan(b, fanB_);
  queueGathered(a, b);
}

void BoundingMeshSimplifier::queueGathered(std::uint32_t a, std::uint32_t b) {
  Candidate c;
  if (evaluateGathered(a, b, c)) {
    heap_.push_back(c);
    std::push_heap(heap_.begin(), heap_.end(), std::greater<>{});
  } else {
    ++stats_.rejectedInfeasible;
  }
}

BoundingMeshSimplifier::Outcome BoundingMeshSimplifier::contract(const Candidate& c) {
  const std::uint32_t a = c.a, b = c.b;
  gatherFan(a, fanA_);
  gatherFan(b, fanB_);
  const bool changed = versionsOf(a, b) != c.versions;
  if (changed && !stillAboveFanPlanes(c)) return Outcome::Stale;

  // Topology: exactly two triangles on the edge, and the link condition (the only common
  // neighbours of a and b are the two vertices opposite the edge), or the mesh stops being
  // manifold.
  std::uint32_t opposite[2] = {kNone, kNone};
  int shared = 0;
  for (std::uint32_t t : fanA_) {
    if (!contains(t, b)) continue;
    if (shared == 2) return Outcome::Topology;
    for (std::uint32_t w : triangles_[t]) {
      if (w != a && w != b) opposite[shared] = w;
    }
    ++shared;
  }
  if (shared != 2) return Outcome::Topology;
  for (std::uint32_t w : opposite) {
    if (triangleCount_[w] <= 3) return Outcome::Topology;  // would leave a valence-2 vertex
  }
  ++stamp_;
  for (std::uint32_t t : fanA_) {
    for (std::uint32_t w : triangles_[t]) markA_[w] = stamp_;
  }
  int common = 0;
  for (std::uint32_t t : fanB_) {
    for (std::uint32_t w : triangles_[t]) {
      if (w == a || w == b || markB_[w] == stamp_) continue;
      markB_[w] = stamp_;
      if (markA_[w] == stamp_) ++common;
    }
  }
  if (common != 2) return Outcome::Topology;

  // Geometry: no new triangle may be degenerate or turn over relative to the one it replaces.
  const auto keepsShape = [&](std::uint32_t t, std::uint32_t moved) {
    std::array<Vec3, 3> p;
    for (int k = 0; k < 3; ++k) {
      p[k] = triangles_[t][k] == moved ? c.position : positions_[triangles_[t][k]];
    }
    const Vec3 cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double longest = std::max(
        {(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm()});
    const double length = cross.norm();
    if (!(length > 1e-10 * longest)) return false;
    return normals_[t] == Vec3::Zero() || cross.dot(normals_[t]) > 1e-3 * length;
  };
  for (std::uint32_t t : fanA_) {
    if (!contains(t, b) && !keepsShape(t, a)) return Outcome::Geometry;
  }
  for (std::uint32_t t : fanB_) {
    if (!contains(t, a) && !keepsShape(t, b)) return Outcome::Geometry;
  }

  if (newFanCrossesMesh(c)) return Outcome::Crossing;

  // Execute: b merges into a at the new position.
  for (std::uint32_t t : fanA_) {
    if (contains(t, b)) {
      grid_->remove(t, boxes_[t]);
      triangleAlive_[t] = 0;
      for (std::uint32_t w : triangles_[t]) --triangleCount_[w];
    }
  }
  std::uint32_t tail = kNone;
  for (std::uint32_t corner = firstCorner_[b]; corner != kNone; corner = nextCorner_[corner]) {
    triangles_[corner / 3][corner % 3] = a;
    tail = corner;
  }
  if (tail != kNone) {
    nextCorner_[tail] = firstCorner_[a];
    firstCorner_[a] = firstCorner_[b];
    firstCorner_[b] = kNone;
  }
  triangleCount_[a] += triangleCount_[b];
  triangleCount_[b] = 0;
  const Vec3 reference = c.position;
  const double length = options_.mergeLength;
  quadrics_[a] = mergeQuadrics(quadrics_[a], quadrics_[b], options_.merge, reference, length);
  positions_[a] = c.position;
  vertexAlive_[b] = 0;
  --aliveVertices_;
  fanA_.clear();
  forEachTriangle(a, [&](std::uint32_t t) {
    updatePlane(t);
    const Box3 box = boxOf(t);
    grid_->move(t, boxes_[t], box);
    boxes_[t] = box;
    fanA_.push_back(t);
  });

  ++version_[a];
  ++fanVersion_[a];
  gatherNeighbours(a, neighbours_);
  for (std::uint32_t w : neighbours_) ++version_[w];
  // Re-queue the edges around the new vertex; its fan (in fanA_) is gathered once for all of them.
  for (std::uint32_t w : neighbours_) {
    if (vertexLocked_[w]) continue;
    gatherFan(w, fanB_);
    queueGathered(a, w);
  }
  return Outcome::Done;
}

// A candidate whose neighbourhood changed keeps its cost (the quadrics of a and b did not change)
// and stays valid as long as its point is still on the kept side of every current plane around the
// edge; only then does it need solving again. This spares most re-evaluations.
bool BoundingMeshSimplifier::stillAboveFanPlanes(const Candidate& c) const {
  const double sign = options_.side == BoundSide::Outer ? 1.0 : -1.0;
  const auto above = [&](std::uint32_t t) {
    return normals_[t] == Vec3::Zero() ||
           sign * (normals_[t].dot(c.position) - offsets_[t]) >= -tolerance_;
  };
  return std::all_of(fanA_.begin(), fanA_.end(), above) &&
         std::all_of(fanB_.begin(), fanB_.end(), above);
}

// The new fan may not cross any other triangle of the mesh nor itself: this keeps outer results
// free of folds (which parity-based inside tests misread) and inner results inside the original.
// Each pair whose boxes overlap is first given the cheap certificate certainlyApart (cached unit
// normals and twice-areas); only the pairs it cannot clear reach the exact predicate, so the
// verdict is the predicate's.
bool BoundingMeshSimplifier::newFanCrossesMesh(const Candidate& c) {
  const std::uint32_t a = c.a, b = c.b;
  ++stamp_;
  const std::uint32_t exclude = stamp_;
  newTriangles_.clear();
  Box3 fanBox{Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()),
              Eigen::Vector3f::Constant(-std::numeric_limits<float>::infinity())};
  const auto addNew = [&](std::uint32_t t) {
    triangleMark_[t] = exclude;
    if (contains(t, a) && contains(t, b)) return;
    NewTriangle& n = newTriangles_.emplace_back();
    n.ids = triangles_[t];
    for (int k = 0; k < 3; ++k) {
      if (n.ids[k] == b) n.ids[k] = a;
      n.corners[k] = n.ids[k] == a ? c.position : positions_[n.ids[k]];
    }
    const Vec3 cross = (n.corners[1] - n.corners[0]).cross(n.corners[2] - n.corners[0]);
    n.crossLength = cross.norm();  // > 0: keepsShape refused degenerate new triangles
    n.unitNormal = cross / n.crossLength;
    n.box = triangleBox(n.corners[0], n.corners[1], n.corners[2]);
    n.sizeSquared = n.box.diagonalSquared();
    fanBox = {fanBox.lo.cwiseMin(n.box.lo), fanBox.hi.cwiseMax(n.box.hi)};
  };
  for (std::uint32_t t : fanA_) addNew(t);
  for (std::uint32_t t : fanB_) addNew(t);
  newPlaned_.clear();
  for (const NewTriangle& n : newTriangles_) {
    newPlaned_.push_back({{&n.corners[0], &n.corners[1], &n.corners[2]},
                          n.ids,
                          n.unitNormal,
                          n.crossLength,
                          n.sizeSquared});
  }

  // One grid query for the whole fan; then each nearby triangle is tested against the new
  // triangles whose boxes it overlaps.
  nearby_.clear();
  grid_->forEachNear(fanBox, [&](std::uint32_t u) {
    if (triangleMark_[u] == exclude) return;
    triangleMark_[u] = exclude;  // seen
    if (triangleAlive_[u] && fanBox.overlaps(boxes_[u])) nearby_.push_back(u);
  });
  for (std::size_t i = 0; i < newTriangles_.size(); ++i) {
    for (std::size_t j = i + 1; j < newTriangles_.size(); ++j) {
      if (!certainlyApart(newPlaned_[i], newPlaned_[j]) &&
          meshTrianglesIntersect(newTriangles_[i].corners, newTriangles_[i].ids,
                                 newTriangles_[j].corners, newTriangles_[j].ids)) {
        return true;
      }
    }
  }
  for (std::uint32_t u : nearby_) {
    const Triangle& ids = triangles_[u];
    const PlanedTriangle old{{&positions_[ids[0]], &positions_[ids[1]], &positions_[ids[2]]},
                             ids,
                             normals_[u],
                             crossLengths_[u],
                             boxes_[u].diagonalSquared()};
    for (std::size_t i = 0; i < newTriangles_.size(); ++i) {
      const NewTriangle& n = newTriangles_[i];
      if (!n.box.overlaps(boxes_[u]) || certainlyApart(newPlaned_[i], old)) continue;
      const std::array<Vec3, 3> corners{positions_[ids[0]], positions_[ids[1]], positions_[ids[2]]};
      if (meshTrianglesIntersect(n.corners, n.ids, corners, ids)) return true;
    }
  }
  return false;
}

void BoundingMeshSimplifier::buildGrid(double cellSize) {
  grid_ = std::make_unique<TriangleGrid>(cellSize, triangles_.size());
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    if (!triangleAlive_[t]) continue;
    boxes_[t] = boxOf(t);
    grid_->insert(t, boxes_[t]);
  }
  verticesAtGridBuild_ = aliveVertices_;
}

// Drops candidates of dead vertices and superseded ones, which otherwise accumulate (every
// contraction queues fresh candidates for the new vertex's edges) and dominate peak memory.
void BoundingMeshSimplifier::purgeHeap() {
  std::erase_if(heap_, [&](const Candidate& c) {
    return !vertexAlive_[c.a] || !vertexAlive_[c.b] || fanVersionsOf(c.a, c.b) != c.fanVersions;
  });
  std::make_heap(heap_.begin(), heap_.end(), std::greater<>{});
}

bool BoundingMeshSimplifier::revisitParked() {
  bool any = false;
  std::size_t kept = 0;
  for (const Candidate& c : parked_) {
    if (!vertexAlive_[c.a] || !vertexAlive_[c.b]) continue;
    if (versionsOf(c.a, c.b) == c.versions) {
      parked_[kept++] = c;  // nothing changed around it: still invalid
      continue;
    }
    queue(c.a, c.b);
    any = true;
  }
  parked_.resize(kept);
  return any;
}

TriangleMesh BoundingMeshSimplifier::compact() const {
  TriangleMesh out;
  std::vector<std::uint32_t> remap(positions_.size(), kNone);
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    if (!triangleAlive_[t]) continue;
    Triangle tri = triangles_[t];
    for (std::uint32_t& v : tri) {
      if (remap[v] == kNone) {
        remap[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(positions_[v]);
      }
      v = remap[v];
    }
    out.triangles.push_back(tri);
  }
  return out;
}

BoundingMeshResult BoundingMeshSimplifier::run() {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = positions_.size();
  vertexLocked_.assign(n, 0);
  vertexAlive_.assign(n, 1);
  version_.assign(n, 0);
  fanVersion_.assign(n, 0);
  markA_.assign(n, 0);
  markB_.assign(n, 0);
  triangleAlive_.assign(triangles_.size(), 1);
  triangleMark_.assign(triangles_.size(), 0);
  boxes_.resize(triangles_.size());
  normals_.resize(triangles_.size());
  offsets_.resize(triangles_.size());
  crossLengths_.resize(triangles_.size());

  buildAdjacency();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> interiorEdges;
  classifyEdges(interiorEdges);
  lockNonManifoldVertices();
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) updatePlane(t);
  initQuadrics();

  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (triangleCount_[v] == 0) {
      vertexAlive_[v] = 0;
      continue;
    }
    ++aliveVertices_;
    lo = lo.cwiseMin(positions_[v]);
    hi = hi.cwiseMax(positions_[v]);
    stats_.lockedVertices += vertexLocked_[v];
  }
  const double diagonal = aliveVertices_ > 0 ? (hi - lo).norm() : 0.0;
  tolerance_ = 1e-12 * diagonal;
  if (options_.mergeLength <= 0.0) options_.mergeLength = 0.01 * diagonal;
  stats_.inputVertices = aliveVertices_;
  double edgeLengthSum = 0.0;
  for (const Triangle& t : triangles_) {
    edgeLengthSum += (positions_[t[0]] - positions_[t[1]]).norm();
  }
  buildGrid(
      std::max(2.0 * edgeLengthSum / std::max<double>(1.0, static_cast<double>(triangles_.size())),
               1e-9 * diagonal + 1e-300));

  std::vector<Candidate> initial;
  initial.reserve(interiorEdges.size());
  for (const auto& [a, b] : interiorEdges) {
    Candidate c;
    if (vertexLocked_[a] || vertexLocked_[b]) continue;
    if (evaluate(a, b, c)) {
      initial.push_back(c);
    } else {
      ++stats_.rejectedInfeasible;
    }
  }
  heap_ = std::move(initial);
  std::make_heap(heap_.begin(), heap_.end(), std::greater<>{});

  const std::size_t target = options_.targetVertices;
  const double maxCost = options_.maxError * options_.maxError;
  const std::size_t toRemove = aliveVertices_ > target ? aliveVertices_ - target : 0;
  double worstCost = 0.0;
  while (aliveVertices_ > target) {
    if (heap_.empty() && !revisitParked()) break;
    if (heap_.empty()) continue;
    if (heap_.size() > 12 * aliveVertices_) purgeHeap();
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>{});
    const Candidate c = heap_.back();
    heap_.pop_back();
    if (!vertexAlive_[c.a] || !vertexAlive_[c.b]) continue;
    if (fanVersionsOf(c.a, c.b) != c.fanVersions) continue;  // superseded
    if (c.cost > maxCost) {
      parked_.push_back(c);
      continue;
    }
    if (aliveVertices_ * 2 < verticesAtGridBuild_) {
      buildGrid(grid_->cellSize() * std::sqrt(2.0));  // triangles grew: coarser cells
    }
    switch (contract(c)) {
      case Outcome::Done:
        ++stats_.contractions;
        worstCost = std::max(worstCost, c.cost);
        if (options_.progress && stats_.contractions % 8192 == 0 && toRemove > 0) {
          options_.progress(static_cast<double>(stats_.contractions) /
                            static_cast<double>(toRemove));
        }
        break;
      case Outcome::Stale:
        queueGathered(c.a, c.b);  // contract() left the fans of a and b in fanA_ and fanB_
        break;
      case Outcome::Topology:
        ++stats_.rejectedTopology;
        parked_.push_back(c);
        break;
      case Outcome::Geometry:
        ++stats_.rejectedGeometry;
        parked_.push_back(c);
        break;
      case Outcome::Crossing:
        ++stats_.rejectedCrossing;
        parked_.push_back(c);
        break;
    }
  }

  BoundingMeshResult result;
  result.mesh = compact();
  stats_.outputVertices = result.mesh.vertices.size();
  stats_.quadricError = std::sqrt(worstCost);
  if (aliveVertices_ <= target) {
    stats_.stopReason = "vertex target reached";
  } else if (std::isfinite(options_.maxError)) {
    stats_.stopReason = "no contraction left within the error limit";
  } else {
    stats_.stopReason = "no contraction left that keeps the mesh valid and bounding";
  }
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options_.progress) options_.progress(1.0);
  result.stats = stats_;
  return result;
}

}  // namespace

BoundingMeshResult simplifyBounding(const TriangleMesh& input, const BoundingMeshOptions& options) {
  return BoundingMeshSimplifier(input, options).run();
}

BoundingMeshResult simplifyBoundingWithin(const TriangleMesh& input, BoundingMeshOptions options,
                                          double epsilon, std::size_t samples,
                                          HausdorffReport& measured, int maxRuns) {
  int runs = 0;
  const HausdorffMeter meter(input, samples, 1);
  const auto attempt = [&](double scale) {
    ++runs;
    options.maxError = scale * epsilon;
    return simplifyBounding(input, options);
  };
  BoundingMeshResult best;
  bool haveBest = false;
  double fits = 0.0, fails = 0.0;  // largest scale known to fit, smallest known to fail (0: none)
  double scale = 1.0;
  while (runs < maxRuns) {
    BoundingMeshResult result = attempt(scale);
    const std::optional<HausdorffReport> report = meter.measureWithin(result.mesh, epsilon);
    if (report) {
      fits = scale;
      best = std::move(result);
      measured = *report;
      haveBest = true;
      if (best.stats.stopReason == "vertex target reached") break;  // cannot go further
    } else {
      fails = scale;
    }
    if (fails == 0.0) {
      scale *= 2.0;  // nothing failed yet: widen
    } else if (fits == 0.0) {
      scale *= 0.5;  // nothing fitted yet: narrow
    } else {
      if (fails / fits < 1.1) break;
      scale = std::sqrt(fits * fails);
    }
  }
  if (!haveBest) {  // nothing fitted: no contraction at all
    best = attempt(0.0);
    measured = meter.measure(best.mesh);
  }
  if (best.stats.stopReason != "vertex target reached") {
    best.stats.stopReason = "largest simplification found within the distance limit";
  }
  best.stats.runs = runs;
  return best;
}

}  // namespace kaboum
