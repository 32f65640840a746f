#include "kaboum/geometry/bounding_mesh.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounded_contraction.hpp"
#include "kaboum/geometry/bounding_polish.hpp"
#include "kaboum/geometry/indexed_heap.hpp"
#include "kaboum/geometry/separation_certificate.hpp"
#include "kaboum/geometry/star_directions.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/geometry/triangle_grid.hpp"

namespace kaboum::geometry {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// Vertices of at least this valence are hubs: their stars leave the spatial hash for an angular
// index (see newFanCrossesMesh). Real robot meshes have valences of at most 40.
constexpr std::uint32_t kHubValence = 64;
// A star triangle is left out of a guard query only when the directions of the two triangles from
// the hub are more than this apart (chord on the unit sphere), and every height involved is at
// least kHubHeightRatio of the longest edge involved: then the pair stays farther than
// (2/π)·kHubMargin·kHubHeightRatio > 1e-6 of that edge apart, the separation certificate's margin.
constexpr double kHubMargin = 2e-4;
constexpr double kHubHeightRatio = 1e-2;
// A direction box spanning more cells than this per axis is not indexed (its triangle is enumerated
// with the whole star instead).
constexpr double kHubMaxCellSpan = 16.0;
// The coarse index of a hub, which prunes query pieces far from its star's directions, has cells
// this many times larger.
constexpr double kHubCoarse = 16.0;

// Where an edge stands in the greedy loop. A queued edge's key is its exact cost when Solved, and
// otherwise a lower bound of its cost, see run().
enum class EdgeState : std::uint8_t {
  Off,         // not a candidate: an endpoint is locked, or the edge was contracted away
  Lower,       // queued by a cheap lower bound; tightened (Bounded) when it reaches the top
  Bounded,     // queued by a tighter lower bound; solved when it reaches the top
  Solved,      // queued by its exact cost; edgePositions_ holds its contraction point
  Infeasible,  // queued last (key +∞): no point satisfies the current planes
  Parked,      // rejected; retried when the queue runs empty if its neighbourhood changed
};

// The contraction of edge (a, b): b merges into a, which moves to `position`.
struct Contraction {
  std::uint32_t a, b;
  Vec3 position;
};

// An edge's quadric in coordinates centred on the edge, with its unconstrained minimizer.
struct EdgeProblem {
  Vec3 origin;
  Quadric quadric;  // regularized, positive definite
  std::optional<Vec3> start;
  double minimum;         // the quadric at `start` (0 without one)
  double lowerBound;      // of the cost: max(minimum, 0)
  double curvatureFloor;  // the regularization: the quadric's smallest eigenvalue is at least this
};

// The edge's cost at x, computed as minimum + (x - x₀)ᵀA(x - x₀) for the unconstrained minimizer
// x₀: never below the lower bound, even in floating point.
double costAt(const EdgeProblem& p, const Vec3& x) {
  if (!p.start) return std::max(p.quadric(x), 0.0);
  const Vec3 step = x - *p.start;
  return std::max(p.minimum + std::max(step.dot(p.quadric.a * step), 0.0), 0.0);
}

class BoundingMeshSimplifier {
 public:
  BoundingMeshSimplifier(const TriangleMesh& input, const BoundingMeshOptions& options)
      : options_(options), positions_(input.vertices), triangles_(input.triangles) {}

  // Algorithm 2 up to options.maxError: start(), advance(maxError), result().
  BoundingMeshResult run();
  // Builds the mesh structures and queues every edge; then advance() contracts.
  void start();
  // Contracts edges, cheapest first, while the cheapest exact cost is within maxError (a distance)
  // and the vertex target is not reached. Advancing again with a larger limit goes on from here:
  // the edges the last limit stopped are queued again.
  void advance(double maxError);
  // The mesh as it is now, and the statistics since start().
  [[nodiscard]] BoundingMeshResult result() const;
  // Where later advance() calls report their progress (options.progress at first).
  void reportProgressTo(std::function<void(double)> progress) {
    options_.progress = std::move(progress);
  }

 private:
  void buildAdjacency();
  void classifyEdges(std::vector<std::uint32_t>& interiorEdges);
  void lockNonManifoldVertices();
  void updatePlane(std::uint32_t t);
  void initQuadrics();

  template <class F>
  void forEachTriangle(std::uint32_t v, F&& f);
  void gatherFan(std::uint32_t v, std::vector<std::uint32_t>& fan);
  void gatherNeighbours(std::uint32_t v, std::vector<std::uint32_t>& out);
  // Versions only grow, so the sum is unchanged exactly when both are.
  std::uint32_t versionsOf(std::uint32_t e) const {
    return version_[edgeEnds_[e][0]] + version_[edgeEnds_[e][1]];
  }
  bool contains(std::uint32_t t, std::uint32_t v) const {
    return triangles_[t][0] == v || triangles_[t][1] == v || triangles_[t][2] == v;
  }

  EdgeProblem problemOf(std::uint32_t e) const;
  void addHalfSpace(std::uint32_t t, const Vec3& origin);
  void queueEdge(std::uint32_t e);
  void solveEdge(std::uint32_t e);
  bool tightenBound(std::uint32_t e);
  void invalidateEdge(std::uint32_t e);
  double boundAfterChange(std::uint32_t e, bool& fromLastCost) const;
  void park(std::uint32_t e);
  enum class Outcome { Done, Topology, Geometry, Crossing };
  bool newFanCrossesMesh(const Contraction& c);
  void buildGrid(double cellSize);
  struct Hub;
  bool hasHubCorner(std::uint32_t t) const {
    return hubOf_[triangles_[t][0]] != kNone || hubOf_[triangles_[t][1]] != kNone ||
           hubOf_[triangles_[t][2]] != kNone;
  }
  void acquireHub(std::uint32_t v);
  std::optional<Box3> starDirectionBox(const Hub& hub, std::uint32_t t) const;
  void indexAtHubs(std::uint32_t t);
  void unindexAtHubs(std::uint32_t t);
  void placeTriangle(std::uint32_t t, const Box3& box);
  void invalidateRaised(Hub& hub);
  void gatherNearHubs(const Box3& fanBox, std::uint32_t a, std::uint32_t b, std::uint32_t seen);
  Box3 boxOf(std::uint32_t t) const {
    return triangleBox(positions_[triangles_[t][0]], positions_[triangles_[t][1]],
                       positions_[triangles_[t][2]]);
  }
  Outcome contract(std::uint32_t e);
  void retireMergedEdges(std::uint32_t a, std::uint32_t b);
  void requeueAround(std::uint32_t a);
  bool revisitParked();
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
  std::vector<std::uint32_t> version_;  // grows whenever the vertex's neighbourhood changes
  std::vector<std::uint32_t> markA_, markB_;
  std::vector<std::uint32_t> triangleMark_;  // stamps for excluding/deduplicating triangles
  std::vector<Box3> boxes_;                  // each live triangle's box as registered in grid_
  std::optional<TriangleGrid> grid_;         // the live triangles with no hub corner (inGrid_)
  std::vector<std::uint8_t> inGrid_;
  // A hub (a vertex of valence ≥ kHubValence) and the angular index of its star: each star
  // triangle (v, p, q) is registered by the box of its directions from v (directionBox of p, q).
  struct Hub {
    std::uint32_t vertex = kNone;
    std::optional<TriangleGrid> directions, coarse;  // coarse: kHubCoarse times larger cells
    // Since the hub last moved: a box containing every star triangle, the least distance from the
    // hub to a far edge, the longest edge (bounded by a box diagonal), and the star triangles
    // without a direction box (while there are any, queries enumerate the whole star).
    Box3 starBox;
    double minHeight = 0.0, maxEdge = 0.0;
    std::uint32_t unindexed = 0;
    // Edges at the hub keyed above their plane-independent lower bound (Bounded, Solved or
    // Infeasible; perhaps some no longer): the only ones a change of its planes must re-key.
    std::vector<std::uint32_t> raised;
  };
  std::vector<Hub> hubs_;
  std::vector<std::uint32_t> hubOf_;      // per vertex: its slot in hubs_, or kNone
  std::vector<std::uint8_t> edgeRaised_;  // listed in the `raised` list of its hub ends
  void noteRaised(std::uint32_t e);
  std::size_t verticesAtGridBuild_ = 0;
  std::uint32_t stamp_ = 0;
  std::size_t aliveVertices_ = 0;
  double tolerance_ = 0.0;

  // Edges: cornerEdge_[3t + k] is the edge from corner k of triangle t to corner k + 1.
  std::vector<std::uint32_t> cornerEdge_;
  std::vector<std::array<std::uint32_t, 2>> edgeEnds_;  // (survivor, merged) of a contraction
  std::vector<EdgeState> edgeState_;
  std::vector<double> lowerBounds_;
  std::vector<Vec3> edgePositions_;            // contraction point of a Solved edge
  std::vector<std::uint32_t> parkedVersions_;  // versionsOf(e) when it was parked
  std::vector<std::uint8_t> edgeListed_;       // in parked_
  // The last solve of each edge: its cost, when (contractionCount_) and its active triangles
  // (activeKnown_: with the edge's current quadric; the triangles are kept as hints afterwards).
  std::vector<double> solvedCosts_;
  std::vector<std::uint32_t> solvedAt_;
  std::vector<std::array<std::uint32_t, 3>> activeTriangles_;
  std::vector<std::uint8_t> activeKnown_;
  std::vector<std::uint32_t> triangleChangedAt_;  // contractionCount_ when its plane last changed
  std::uint32_t contractionCount_ = 0;
  double costSlack_ = 0.0;  // absolute rounding allowance of a cost: 10⁻¹⁰ of the diagonal²
  IndexedMinHeap queue_;    // queued edges by key, ties by edge id
  std::vector<std::uint32_t> parked_;  // parked edges (and some no longer parked)
  // Edges parked because the limit of advance() stopped them, queued again by the next advance().
  std::vector<std::uint32_t> overLimit_;
  double worstCost_ = 0.0;  // largest exact cost of an executed contraction
  double seconds_ = 0.0;    // spent in start() and advance() on the way to this state
  // Scratch, reused by every call so the main loop does not allocate once warmed up.
  std::vector<std::uint32_t> fanA_, fanB_, neighbours_, solveFanU_, solveFanV_;
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
  std::vector<std::uint32_t> halfSpaceTriangles_;  // the triangle of each half-space
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

// Numbers the edges in order of (lower, higher) vertex, fills cornerEdge_ and edgeEnds_, locks the
// vertices of border and non-manifold edges and lists the interior edges. Each vertex v numbers its
// edges to higher vertices from its own corners (a short sort per vertex, not one of all edges).
void BoundingMeshSimplifier::classifyEdges(std::vector<std::uint32_t>& interiorEdges) {
  struct HalfEdge {
    std::uint32_t other;  // the higher vertex (or v itself)
    std::uint32_t corner;
    bool forward;  // stored direction is lower → higher
  };
  std::vector<HalfEdge> halfEdges;
  cornerEdge_.assign(triangles_.size() * 3, kNone);
  for (std::uint32_t v = 0; v < positions_.size(); ++v) {
    halfEdges.clear();
    for (std::uint32_t c = firstCorner_[v]; c != kNone; c = nextCorner_[c]) {
      const std::uint32_t t = c / 3, k = c % 3;
      const std::uint32_t next = triangles_[t][(k + 1) % 3], previous = triangles_[t][(k + 2) % 3];
      if (next >= v) halfEdges.push_back({next, c, next > v});  // (v, v) of a degenerate triangle
      if (previous > v) halfEdges.push_back({previous, 3 * t + (k + 2) % 3, false});
    }
    std::sort(halfEdges.begin(), halfEdges.end(),
              [](const HalfEdge& l, const HalfEdge& r) { return l.other < r.other; });
    for (std::size_t i = 0; i < halfEdges.size();) {
      std::size_t j = i;
      int forward = 0;
      const auto edge = static_cast<std::uint32_t>(edgeEnds_.size());
      while (j < halfEdges.size() && halfEdges[j].other == halfEdges[i].other) {
        forward += halfEdges[j].forward ? 1 : 0;
        cornerEdge_[halfEdges[j].corner] = edge;
        ++j;
      }
      const std::uint32_t lo = v, hi = halfEdges[i].other;
      edgeEnds_.push_back({lo, hi});
      const std::size_t count = j - i;
      if (count == 2 && forward != 1) {
        throw InputError("triangles are not consistently oriented (edge between vertices " +
                         std::to_string(lo) + " and " + std::to_string(hi) +
                         " is traversed twice in the same direction)");
      }
      if (count == 2) {
        interiorEdges.push_back(edge);
      } else {  // border (1) or non-manifold (> 2): keep it exactly as it is
        vertexLocked_[lo] = vertexLocked_[hi] = 1;
      }
      i = j;
    }
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
    // Walked through the link sorted by first vertex (a binary search per step, not a scan: hubs
    // have thousands of link edges). Only a link whose edges all start at distinct vertices can be
    // one cycle, so which of several edges from one vertex is found does not change the verdict.
    const std::pair<std::uint32_t, std::uint32_t> start = link[0];
    std::sort(link.begin(), link.end());
    std::size_t steps = 0;
    std::uint32_t at = start.second;
    while (at != start.first && steps < link.size()) {
      const auto next = std::lower_bound(
          link.begin(), link.end(), at, [](const auto& e, std::uint32_t x) { return e.first < x; });
      if (next == link.end() || next->first != at) break;
      at = next->second;
      ++steps;
    }
    if (at != start.first || steps + 1 != link.size()) vertexLocked_[v] = 1;
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
  halfSpaceTriangles_.push_back(t);
}

// The edge's merged quadric in coordinates centred on the edge (so large absolute coordinates lose
// no precision), with a tiny pull towards the edge midpoint that makes the problem strictly convex:
// flat and cylindrical neighbourhoods (singular quadrics) get a unique, central minimizer.
EdgeProblem BoundingMeshSimplifier::problemOf(std::uint32_t e) const {
  const auto [a, b] = edgeEnds_[e];
  EdgeProblem p;
  p.origin = 0.5 * (positions_[a] + positions_[b]);
  p.quadric = (quadrics_[a] + quadrics_[b]).centredAt(p.origin);
  p.curvatureFloor = 1e-9 * p.quadric.a.trace() + 1e-300;
  p.quadric.a += p.curvatureFloor * Eigen::Matrix3d::Identity();
  p.start = unconstrainedMinimizer(p.quadric);
  p.minimum = p.start ? p.quadric(*p.start) : 0.0;
  p.lowerBound = std::max(p.minimum, 0.0);
  return p;
}

// Queues edge e by the lower bound of its cost (lazy), or by its exact cost (eager reference).
void BoundingMeshSimplifier::queueEdge(std::uint32_t e) {
  lowerBounds_[e] = problemOf(e).lowerBound;
  edgeState_[e] = EdgeState::Lower;
  edgeRaised_[e] = 0;  // listed again at its (perhaps new) hub ends when raised
  activeKnown_[e] = 0;
  queue_.set(e, lowerBounds_[e]);
  if (!options_.lazyQueue) solveEdge(e);
}

// Solves edge e's constrained problem (Algorithm 1) with the current planes and re-keys it by its
// exact cost (costAt).
void BoundingMeshSimplifier::solveEdge(std::uint32_t e) {
  const auto [a, b] = edgeEnds_[e];
  gatherFan(a, solveFanU_);
  gatherFan(b, solveFanV_);
  const EdgeProblem p = problemOf(e);
  halfSpaces_.clear();
  halfSpaceTriangles_.clear();
  for (std::uint32_t t : solveFanU_) addHalfSpace(t, p.origin);
  for (std::uint32_t t : solveFanV_) {
    if (!contains(t, a)) addHalfSpace(t, p.origin);
  }
  const ContractionPoint point =
      p.start ? solveContractionFrom(p.quadric, *p.start, halfSpaces_, tolerance_)
              : solveContraction(p.quadric, halfSpaces_, tolerance_);
  if (!hubs_.empty()) noteRaised(e);
  if (!point.feasible) {
    edgeState_[e] = EdgeState::Infeasible;
    queue_.set(e, std::numeric_limits<double>::infinity());
    return;
  }
  const double cost = costAt(p, point.position);
  edgeState_[e] = EdgeState::Solved;
  edgePositions_[e] = p.origin + point.position;
  queue_.set(e, cost);
  solvedCosts_[e] = cost;
  solvedAt_[e] = contractionCount_;
  activeTriangles_[e] = {kNone, kNone, kNone};
  activeKnown_[e] = point.activeCount >= 0;
  for (int i = 0; i < point.activeCount; ++i) {
    activeTriangles_[e][static_cast<std::size_t>(i)] =
        halfSpaceTriangles_[static_cast<std::size_t>(point.active[static_cast<std::size_t>(i)])];
  }
}

// Raises Lower edge e's key to the minimum of its quadric over the half-spaces of the triangles
// active at its last solve that still bound it (alive, at one of its ends), from the dual in closed
// form (dualMinimumBound): a subset of its current planes, so at most its exact cost, less a
// relative 10⁻⁶ and 10⁻¹⁰ of the diagonal² for rounding. False when no such triangle exists.
bool BoundingMeshSimplifier::tightenBound(std::uint32_t e) {
  const auto [a, b] = edgeEnds_[e];
  std::array<std::uint32_t, 3> hints{};
  std::size_t hintCount = 0;
  for (const std::uint32_t t : activeTriangles_[e]) {
    if (t != kNone && triangleAlive_[t] && (contains(t, a) || contains(t, b))) {
      hints[hintCount++] = t;
    }
  }
  if (hintCount == 0) return false;
  const EdgeProblem p = problemOf(e);
  if (!p.start) return false;
  halfSpaces_.clear();
  halfSpaceTriangles_.clear();
  for (std::size_t i = 0; i < hintCount; ++i) addHalfSpace(hints[i], p.origin);
  const double minimum =
      dualMinimumBound(p.quadric, *p.start, p.minimum, halfSpaces_, tolerance_, p.curvatureFloor);
  edgeState_[e] = EdgeState::Bounded;
  if (!hubs_.empty()) noteRaised(e);
  if (minimum > p.lowerBound) {
    const double bound = minimum * (1.0 - 1e-6) - costSlack_;
    if (bound > queue_.key(e)) queue_.set(e, bound);
  }
  return true;
}

// A lower bound of edge e's exact cost after its planes changed. If none of the planes held as
// equalities at its last optimum changed since, that optimum is still the optimum over the planes
// that did not change (the KKT conditions involve only the active ones), and adding the changed
// planes can only raise it: its cost (less a relative 10⁻⁷ for rounding) bounds the new one.
// Otherwise the unconstrained minimum does. `fromLastCost` tells which.
double BoundingMeshSimplifier::boundAfterChange(std::uint32_t e, bool& fromLastCost) const {
  fromLastCost = false;
  if (!activeKnown_[e]) return lowerBounds_[e];
  for (const std::uint32_t t : activeTriangles_[e]) {
    if (t != kNone && (!triangleAlive_[t] || triangleChangedAt_[t] > solvedAt_[e])) {
      return lowerBounds_[e];
    }
  }
  fromLastCost = true;
  return std::max(lowerBounds_[e], solvedCosts_[e] * (1.0 - 1e-7) - costSlack_);
}

// Edge e's planes changed: its exact cost is no longer known, only a lower bound.
void BoundingMeshSimplifier::invalidateEdge(std::uint32_t e) {
  const EdgeState state = edgeState_[e];
  if (state == EdgeState::Off || state == EdgeState::Parked) return;
  if (!options_.lazyQueue) {
    solveEdge(e);
    return;
  }
  if (state == EdgeState::Infeasible) {
    edgeState_[e] = EdgeState::Lower;
    activeKnown_[e] = 0;
    queue_.set(e, lowerBounds_[e]);
    return;
  }
  bool fromLastCost = false;
  const double bound = boundAfterChange(e, fromLastCost);
  if (state != EdgeState::Lower || bound < queue_.key(e)) {  // a tightened bound may not hold now
    edgeState_[e] = fromLastCost ? EdgeState::Bounded : EdgeState::Lower;
    queue_.set(e, bound);
  }
}

void BoundingMeshSimplifier::park(std::uint32_t e) {
  queue_.erase(e);
  edgeState_[e] = EdgeState::Parked;
  parkedVersions_[e] = versionsOf(e);
  if (!edgeListed_[e]) {
    edgeListed_[e] = 1;
    parked_.push_back(e);
  }
}

// Executes the contraction of Solved edge e unless it would break the mesh's topology or geometry
// or make the new fan cross the mesh; then re-queues the edges whose cost it changed.
BoundingMeshSimplifier::Outcome BoundingMeshSimplifier::contract(std::uint32_t e) {
  const auto [a, b] = edgeEnds_[e];
  const Contraction c{a, b, edgePositions_[e]};
  gatherFan(a, fanA_);
  gatherFan(b, fanB_);

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
  ++contractionCount_;
  retireMergedEdges(a, b);
  // Star triangles of hubs leave the indexes while their geometry changes (placeTriangle below).
  for (std::uint32_t t : fanA_) {
    if (!inGrid_[t]) unindexAtHubs(t);
  }
  for (std::uint32_t t : fanB_) {
    if (!inGrid_[t] && !contains(t, a)) unindexAtHubs(t);
  }
  for (std::uint32_t t : fanA_) {
    if (contains(t, b)) {
      if (inGrid_[t]) grid_->remove(t, boxes_[t]);
      inGrid_[t] = 0;
      triangleAlive_[t] = 0;
      triangleChangedAt_[t] = contractionCount_;
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
  const bool hub = hubOf_[a] != kNone || hubOf_[b] != kNone || triangleCount_[a] >= kHubValence;
  if (hubOf_[b] != kNone) {
    hubs_[hubOf_[b]].vertex = kNone;
    hubOf_[b] = kNone;
  }
  const Vec3 reference = c.position;
  const double length = options_.mergeLength;
  quadrics_[a] = mergeQuadrics(quadrics_[a], quadrics_[b], options_.merge, reference, length);
  positions_[a] = c.position;
  vertexAlive_[b] = 0;
  --aliveVertices_;
  if (hub) acquireHub(a);
  fanA_.clear();
  forEachTriangle(a, [&](std::uint32_t t) {
    updatePlane(t);
    triangleChangedAt_[t] = contractionCount_;
    placeTriangle(t, boxOf(t));
    fanA_.push_back(t);
  });

  requeueAround(a);
  return Outcome::Done;
}

// Before b merges into a: edge (a, b) and, for each triangle (a, b, o) that collapses, edge (b, o)
// disappear; the triangle across (b, o) takes over edge (a, o). fanA_ and fanB_ hold the fans.
void BoundingMeshSimplifier::retireMergedEdges(std::uint32_t a, std::uint32_t b) {
  const auto retire = [&](std::uint32_t e) {
    queue_.erase(e);
    edgeState_[e] = EdgeState::Off;
  };
  for (std::uint32_t t : fanA_) {
    if (!contains(t, b)) continue;
    std::uint32_t fromB = kNone, fromA = kNone;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t u = triangles_[t][k], w = triangles_[t][(k + 1) % 3];
      const std::uint32_t edge = cornerEdge_[3 * t + k];
      if ((u == a && w == b) || (u == b && w == a)) {
        retire(edge);
      } else if (u == b || w == b) {
        fromB = edge;
      } else {
        fromA = edge;
      }
    }
    retire(fromB);
    for (std::uint32_t u : fanB_) {
      if (u == t || contains(u, a)) continue;
      for (std::uint32_t k = 0; k < 3; ++k) {
        if (cornerEdge_[3 * u + k] == fromB) cornerEdge_[3 * u + k] = fromA;
      }
    }
  }
}

// After a contraction into a: the edges at a get a new quadric and are queued afresh; the other
// edges at a's neighbours keep their quadrics, but their planes moved, so their exact costs are
// invalidated (thesis Algorithm 2, "update the costs of the edges around the new vertex").
void BoundingMeshSimplifier::requeueAround(std::uint32_t a) {
  ++version_[a];
  gatherNeighbours(a, neighbours_);
  for (std::uint32_t w : neighbours_) ++version_[w];
  for (std::uint32_t t : fanA_) {  // each edge (a, w) leaves a in exactly one triangle of its fan
    const Triangle& tri = triangles_[t];
    const std::uint32_t k = tri[0] == a ? 0 : (tri[1] == a ? 1 : 2);
    const std::uint32_t e = cornerEdge_[3 * t + k], w = tri[(k + 1) % 3];
    edgeEnds_[e] = {a, w};
    if (!vertexLocked_[w]) queueEdge(e);
  }
  for (std::uint32_t w : neighbours_) {
    if (vertexLocked_[w]) continue;
    if (hubOf_[w] != kNone) {  // only its raised edges can need a lower key (see invalidateEdge)
      invalidateRaised(hubs_[hubOf_[w]]);
      continue;
    }
    forEachTriangle(w, [&](std::uint32_t t) {
      const Triangle& tri = triangles_[t];
      const std::uint32_t k = tri[0] == w ? 0 : (tri[1] == w ? 1 : 2);
      if (tri[(k + 1) % 3] != a) invalidateEdge(cornerEdge_[3 * t + k]);
    });
  }
}

// Invalidates the raised edges of `hub` (all its edges but the Lower ones, whose key, their
// plane-independent lower bound, invalidateEdge leaves as it is) and forgets those no longer raised
// or no longer at the hub.
void BoundingMeshSimplifier::invalidateRaised(Hub& hub) {
  std::size_t kept = 0;
  for (const std::uint32_t e : hub.raised) {
    const EdgeState state = edgeState_[e];
    const bool atHub = edgeEnds_[e][0] == hub.vertex || edgeEnds_[e][1] == hub.vertex;
    const bool raised =
        state == EdgeState::Bounded || state == EdgeState::Solved || state == EdgeState::Infeasible;
    if (atHub && raised) invalidateEdge(e);
    if (atHub && (edgeState_[e] == EdgeState::Bounded || edgeState_[e] == EdgeState::Solved ||
                  edgeState_[e] == EdgeState::Infeasible)) {
      hub.raised[kept++] = e;
    } else {
      edgeRaised_[e] = 0;
    }
  }
  hub.raised.resize(kept);
}

// The new fan may not cross any other triangle of the mesh nor itself: this keeps outer results
// free of folds (which parity-based inside tests misread) and inner results inside the original.
// Each pair whose boxes overlap is first given the cheap certificate certainlyApart (cached unit
// normals and twice-areas); only the pairs it cannot clear reach the exact predicate, so the
// verdict is the predicate's.
bool BoundingMeshSimplifier::newFanCrossesMesh(const Contraction& c) {
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
  if (!hubs_.empty()) gatherNearHubs(fanBox, a, b, exclude);
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
  grid_.emplace(cellSize, triangles_.size());
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    if (triangleAlive_[t] && inGrid_[t]) grid_->insert(t, boxes_[t]);
  }
  verticesAtGridBuild_ = aliveVertices_;
}

// Makes v a hub with an empty index (reusing a free slot and its table when there is one), or
// empties the record of hub v, whose star triangles are all out of its index.
void BoundingMeshSimplifier::acquireHub(std::uint32_t v) {
  if (hubOf_[v] == kNone) {
    std::uint32_t slot = 0;
    while (slot < hubs_.size() && hubs_[slot].vertex != kNone) ++slot;
    if (slot == hubs_.size()) hubs_.emplace_back();
    hubOf_[v] = slot;
  }
  Hub& hub = hubs_[hubOf_[v]];
  hub.vertex = v;
  if (!hub.directions) {
    const double valence = std::max<double>(triangleCount_[v], 1.0);
    const double cellSize = std::max(4.0 * std::numbers::pi / valence, 8.0 * kHubMargin);
    hub.directions.emplace(cellSize, triangleCount_[v]);
    // The coarse index holds about one entry per triangle (the fine one a few): a third of the
    // table and pool keeps its memory at a third.
    hub.coarse.emplace(kHubCoarse * cellSize, triangleCount_[v] / 3);
  }
  const float inf = std::numeric_limits<float>::infinity();
  hub.starBox = {Eigen::Vector3f::Constant(inf), Eigen::Vector3f::Constant(-inf)};
  hub.minHeight = std::numeric_limits<double>::infinity();
  hub.maxEdge = 0.0;
  hub.unindexed = 0;
  hub.raised.clear();  // v's edges are all queued afresh by their lower bounds
  // Room for every edge at v now, so that the first contractions next to it do not allocate.
  hub.raised.reserve(triangleCount_[v]);
}

// Edge e is now keyed above its lower bound: lists it at its hub ends.
void BoundingMeshSimplifier::noteRaised(std::uint32_t e) {
  if (edgeRaised_[e]) return;
  for (const std::uint32_t v : edgeEnds_[e]) {
    if (hubOf_[v] == kNone) continue;
    hubs_[hubOf_[v]].raised.push_back(e);
    edgeRaised_[e] = 1;
  }
}

// The box under which star triangle t of `hub` is indexed: its directions from the hub; empty when
// they cannot be boxed or span too many cells. A function of the current positions only, so the
// box a triangle was indexed with is found again for removal.
std::optional<Box3> BoundingMeshSimplifier::starDirectionBox(const Hub& hub,
                                                             std::uint32_t t) const {
  const Triangle& tri = triangles_[t];
  const std::uint32_t k = tri[0] == hub.vertex ? 0 : (tri[1] == hub.vertex ? 1 : 2);
  const std::array<Vec3, 2> far{positions_[tri[(k + 1) % 3]], positions_[tri[(k + 2) % 3]]};
  const std::optional<std::array<Vec3, 3>> directions = directionsFrom(positions_[hub.vertex], far);
  if (!directions) return std::nullopt;
  const Box3 box = sphericalBox(*directions, 2, 0.0);
  if ((box.hi - box.lo).maxCoeff() > kHubMaxCellSpan * hub.directions->cellSize()) {
    return std::nullopt;
  }
  return box;
}

// Registers triangle t, with its current geometry and boxes_[t], in the index of each hub corner.
void BoundingMeshSimplifier::indexAtHubs(std::uint32_t t) {
  for (const std::uint32_t v : triangles_[t]) {
    if (hubOf_[v] == kNone) continue;
    Hub& hub = hubs_[hubOf_[v]];
    if (const std::optional<Box3> box = starDirectionBox(hub, t)) {
      hub.directions->insert(t, *box);
      hub.coarse->insert(t, *box);
    } else {
      ++hub.unindexed;
    }
    const Triangle& tri = triangles_[t];
    const std::uint32_t k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    hub.minHeight =
        std::min(hub.minHeight, pointSegmentDistance(positions_[v], positions_[tri[(k + 1) % 3]],
                                                     positions_[tri[(k + 2) % 3]]));
    hub.maxEdge = std::max(hub.maxEdge, std::sqrt(boxes_[t].diagonalSquared()));
    hub.starBox = {hub.starBox.lo.cwiseMin(boxes_[t].lo), hub.starBox.hi.cwiseMax(boxes_[t].hi)};
  }
}

// Removes triangle t, with the geometry it was indexed with, from the index of each hub corner.
void BoundingMeshSimplifier::unindexAtHubs(std::uint32_t t) {
  for (const std::uint32_t v : triangles_[t]) {
    if (hubOf_[v] == kNone) continue;
    Hub& hub = hubs_[hubOf_[v]];
    if (const std::optional<Box3> box = starDirectionBox(hub, t)) {
      hub.directions->remove(t, *box);
      hub.coarse->remove(t, *box);
    } else {
      --hub.unindexed;
    }
  }
}

// Registers triangle t, whose geometry changed and which is in no hub's index, under its new box:
// in the indexes of its hub corners if it has any, else in the spatial hash.
void BoundingMeshSimplifier::placeTriangle(std::uint32_t t, const Box3& box) {
  if (hasHubCorner(t)) {
    if (inGrid_[t]) grid_->remove(t, boxes_[t]);
    inGrid_[t] = 0;
    boxes_[t] = box;
    indexAtHubs(t);
    return;
  }
  if (inGrid_[t]) {
    grid_->move(t, boxes_[t], box);
  } else {
    grid_->insert(t, box);
  }
  inGrid_[t] = 1;
  boxes_[t] = box;
}

// Adds to nearby_ the star triangles of hubs (other than a and b) that the new fan might meet,
// marking them `seen`. Two triangles whose directions from hub v are more than kHubMargin apart
// stay farther apart than 0.6·kHubMargin times the distance from v to either one's points away from
// v; the predicate only looks at far edges when they share v. So when every height (hub to a far
// edge of its star, hub to a new triangle or its far edge) is at least kHubHeightRatio of every
// edge involved, only the star triangles indexed in a cell the new triangles' grown direction boxes
// touch can meet them. Otherwise the whole star is listed.
void BoundingMeshSimplifier::gatherNearHubs(const Box3& fanBox, std::uint32_t a, std::uint32_t b,
                                            std::uint32_t seen) {
  const auto add = [&](std::uint32_t u) {
    if (triangleMark_[u] == seen) return;
    triangleMark_[u] = seen;
    if (triangleAlive_[u] && fanBox.overlaps(boxes_[u])) nearby_.push_back(u);
  };
  for (Hub& hub : hubs_) {
    if (hub.vertex == kNone || hub.vertex == a || hub.vertex == b ||
        !fanBox.overlaps(hub.starBox)) {
      continue;
    }
    const Vec3& apex = positions_[hub.vertex];
    const double fine = hub.directions->cellSize(), coarse = hub.coarse->cellSize();
    bool indexed = hub.unindexed == 0;
    for (const NewTriangle& n : newTriangles_) {
      if (!indexed) break;
      if (!n.box.overlaps(hub.starBox)) continue;
      const std::uint32_t k = n.ids[0] == hub.vertex
                                  ? 0
                                  : (n.ids[1] == hub.vertex ? 1 : (n.ids[2] == hub.vertex ? 2 : 3));
      // A new triangle at the hub is seen from it along its far edge; the predicate ignores the
      // hub itself.
      const std::array<Vec3, 2> far{n.corners[(k + 1) % 3], n.corners[(k + 2) % 3]};
      const double height =
          k < 3 ? pointSegmentDistance(apex, far[0], far[1])
                : (closestPointOnTriangle(apex, n.corners[0], n.corners[1], n.corners[2]) - apex)
                      .norm();
      const double longest = std::max(hub.maxEdge, std::sqrt(n.sizeSquared));
      const std::optional<std::array<Vec3, 3>> directions =
          k < 3 ? directionsFrom(apex, far) : directionsFrom(apex, n.corners);
      indexed = directions && std::min(height, hub.minHeight) >= kHubHeightRatio * longest;
      if (!indexed) break;
      const int count = k < 3 ? 2 : 3;
      forEachSphericalPiece(*directions, count, kHubMargin, coarse,
                            [&](const Box3& box, const std::array<Vec3, 3>& piece) {
                              if (!hub.coarse->anyNear(box)) return;
                              forEachSphericalPiece(
                                  piece, count, kHubMargin, fine,
                                  [&](const Box3& fineBox, const std::array<Vec3, 3>&) {
                                    hub.directions->forEachNear(fineBox, add);
                                  });
                            });
    }
    if (!indexed) forEachTriangle(hub.vertex, add);
  }
}

// Re-queues the parked edges whose neighbourhood changed since they were parked.
bool BoundingMeshSimplifier::revisitParked() {
  bool any = false;
  std::size_t kept = 0;
  for (const std::uint32_t e : parked_) {
    if (edgeState_[e] == EdgeState::Parked && versionsOf(e) == parkedVersions_[e]) {
      parked_[kept++] = e;  // nothing changed around it: still rejected
      continue;
    }
    edgeListed_[e] = 0;
    if (edgeState_[e] == EdgeState::Parked) {
      queueEdge(e);
      any = true;
    }
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
  start();
  advance(options_.maxError);
  return result();
}

void BoundingMeshSimplifier::start() {
  const auto startTime = std::chrono::steady_clock::now();
  const std::size_t n = positions_.size();
  vertexLocked_.assign(n, 0);
  vertexAlive_.assign(n, 1);
  version_.assign(n, 0);
  markA_.assign(n, 0);
  markB_.assign(n, 0);
  triangleAlive_.assign(triangles_.size(), 1);
  triangleMark_.assign(triangles_.size(), 0);
  boxes_.resize(triangles_.size());
  inGrid_.assign(triangles_.size(), 1);
  hubOf_.assign(n, kNone);
  normals_.resize(triangles_.size());
  offsets_.resize(triangles_.size());
  crossLengths_.resize(triangles_.size());

  buildAdjacency();
  std::vector<std::uint32_t> interiorEdges;
  classifyEdges(interiorEdges);
  const std::size_t edgeCount = edgeEnds_.size();
  edgeState_.assign(edgeCount, EdgeState::Off);
  lowerBounds_.assign(edgeCount, 0.0);
  edgePositions_.resize(edgeCount);
  parkedVersions_.assign(edgeCount, 0);
  edgeListed_.assign(edgeCount, 0);
  edgeRaised_.assign(edgeCount, 0);
  solvedCosts_.assign(edgeCount, 0.0);
  solvedAt_.assign(edgeCount, 0);
  activeTriangles_.assign(edgeCount, {kNone, kNone, kNone});
  activeKnown_.assign(edgeCount, 0);
  triangleChangedAt_.assign(triangles_.size(), 0);
  queue_.reset(edgeCount);
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
  costSlack_ = 1e-10 * diagonal * diagonal;
  if (options_.mergeLength <= 0.0) options_.mergeLength = 0.01 * diagonal;
  stats_.inputVertices = aliveVertices_;
  double edgeLengthSum = 0.0;
  for (const Triangle& t : triangles_) {
    edgeLengthSum += (positions_[t[0]] - positions_[t[1]]).norm();
  }
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) boxes_[t] = boxOf(t);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (triangleCount_[v] >= kHubValence) acquireHub(v);
  }
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    inGrid_[t] = hasHubCorner(t) ? 0 : 1;
    if (!inGrid_[t]) indexAtHubs(t);
  }
  buildGrid(
      std::max(2.0 * edgeLengthSum / std::max<double>(1.0, static_cast<double>(triangles_.size())),
               1e-9 * diagonal + 1e-300));

  for (const std::uint32_t e : interiorEdges) {
    if (!vertexLocked_[edgeEnds_[e][0]] && !vertexLocked_[edgeEnds_[e][1]]) queueEdge(e);
  }
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
}

void BoundingMeshSimplifier::advance(double maxError) {
  const auto startTime = std::chrono::steady_clock::now();
  for (const std::uint32_t e : overLimit_) {
    if (edgeState_[e] == EdgeState::Parked) queueEdge(e);
  }
  overLimit_.clear();
  // Algorithm 2 with a lazy queue. Every queued edge's key is at most its exact cost (a minimum
  // over fewer planes is at most the minimum over all), and a popped edge is first given a tighter
  // bound, then solved if it is not yet: it is contracted only once it is the least by exact cost.
  // So edges are taken in exactly the order of a queue holding every exact cost
  // (options_.lazyQueue = false), ties broken by edge id.
  options_.maxError = maxError;
  const std::size_t target = options_.targetVertices;
  const double maxCost = maxError * maxError;
  const std::size_t toRemove = aliveVertices_ > target ? aliveVertices_ - target : 0;
  const std::size_t contractionsBefore = stats_.contractions;
  while (aliveVertices_ > target) {
    if (queue_.empty()) {
      if (!revisitParked()) break;
      continue;
    }
    const std::uint32_t e = queue_.top();
    const double cost = queue_.topKey();
    if (cost > maxCost) {  // every queued exact cost is at least this: none may be contracted
      park(e);
      overLimit_.push_back(e);
      continue;
    }
    if (edgeState_[e] == EdgeState::Lower) {
      if (!tightenBound(e)) solveEdge(e);
      continue;
    }
    if (edgeState_[e] == EdgeState::Bounded) {
      solveEdge(e);
      continue;
    }
    if (edgeState_[e] == EdgeState::Infeasible) {
      ++stats_.rejectedInfeasible;
      park(e);
      continue;
    }
    if (aliveVertices_ * 2 < verticesAtGridBuild_) {
      buildGrid(grid_->cellSize() * std::sqrt(2.0));  // triangles grew: coarser cells
    }
    switch (contract(e)) {
      case Outcome::Done: {
        ++stats_.contractions;
        worstCost_ = std::max(worstCost_, cost);
        const std::size_t made = stats_.contractions - contractionsBefore;
        if (options_.progress && made % 8192 == 0 && toRemove > 0) {
          options_.progress(static_cast<double>(made) / static_cast<double>(toRemove));
        }
        break;
      }
      case Outcome::Topology:
        ++stats_.rejectedTopology;
        park(e);
        break;
      case Outcome::Geometry:
        ++stats_.rejectedGeometry;
        park(e);
        break;
      case Outcome::Crossing:
        ++stats_.rejectedCrossing;
        park(e);
        break;
    }
  }

  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
  if (options_.progress) options_.progress(1.0);
}

BoundingMeshResult BoundingMeshSimplifier::result() const {
  BoundingMeshResult result;
  result.mesh = compact();
  result.stats = stats_;
  result.stats.outputVertices = result.mesh.vertices.size();
  result.stats.quadricError = std::sqrt(worstCost_);
  if (aliveVertices_ <= options_.targetVertices) {
    result.stats.stopReason = "vertex target reached";
  } else if (std::isfinite(options_.maxError)) {
    result.stats.stopReason = "no contraction left within the error limit";
  } else {
    result.stats.stopReason = "no contraction left that keeps the mesh valid and bounding";
  }
  result.stats.seconds = seconds_;
  return result;
}

}  // namespace

namespace {

// Applies the polish pass of options.polish to `result` and records it in its stats.
void polishResult(const TriangleMesh& input, const BoundingMeshOptions& options,
                  BoundingMeshResult& result) {
  PolishOptions polish;
  polish.side = options.side;
  polish.progress = options.polishProgress;
  polish.relocations = options.polishRelocations;
  const PolishStats stats = polishBoundingMesh(input, result.mesh, polish);
  result.stats.polishMoves = stats.moves;
  result.stats.polishFlips = stats.flips;
  result.stats.polishRelocations = stats.relocations;
  result.stats.polishSeconds = stats.seconds;
}

}  // namespace

BoundingMeshResult simplifyBounding(const TriangleMesh& input, const BoundingMeshOptions& options) {
  BoundingMeshResult result = BoundingMeshSimplifier(input, options).run();
  if (options.polish) polishResult(input, options, result);
  return result;
}

BoundingMeshResult simplifyBoundingWithin(const TriangleMesh& input, BoundingMeshOptions options,
                                          double epsilon, std::size_t samples,
                                          HausdorffReport& measured, int maxRuns) {
  const HausdorffMeter meter(input, samples, 1);
  // Every limit tried is above the largest one known to fit, so each run goes on from a copy of
  // that one's simplifier instead of starting over (at first: after the contractions of cost 0).
  const std::function<void(double)> progress = std::move(options.progress);
  options.progress = nullptr;
  BoundingMeshSimplifier fitting(input, options);
  fitting.start();
  fitting.advance(0.0);
  fitting.reportProgressTo(progress);
  int runs = 0;
  double fits = 0.0, fails = 0.0;  // largest scale known to fit, smallest known to fail (0: none)
  double scale = 1.0;
  while (runs < maxRuns) {
    ++runs;
    BoundingMeshSimplifier attempt = fitting;
    attempt.advance(scale * epsilon);
    const BoundingMeshResult result = attempt.result();
    if (meter.within(result.mesh, epsilon)) {
      fits = scale;
      fitting = std::move(attempt);
      if (result.stats.stopReason == "vertex target reached") break;  // cannot go further
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
  BoundingMeshResult best = fitting.result();  // nothing fitted: the contractions of cost 0 only
  if (options.polish) {  // kept only when it stays within the limit on the meter's samples
    BoundingMeshResult polished = best;
    polishResult(input, options, polished);
    if (meter.within(polished.mesh, epsilon)) best = std::move(polished);
  }
  measured = meter.measure(best.mesh);
  if (best.stats.stopReason != "vertex target reached") {
    best.stats.stopReason = "largest simplification found within the distance limit";
  }
  best.stats.runs = runs;
  return best;
}

}  // namespace kaboum::geometry
