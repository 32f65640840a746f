// Implements bounding_polish.hpp: greedy sweeps of guarded vertex moves and edge flips, scored on
// fixed samples of both surfaces (docs/bounding-mesh.md, "Polish").
#include "kaboum/geometry/bounding_polish.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <unordered_map>

#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"
#include "kaboum/geometry/triangle_grid.hpp"

namespace kaboum::geometry {
namespace {

// Barycentric points of a result triangle whose distances to the original score it.
constexpr double kTrianglePoints[7][3] = {{1, 0, 0},
                                          {0, 1, 0},
                                          {0, 0, 1},
                                          {.5, .5, 0},
                                          {.5, 0, .5},
                                          {0, .5, .5},
                                          {1. / 3, 1. / 3, 1. / 3}};
// Relocations are judged on the result→original distance at the barycentric grid points
// (i, j, k) / kCheckGrid of every result triangle: a denser set than kTrianglePoints, because a
// relocation changes long triangles whose interior the scoring points do not see.
constexpr int kCheckGrid = 8;
constexpr std::uint32_t kNone = 0xffffffffu;
// Bisection steps of the line search for the farthest valid point along a move direction.
constexpr int kBisections = 7;
// A move direction blocked before this fraction of its step is also tried tilted.
constexpr double kTiltBelow = 0.5;
// A split point's barycentric coordinates are at least this (no slivers).
constexpr double kSplitMargin = 0.1;

// The projections of `p` and `q` on `axis` are more than `gap`·|axis| apart.
bool separatedAlong(const Vec3& axis, std::span<const Vec3> p, std::span<const Vec3> q,
                    double gap) {
  const double length = axis.norm();
  if (!(length > 1e-300)) return false;
  double pLo = INFINITY, pHi = -INFINITY, qLo = INFINITY, qHi = -INFINITY;
  for (const Vec3& x : p) {
    const double s = axis.dot(x);
    pLo = std::min(pLo, s);
    pHi = std::max(pHi, s);
  }
  for (const Vec3& x : q) {
    const double s = axis.dot(x);
    qLo = std::min(qLo, s);
    qHi = std::max(qHi, s);
  }
  return qLo - pHi > gap * length || pLo - qHi > gap * length;
}

// Separating-axis test of a (possibly flat) tetrahedron and a triangle. Sets within `gap` of each
// other count as meeting; a zero axis is skipped, which can only turn "apart" into "meets".
bool tetrahedronMeetsTriangle(const std::array<Vec3, 4>& t, const std::array<Vec3, 3>& u,
                              double gap) {
  const std::array<Vec3, 6> tetEdges{t[1] - t[0], t[2] - t[0], t[3] - t[0],
                                     t[2] - t[1], t[3] - t[1], t[3] - t[2]};
  const std::array<Vec3, 3> triEdges{u[1] - u[0], u[2] - u[1], u[0] - u[2]};
  if (separatedAlong(triEdges[0].cross(triEdges[1]), t, u, gap)) return false;
  constexpr int kFaces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const auto& f : kFaces) {
    if (separatedAlong((t[f[1]] - t[f[0]]).cross(t[f[2]] - t[f[0]]), t, u, gap)) return false;
  }
  for (const Vec3& e : tetEdges) {
    for (const Vec3& g : triEdges) {
      if (separatedAlong(e.cross(g), t, u, gap)) return false;
    }
  }
  return true;
}

// A hashed uniform grid over fixed points, stored as buckets of point indices.
class PointGrid {
 public:
  PointGrid(const std::vector<Vec3>& points, double cellSize) : points_(points), cell_(cellSize) {
    std::size_t buckets = 1;
    while (buckets < points.size()) buckets *= 2;
    mask_ = buckets - 1;
    start_.assign(buckets + 1, 0);
    for (const Vec3& p : points) ++start_[bucketOf(cellOf(p)) + 1];
    for (std::size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    order_.resize(points.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t i = 0; i < points.size(); ++i)
      order_[fill[bucketOf(cellOf(points[i]))]++] = i;
  }

  // Calls f(index) once for every point inside the box [lo, hi].
  template <class F>
  void forEachIn(const Vec3& lo, const Vec3& hi, F&& f) const {
    const Eigen::Array3i a = cellOf(lo), b = cellOf(hi);
    const double cells = (b - a + 1).cast<double>().prod();
    const auto inside = [&](const Vec3& p) {
      return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    if (cells > static_cast<double>(points_.size())) {  // a scan is cheaper than the cells
      for (std::uint32_t i = 0; i < points_.size(); ++i) {
        if (inside(points_[i])) f(i);
      }
      return;
    }
    for (int x = a.x(); x <= b.x(); ++x) {
      for (int y = a.y(); y <= b.y(); ++y) {
        for (int z = a.z(); z <= b.z(); ++z) {
          const Eigen::Array3i cell(x, y, z);
          const std::size_t bucket = bucketOf(cell);
          for (std::uint32_t k = start_[bucket]; k < start_[bucket + 1]; ++k) {
            const std::uint32_t i = order_[k];
            // Other cells hashed to this bucket are visited from their own cell.
            if ((cellOf(points_[i]) == cell).all() && inside(points_[i])) f(i);
          }
        }
      }
    }
  }

 private:
  [[nodiscard]] Eigen::Array3i cellOf(const Vec3& p) const {
    return (p.array() / cell_).floor().cast<int>();
  }
  [[nodiscard]] std::size_t bucketOf(const Eigen::Array3i& c) const {
    return static_cast<std::size_t>(cellHash(c.x(), c.y(), c.z()) & mask_);
  }

  const std::vector<Vec3>& points_;
  double cell_;
  std::uint64_t mask_ = 0;
  std::vector<std::uint32_t> start_, order_;
};

// The corner (0, 1 or 2) of triangle t at vertex v, which must be one of its corners.
int cornerOf(const Triangle& t, std::uint32_t v) {
  return t[0] == v ? 0 : t[1] == v ? 1 : 2;
}

double meanEdgeLength(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) sum += (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm();
  }
  return sum / static_cast<double>(3 * mesh.triangles.size());
}

// A point on result triangle `triangle` and its distance to the other surface.
struct Spot {
  std::uint32_t triangle;
  Vec3 point;
  double distance;
};

class Polisher {
 public:
  // `focus`: the vertices each phase starts with (all when empty).
  Polisher(const TriangleMesh& original, TriangleMesh& result, const PolishOptions& options,
           std::vector<std::uint32_t> focus = {})
      : original_(original),
        mesh_(result),
        options_(options),
        originalBvh_(original),
        diagonal_(boundingBoxDiagonal(original)),
        gap_(1e-9 * diagonal_),
        samples_(sampleSurface(original, options.samples, options.seed)),
        cellSize_(std::max(meanEdgeLength(result), 1e-6 * diagonal_)),
        sampleGrid_(samples_, cellSize_),
        grid_(cellSize_, result.triangles.size()) {
    const TriangleBvh resultBvh(result);
    distance_.resize(samples_.size());
    nearest_.resize(samples_.size());
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const TriangleBvh::Closest c = resultBvh.closest(samples_[i]);
      distance_[i] = c.distance;
      nearest_[i] = c.triangle;
    }
    incident_.resize(mesh_.vertices.size());
    boxes_.resize(mesh_.triangles.size());
    for (std::uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (const std::uint32_t v : mesh_.triangles[t]) incident_[v].push_back(t);
      boxes_[t] = boxOf(t);
      grid_.insert(t, boxes_[t]);
    }
    stamp_.assign(mesh_.triangles.size(), 0);
    focus_ = std::move(focus);
    findMovableVertices();
  }

  PolishStats run() {
    const auto begin = std::chrono::steady_clock::now();
    const int total = std::max(options_.maxSweeps, 0) + std::max(options_.sumSweeps, 0);
    int done = 0;
    if (options_.progress) options_.progress(0.0);
    for (const Rule rule : {Rule::Max, Rule::Sum}) {
      const int sweeps = rule == Rule::Max ? options_.maxSweeps : options_.sumSweeps;
      for (int s = 0; s < sweeps; ++s) {
        worstSample_ =
            distance_.empty() ? 0.0 : *std::max_element(distance_.begin(), distance_.end());
        if (s == 0) startPhase();
        changedNear_.assign(mesh_.vertices.size(), 0);
        const std::size_t moves = moveVertices(rule, [&](double sweepFraction) {
          if (options_.progress) options_.progress((done + sweepFraction) / total);
        });
        const std::size_t flips = flipEdges(rule);
        dirty_.swap(changedNear_);
        stats_.moves += moves;
        stats_.flips += flips;
        ++done;
        if (options_.progress) options_.progress(static_cast<double>(done) / total);
        if (moves + flips == 0) break;
      }
    }
    if (options_.progress) options_.progress(1.0);
    stats_.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return stats_;
  }

  // The two worst spots, whose distances are the largest ones: the point of the result nearest
  // to the sample farthest from it, and the grid point (kCheckGrid) of the result farthest from
  // the original.
  [[nodiscard]] std::array<Spot, 2> worstSpots() const {
    Spot nearWorstSample{kNone, Vec3::Zero(), 0.0};
    if (!distance_.empty()) {
      const auto worst = std::max_element(distance_.begin(), distance_.end());
      const std::uint32_t i = static_cast<std::uint32_t>(worst - distance_.begin());
      const std::uint32_t t = nearest_[i];
      nearWorstSample = {
          t, closestPointOnTriangle(samples_[i], corner(t, 0), corner(t, 1), corner(t, 2)), *worst};
    }
    return {nearWorstSample, worstResultPoint()};
  }

  // The half-edge collapse of an interior vertex v into a neighbour w that keeps every guarantee
  // (the sweep of v to w meets no original triangle, the link condition holds, no triangle
  // flips, degenerates or crosses another) with the smallest largest distance around it.
  [[nodiscard]] std::optional<std::pair<std::uint32_t, std::uint32_t>> cheapestCollapse() {
    worstSample_ = distance_.empty() ? 0.0 : *std::max_element(distance_.begin(), distance_.end());
    std::optional<std::pair<std::uint32_t, std::uint32_t>> best;
    Score bestScore{INFINITY, INFINITY};
    std::vector<std::uint32_t> full, neighbours;
    for (std::uint32_t v = 0; v < mesh_.vertices.size(); ++v) {
      if (!movable_[v] || incident_[v].size() < 4) continue;
      full = fan_ = incident_[v];
      neighbours.clear();
      for (const std::uint32_t t : full) {
        const Triangle& tri = mesh_.triangles[t];
        neighbours.push_back(tri[(cornerOf(tri, v) + 1) % 3]);
      }
      Vec3 lo, hi;
      fanBounds(lo, hi);
      collectStarPoints(v);
      gatherAffected(lo, hi);
      // The points no collapse of v changes already score above the best collapse found.
      if (unaffected_.max > bestScore.max) continue;
      for (const std::uint32_t w : neighbours) {
        std::uint32_t opposite[2] = {kNone, kNone};
        removed_ = {kNone, kNone};
        fan_.clear();
        for (const std::uint32_t t : full) {
          const Triangle& tri = mesh_.triangles[t];
          const int k = cornerOf(tri, v);
          const int side = tri[(k + 1) % 3] == w ? 0 : tri[(k + 2) % 3] == w ? 1 : -1;
          if (side < 0) {
            fan_.push_back(t);
          } else {
            removed_[side] = t;
            opposite[side] = tri[(k + 2 - side) % 3];
          }
        }
        if (!movable_[w] || removed_[0] == kNone || removed_[1] == kNone ||
            incident_[opposite[0]].size() < 4 || incident_[opposite[1]].size() < 4) {
          continue;
        }
        const bool linkCondition = std::all_of(neighbours.begin(), neighbours.end(), [&](auto u) {
          return u == w || u == opposite[0] || u == opposite[1] || !edgeExists(u, w);
        });
        if (!linkCondition) continue;
        gatherBlockers(v, mesh_.vertices[w]);
        if (!keepsSide(v, mesh_.vertices[w])) continue;
        for (const std::uint32_t t : fan_) mesh_.triangles[t][cornerOf(mesh_.triangles[t], v)] = w;
        movingVertex_ = w;
        if (fanCrossesNothing()) {
          const Score s = score(false);
          if (s.max < bestScore.max || (s.max == bestScore.max && s.sum < bestScore.sum)) {
            bestScore = s;
            best = {{v, w}};
          }
        }
        for (const std::uint32_t t : fan_) mesh_.triangles[t][cornerOf(mesh_.triangles[t], w)] = v;
        movingVertex_ = v;
      }
      removed_ = {kNone, kNone};
    }
    return best;
  }

 private:
  enum class Rule { Max, Sum };
  struct Score {
    double max = 0.0, sum = 0.0;  // over the scored points; sum of (distance / diagonal)^4
    void add(double distance, double diagonal) {
      max = std::max(max, distance);
      const double r = distance / diagonal;
      sum += (r * r) * (r * r);
    }
  };

  [[nodiscard]] const Vec3& corner(std::uint32_t t, int k) const {
    return mesh_.vertices[mesh_.triangles[t][k]];
  }
  [[nodiscard]] Box3 boxOf(std::uint32_t t) const {
    return triangleBox(corner(t, 0), corner(t, 1), corner(t, 2));
  }
  [[nodiscard]] double distanceSquaredTo(const Vec3& p, std::uint32_t t) const {
    return (closestPointOnTriangle(p, corner(t, 0), corner(t, 1), corner(t, 2)) - p).squaredNorm();
  }
  static double boxDistanceSquared(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    return (p.cwiseMax(lo).cwiseMin(hi) - p).squaredNorm();
  }
  // Starts a query that visits each result triangle once (stamp_[t] == epoch_ once visited).
  void nextEpoch() {
    if (++epoch_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      epoch_ = 1;
    }
  }
  // Triangles of fan_, and those a collapse being scored removes.
  [[nodiscard]] bool inFan(std::uint32_t t) const {
    return t == removed_[0] || t == removed_[1] ||
           std::find(fan_.begin(), fan_.end(), t) != fan_.end();
  }
  void startPhase() {
    dirty_.assign(mesh_.vertices.size(), focus_.empty() ? 1 : 0);
    for (const std::uint32_t v : focus_) dirty_[v] = 1;
  }
  [[nodiscard]] Spot worstResultPoint() const {
    Spot worst{kNone, Vec3::Zero(), -1.0};
    for (std::uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (int i = 0; i <= kCheckGrid; ++i) {
        for (int j = 0; i + j <= kCheckGrid; ++j) {
          const Vec3 p =
              (i * corner(t, 0) + j * corner(t, 1) + (kCheckGrid - i - j) * corner(t, 2)) /
              kCheckGrid;
          const double d = originalBvh_.closest(p).distance;
          if (d > worst.distance) worst = {t, p, d};
        }
      }
    }
    return worst;
  }

  // Interior manifold vertices: every link edge has exactly one twin and the triangles around
  // the vertex form one ring. Only those move, and only edges between them flip.
  void findMovableVertices() {
    std::unordered_map<std::uint64_t, int> directed;
    const auto key = [](std::uint32_t a, std::uint32_t b) {
      return (static_cast<std::uint64_t>(a) << 32) | b;
    };
    for (const Triangle& t : mesh_.triangles) {
      for (int k = 0; k < 3; ++k) ++directed[key(t[k], t[(k + 1) % 3])];
    }
    const auto single = [&](std::uint32_t a, std::uint32_t b) {
      const auto it = directed.find(key(a, b));
      return it != directed.end() && it->second == 1;
    };
    movable_.assign(mesh_.vertices.size(), 0);
    for (std::uint32_t v = 0; v < mesh_.vertices.size(); ++v) {
      const std::vector<std::uint32_t>& ring = incident_[v];
      if (ring.size() < 3) continue;
      bool ok = true;
      for (const std::uint32_t t : ring) {
        const Triangle& tri = mesh_.triangles[t];
        const int k = cornerOf(tri, v);
        const std::uint32_t next = tri[(k + 1) % 3], prev = tri[(k + 2) % 3];
        ok = ok && single(v, next) && single(next, v) && single(prev, v) && single(v, prev);
      }
      if (!ok) continue;
      // Walk the ring across the edges (v, next): it must come back after every triangle.
      std::size_t steps = 0;
      std::uint32_t t = ring.front();
      do {
        const Triangle& tri = mesh_.triangles[t];
        const int k = cornerOf(tri, v);
        const std::uint32_t next = tri[(k + 1) % 3];
        std::uint32_t following = t;
        for (const std::uint32_t u : ring) {
          const Triangle& w = mesh_.triangles[u];
          for (int j = 0; j < 3; ++j) {
            if (w[j] == next && w[(j + 1) % 3] == v) following = u;
          }
        }
        t = following;
        ++steps;
      } while (t != ring.front() && steps <= ring.size());
      movable_[v] = steps == ring.size() ? 1 : 0;
    }
  }

  // Calls f(i) for each original triangle i that meets the tetrahedron, until f returns false.
  template <class F>
  void forEachOriginalMeeting(const std::array<Vec3, 4>& tet, F&& f) const {
    Vec3 lo = tet[0], hi = tet[0];
    for (const Vec3& p : tet) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    lo.array() -= 2 * gap_;
    hi.array() += 2 * gap_;
    originalBvh_.forEachTriangleOverlapping(lo, hi, [&](std::uint32_t i) {
      const Triangle& t = original_.triangles[i];
      const std::array<Vec3, 3> tri{original_.vertices[t[0]], original_.vertices[t[1]],
                                    original_.vertices[t[2]]};
      const Vec3 triLo = tri[0].cwiseMin(tri[1]).cwiseMin(tri[2]);
      const Vec3 triHi = tri[0].cwiseMax(tri[1]).cwiseMax(tri[2]);
      if ((triLo.array() > hi.array()).any() || (triHi.array() < lo.array()).any()) return true;
      return !tetrahedronMeetsTriangle(tet, tri, gap_) || f(i);
    });
  }

  // No original triangle meets the tetrahedron: changing the surface inside it keeps the side.
  [[nodiscard]] bool sweepIsFree(const std::array<Vec3, 4>& tet) const {
    bool free = true;
    forEachOriginalMeeting(tet, [&](std::uint32_t) { return free = false; });
    return free;
  }

  // The tetrahedron vertex v's move from `from` to `to` sweeps over the link edge of fan_[j].
  [[nodiscard]] std::array<Vec3, 4> sweptOver(std::size_t j, std::uint32_t v, const Vec3& from,
                                              const Vec3& to) const {
    const Triangle& tri = mesh_.triangles[fan_[j]];
    const int k = cornerOf(tri, v);
    return {mesh_.vertices[tri[(k + 1) % 3]], mesh_.vertices[tri[(k + 2) % 3]], from, to};
  }

  // The original triangles the move of v to `to` would sweep over, into blockers_: every move to
  // a point between v and `to` sweeps a part of those tetrahedra, so only these can block it.
  void gatherBlockers(std::uint32_t v, const Vec3& to) {
    blockers_.clear();
    const Vec3 from = mesh_.vertices[v];
    for (std::size_t j = 0; j < fan_.size(); ++j) {
      forEachOriginalMeeting(sweptOver(j, v, from, to), [&](std::uint32_t i) {
        blockers_.push_back({static_cast<std::uint32_t>(j), i});
        return true;
      });
    }
  }

  // The triangles of fan_ (at the current positions) cross neither each other nor the rest.
  [[nodiscard]] bool fanCrossesNothing() {
    for (std::size_t i = 0; i < fan_.size(); ++i) {
      const std::uint32_t t = fan_[i];
      const std::array<Vec3, 3> a{corner(t, 0), corner(t, 1), corner(t, 2)};
      for (std::size_t j = i + 1; j < fan_.size(); ++j) {
        const std::uint32_t u = fan_[j];
        if (meshTrianglesIntersect(a, mesh_.triangles[t],
                                   {corner(u, 0), corner(u, 1), corner(u, 2)},
                                   mesh_.triangles[u])) {
          return false;
        }
      }
      nextEpoch();
      bool crosses = false;
      grid_.forEachNear(boxOf(t), [&](std::uint32_t u) {
        if (crosses || stamp_[u] == epoch_ || inFan(u)) return;
        stamp_[u] = epoch_;
        crosses = meshTrianglesIntersect(
            a, mesh_.triangles[t], {corner(u, 0), corner(u, 1), corner(u, 2)}, mesh_.triangles[u]);
      });
      if (crosses) return false;
    }
    return true;
  }

  // Moving vertex v (whose triangles are fan_) to `to` keeps every guarantee; `to` must lie
  // between v and the point blockers_ were gathered for.
  [[nodiscard]] bool canMove(std::uint32_t v, const Vec3& to) {
    if (!keepsSide(v, to)) return false;
    const Vec3 from = mesh_.vertices[v];
    mesh_.vertices[v] = to;
    const bool ok = fanCrossesNothing();
    mesh_.vertices[v] = from;
    return ok;
  }

  // Moving vertex v to `to` flips and degenerates none of fan_'s triangles and sweeps over none
  // of blockers_.
  [[nodiscard]] bool keepsSide(std::uint32_t v, const Vec3& to) const {
    const Vec3 from = mesh_.vertices[v];
    for (const std::uint32_t t : fan_) {
      const Triangle& tri = mesh_.triangles[t];
      const int k = cornerOf(tri, v);
      const Vec3& a = mesh_.vertices[tri[(k + 1) % 3]];
      const Vec3& b = mesh_.vertices[tri[(k + 2) % 3]];
      const Vec3 before = (a - from).cross(b - from), after = (a - to).cross(b - to);
      const double longest =
          std::max({(a - to).squaredNorm(), (b - to).squaredNorm(), (a - b).squaredNorm()});
      if (!(before.dot(after) > 0.0) || after.norm() < 1e-6 * longest) return false;
    }
    for (const auto& [j, i] : blockers_) {
      const Triangle& t = original_.triangles[i];
      if (tetrahedronMeetsTriangle(
              sweptOver(j, v, from, to),
              {original_.vertices[t[0]], original_.vertices[t[1]], original_.vertices[t[2]]},
              gap_)) {
        return false;
      }
    }
    return true;
  }

  // The original samples within the worst sample distance of the box [lo, hi], where every
  // change scored next happens: those a change can move (nearest to fan_, or farther from the
  // result than from the box) go to affected_, with what is known of their distance to the rest
  // of the mesh in rest_; the others add a constant to every score, as do fixedPoints_.
  void gatherAffected(Vec3 lo, Vec3 hi) {
    const Vec3 reachLo = lo, reachHi = hi;
    lo.array() -= worstSample_;
    hi.array() += worstSample_;
    affected_.clear();
    rest_.clear();
    restNearest_.clear();
    unaffected_ = Score{};
    sampleGrid_.forEachIn(lo, hi, [&](std::uint32_t i) {
      const double d = distance_[i];
      if (inFan(nearest_[i])) {
        affected_.push_back(i);
        rest_.push_back(d);  // a lower bound until searched (it was nearest to the fan)
        restNearest_.push_back(kNone);
      } else if (boxDistanceSquared(samples_[i], reachLo, reachHi) < d * d) {
        affected_.push_back(i);
        rest_.push_back(d);
        restNearest_.push_back(nearest_[i]);
      } else {
        unaffected_.add(d, diagonal_);
      }
    });
    for (const Vec3& p : fixedPoints_) unaffected_.add(originalBvh_.closest(p).distance, diagonal_);
  }

  // Distance from p to the nearest result triangle outside fan_, which goes to `nearest`
  // (infinite and kNone when there is none), searching boxes of growing size from `guess`.
  double distanceToRest(const Vec3& p, double guess, std::uint32_t& nearest) {
    double best = INFINITY;  // squared
    const auto visit = [&](std::uint32_t u) {
      if (stamp_[u] == epoch_ || inFan(u)) return;
      stamp_[u] = epoch_;
      if (boxDistanceSquared(p, boxes_[u].lo.cast<double>(), boxes_[u].hi.cast<double>()) < best) {
        const double d = distanceSquaredTo(p, u);
        if (d < best) {
          best = d;
          nearest = u;
        }
      }
    };
    const double triangles = static_cast<double>(mesh_.triangles.size());
    for (double reach = std::max(guess, cellSize_);; reach *= 2.0) {
      nextEpoch();
      if (std::pow(2.0 * reach / cellSize_ + 1.0, 3) > triangles) {  // cheaper to scan them all
        for (std::uint32_t u = 0; u < mesh_.triangles.size(); ++u) visit(u);
        return std::sqrt(best);
      }
      const Vec3 margin = Vec3::Constant(reach + 1e-6 * diagonal_);  // covers float rounding
      grid_.forEachNear({(p - margin).cast<float>(), (p + margin).cast<float>()}, visit);
      if (best <= reach * reach) return std::sqrt(best);  // nothing outside the box is nearer
    }
  }

  // Points that score the fan: its centroids, plus the moving vertex and its spoke midpoints
  // (vertex moves) or the flipped edge's midpoint (flips), into movingPoints_. fixedPoints_
  // (set before gatherAffected) holds the rest: link vertices and link edge midpoints.
  void collectMovingPoints() {
    movingPoints_.clear();
    for (const std::uint32_t t : fan_) {
      movingPoints_.push_back((corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0);
    }
    if (movingVertex_ != kNone) {
      const Vec3& p = mesh_.vertices[movingVertex_];
      movingPoints_.push_back(p);
      for (const std::uint32_t t : fan_) {
        const Triangle& tri = mesh_.triangles[t];
        const int k = cornerOf(tri, movingVertex_);
        movingPoints_.push_back(0.5 * (p + mesh_.vertices[tri[(k + 1) % 3]]));
      }
    } else {
      movingPoints_.push_back(0.5 * (mesh_.vertices[flipped_[0]] + mesh_.vertices[flipped_[1]]));
    }
  }

  void fanBounds(Vec3& lo, Vec3& hi) const {
    lo = hi = corner(fan_.front(), 0);
    for (const std::uint32_t t : fan_) {
      for (int k = 0; k < 3; ++k) {
        lo = lo.cwiseMin(corner(t, k));
        hi = hi.cwiseMax(corner(t, k));
      }
    }
  }

  // Scores fan_ at the current positions: its own points' distances to the original and the
  // affected samples' distances to the result. `commit` stores the samples' new distances.
  Score score(bool commit) {
    Score s = unaffected_;
    const auto add = [&](double d) { s.add(d, diagonal_); };
    collectMovingPoints();
    for (const Vec3& p : movingPoints_) add(originalBvh_.closest(p).distance);
    Vec3 lo, hi;
    fanBounds(lo, hi);
    fanLo_.clear();
    fanHi_.clear();
    for (const std::uint32_t t : fan_) {
      fanLo_.push_back(corner(t, 0).cwiseMin(corner(t, 1)).cwiseMin(corner(t, 2)));
      fanHi_.push_back(corner(t, 0).cwiseMax(corner(t, 1)).cwiseMax(corner(t, 2)));
    }
    for (std::size_t j = 0; j < affected_.size(); ++j) {
      const std::uint32_t i = affected_[j];
      const Vec3& p = samples_[i];
      const bool searched = restNearest_[j] != kNone;
      double best = searched ? rest_[j] * rest_[j] : INFINITY;  // squared
      std::uint32_t nearest = restNearest_[j];
      if (boxDistanceSquared(p, lo, hi) < best) {
        for (std::size_t f = 0; f < fan_.size(); ++f) {
          if (boxDistanceSquared(p, fanLo_[f], fanHi_[f]) >= best) continue;
          const double d = distanceSquaredTo(p, fan_[f]);
          if (d < best) {
            best = d;
            nearest = fan_[f];
          }
        }
      }
      // The fan no closer than the rest's lower bound: the rest may be nearer, search it once.
      if (!searched && best > rest_[j] * rest_[j]) {
        rest_[j] = distanceToRest(p, rest_[j], restNearest_[j]);
        if (rest_[j] * rest_[j] <= best) {
          best = rest_[j] * rest_[j];
          nearest = restNearest_[j];
        }
      }
      best = std::sqrt(best);
      if (commit) {
        distance_[i] = best;
        nearest_[i] = nearest;
      }
      add(best);
    }
    return s;
  }

  [[nodiscard]] bool better(Rule rule, const Score& candidate, const Score& base,
                            const Score& best) const {
    if (rule == Rule::Max) return candidate.max < best.max - 1e-12 * diagonal_;
    return candidate.max <= base.max && candidate.sum < best.sum * (1.0 - 1e-12);
  }

  // Re-registers the triangles of fan_ in the grid at their current boxes.
  void refreshFanBoxes() {
    for (const std::uint32_t t : fan_) {
      const Box3 box = boxOf(t);
      grid_.move(t, boxes_[t], box);
      boxes_[t] = box;
    }
  }

  // A change next to a vertex makes it worth another look, in this sweep and the next.
  void markChangedAround(std::uint32_t v) {
    for (const std::uint32_t t : incident_[v]) {
      for (const std::uint32_t w : mesh_.triangles[t]) dirty_[w] = changedNear_[w] = 1;
    }
  }

  // Move directions for the vertex at `from` whose fan_ spans [lo, hi], into directions_:
  // towards the original's closest point, towards the worst sample this fan is nearest to,
  // towards the original from the fan's worst point, and along the fan normal; and the first two
  // tilted by 45° four ways, tried when those are blocked early.
  void collectDirections(const Vec3& from, const Vec3& lo, const Vec3& hi) {
    directions_.clear();
    directions_.push_back({originalBvh_.closest(from).point - from});
    double worst = 0.0;
    Vec3 towardsWorst = Vec3::Zero();
    const Vec3 slack = Vec3::Constant(worstSample_);
    sampleGrid_.forEachIn(lo - slack, hi + slack, [&](std::uint32_t i) {
      if (inFan(nearest_[i]) && distance_[i] > worst) {
        worst = distance_[i];
        towardsWorst = samples_[i] - from;
      }
    });
    directions_.push_back({towardsWorst});
    double worstOwn = -1.0;
    Vec3 ownStep = Vec3::Zero(), normal = Vec3::Zero();
    for (const std::uint32_t t : fan_) {
      normal += (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
      for (const auto& w : kTrianglePoints) {
        const Vec3 p = w[0] * corner(t, 0) + w[1] * corner(t, 1) + w[2] * corner(t, 2);
        const TriangleBvh::Closest c = originalBvh_.closest(p);
        if (c.distance > worstOwn) {
          worstOwn = c.distance;
          ownStep = c.point - p;
        }
      }
    }
    directions_.push_back({ownStep});
    if (normal.norm() > 0.0) {
      const double reach = 0.5 * (hi - lo).norm();
      directions_.push_back({-normal.normalized() * reach});
      directions_.push_back({normal.normalized() * (0.5 * reach)});
    }
    for (int parent = 0; parent < 2; ++parent) {
      const Vec3 d = directions_[parent].step;
      if (!(d.squaredNorm() > 0.0)) continue;
      const Vec3 side = d.unitOrthogonal() * d.norm(), up = d.normalized().cross(side);
      for (const Vec3& t : {side, up, Vec3(-side), Vec3(-up)})
        directions_.push_back({d + t, parent});
    }
  }

  // Sets up scoring the moves of vertex v: its link vertices and link edge midpoints, which no
  // move changes, into fixedPoints_.
  void collectStarPoints(std::uint32_t v) {
    movingVertex_ = v;
    fixedPoints_.clear();
    for (const std::uint32_t t : fan_) {
      const Triangle& tri = mesh_.triangles[t];
      const int k = cornerOf(tri, v);
      const Vec3& next = mesh_.vertices[tri[(k + 1) % 3]];
      fixedPoints_.push_back(next);
      fixedPoints_.push_back(0.5 * (next + mesh_.vertices[tri[(k + 2) % 3]]));
    }
  }

  // One sweep of vertex moves; reports the fraction of the vertices tried now and then.
  template <class Report>
  std::size_t moveVertices(Rule rule, Report&& report) {
    std::size_t moves = 0;
    for (std::uint32_t v = 0; v < mesh_.vertices.size(); ++v) {
      if (v % 256 == 0) report(static_cast<double>(v) / static_cast<double>(mesh_.vertices.size()));
      if (!movable_[v] || !dirty_[v]) continue;
      fan_ = incident_[v];
      const Vec3 from = mesh_.vertices[v];
      Vec3 lo, hi;
      fanBounds(lo, hi);
      collectDirections(from, lo, hi);
      Vec3 reachLo = lo, reachHi = hi;
      for (const Direction& d : directions_) {
        reachLo = reachLo.cwiseMin(from + d.step);
        reachHi = reachHi.cwiseMax(from + d.step);
      }
      collectStarPoints(v);
      gatherAffected(reachLo, reachHi);
      const Score base = score(false);
      Score best = base;
      Vec3 bestPosition = from;
      for (Direction& d : directions_) {
        if (!(d.step.squaredNorm() > 0.0)) continue;
        if (d.parent >= 0 && directions_[d.parent].feasible >= kTiltBelow) continue;
        double infeasible = 1.0;
        gatherBlockers(v, from + d.step);
        for (int k = 0; k < kBisections; ++k) {
          const double mid = 0.5 * (d.feasible + infeasible);
          (canMove(v, from + mid * d.step) ? d.feasible : infeasible) = mid;
        }
        if (d.feasible == 0.0) continue;
        for (const double fraction : {1.0, 0.5, 0.25}) {
          const Vec3 to = from + fraction * d.feasible * d.step;
          if (fraction != 1.0 && !canMove(v, to)) continue;
          mesh_.vertices[v] = to;
          const Score s = score(false);
          mesh_.vertices[v] = from;
          if (better(rule, s, base, best)) {
            best = s;
            bestPosition = to;
          }
        }
      }
      if (bestPosition != from) {
        mesh_.vertices[v] = bestPosition;
        score(true);
        refreshFanBoxes();
        markChangedAround(v);
        ++moves;
      }
    }
    return moves;
  }

  // The triangle other than t with the directed edge (b, a), or kNone.
  [[nodiscard]] std::uint32_t twinOf(std::uint32_t t, std::uint32_t a, std::uint32_t b,
                                     std::uint32_t& opposite) const {
    for (const std::uint32_t u : incident_[a]) {
      if (u == t) continue;
      const Triangle& w = mesh_.triangles[u];
      for (int j = 0; j < 3; ++j) {
        if (w[j] == b && w[(j + 1) % 3] == a) {
          opposite = w[(j + 2) % 3];
          return u;
        }
      }
    }
    return kNone;
  }

  [[nodiscard]] bool edgeExists(std::uint32_t c, std::uint32_t d) const {
    for (const std::uint32_t t : incident_[c]) {
      const Triangle& w = mesh_.triangles[t];
      if (w[0] == d || w[1] == d || w[2] == d) return true;
    }
    return false;
  }

  // Flips edge (a, b) of triangles t = (a, b, c) and u = (b, a, d) to (c, d) when that keeps
  // every guarantee and scores better.
  bool tryFlip(Rule rule, std::uint32_t t, int k) {
    const Triangle tri = mesh_.triangles[t];
    const std::uint32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    std::uint32_t d = kNone;
    const std::uint32_t u = twinOf(t, a, b, d);
    if (u == kNone || d == c) return false;
    if (!movable_[a] || !movable_[b] || !movable_[c] || !movable_[d] || edgeExists(c, d) ||
        !(dirty_[a] || dirty_[b] || dirty_[c] || dirty_[d])) {
      return false;
    }
    const Vec3 &A = mesh_.vertices[a], &B = mesh_.vertices[b];
    const Vec3 &C = mesh_.vertices[c], &D = mesh_.vertices[d];
    const Vec3 first = (D - A).cross(C - A), second = (B - D).cross(C - D);  // (a,d,c), (d,b,c)
    const Vec3 before = (B - A).cross(C - A) + (A - B).cross(D - B);
    const double longest =
        std::max({(A - B).squaredNorm(), (C - D).squaredNorm(), (A - C).squaredNorm(),
                  (B - D).squaredNorm(), (A - D).squaredNorm(), (B - C).squaredNorm()});
    if (first.norm() < 1e-6 * longest || second.norm() < 1e-6 * longest ||
        !(first.dot(before) > 0.0) || !(second.dot(before) > 0.0) || !(first.dot(second) > 0.0)) {
      return false;
    }
    if (!sweepIsFree({A, B, C, D})) return false;
    fan_.assign({t, u});
    movingVertex_ = kNone;
    fixedPoints_.assign({A, B, C, D, 0.5 * (A + C), 0.5 * (B + C), 0.5 * (A + D), 0.5 * (B + D)});
    Vec3 lo = A.cwiseMin(B).cwiseMin(C).cwiseMin(D), hi = A.cwiseMax(B).cwiseMax(C).cwiseMax(D);
    gatherAffected(lo, hi);
    flipped_ = {a, b};
    const Score base = score(false);
    const Triangle oldU = mesh_.triangles[u];
    mesh_.triangles[t] = {a, d, c};
    mesh_.triangles[u] = {d, b, c};
    flipped_ = {c, d};
    if (!fanCrossesNothing() || !better(rule, score(false), base, base)) {
      mesh_.triangles[t] = tri;
      mesh_.triangles[u] = oldU;
      return false;
    }
    score(true);
    refreshFanBoxes();
    const auto drop = [&](std::uint32_t v, std::uint32_t x) {
      std::vector<std::uint32_t>& ring = incident_[v];
      ring.erase(std::find(ring.begin(), ring.end(), x));
    };
    drop(a, u);
    drop(b, t);
    incident_[c].push_back(u);
    incident_[d].push_back(t);
    for (const std::uint32_t w : {a, b, c, d}) markChangedAround(w);
    return true;
  }

  std::size_t flipEdges(Rule rule) {
    std::size_t flips = 0;
    for (std::uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        if (tryFlip(rule, t, k)) {
          ++flips;
          break;  // t changed; its other edges wait for the next sweep
        }
      }
    }
    return flips;
  }

  const TriangleMesh& original_;
  TriangleMesh& mesh_;
  const PolishOptions& options_;
  TriangleBvh originalBvh_;
  double diagonal_, gap_;
  std::vector<Vec3> samples_;
  double cellSize_;
  PointGrid sampleGrid_;
  TriangleGrid grid_;
  std::vector<double> distance_;        // per sample: distance to the result
  std::vector<std::uint32_t> nearest_;  // per sample: a nearest result triangle
  std::vector<std::vector<std::uint32_t>> incident_;
  std::vector<Box3> boxes_;  // per result triangle: its box in grid_
  std::vector<char> movable_;
  // Per vertex: something changed around it since it was last looked at (this sweep's list) or
  // during this sweep (the next one's). A phase starts with every vertex listed.
  std::vector<char> dirty_, changedNear_;
  std::vector<std::uint32_t> stamp_;  // per result triangle: last query that visited it
  std::uint32_t epoch_ = 0;
  double worstSample_ = 0.0;  // largest sample distance at the start of the sweep
  std::vector<std::uint32_t> focus_;
  std::vector<std::uint32_t> fan_, affected_;
  std::array<std::uint32_t, 2> removed_{kNone, kNone};  // see inFan
  // Per affected sample: distance to the triangles outside fan_ and the nearest of them; for a
  // sample nearest to the fan, its old distance (a lower bound) and kNone until searched.
  std::vector<double> rest_;
  std::vector<std::uint32_t> restNearest_;
  std::vector<Vec3> fixedPoints_, movingPoints_;  // see collectMovingPoints
  std::uint32_t movingVertex_ = kNone;            // the vertex being moved; kNone for a flip
  std::array<std::uint32_t, 2> flipped_{};        // a flip's edge, before or after it
  Score unaffected_;  // the samples gatherAffected found but left out of affected_
  struct Direction {
    Vec3 step;
    int parent = -1;        // a tilted direction: the index of the one it tilts
    double feasible = 0.0;  // largest valid fraction of `step` found
  };
  std::vector<Direction> directions_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> blockers_;  // (fan index, original triangle)
  std::vector<Vec3> fanLo_, fanHi_;                                // boxes of fan_'s triangles
  PolishStats stats_;
};

// Splits triangle `spot.triangle` at `spot.point` (kept away from its edges) into three; returns
// the new vertex and the triangle's corners.
std::vector<std::uint32_t> splitAt(TriangleMesh& mesh, const Spot& spot) {
  const Triangle t = mesh.triangles[spot.triangle];
  const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
  const Vec3 n = (b - a).cross(c - a);
  Eigen::Array3d w((c - b).cross(spot.point - b).dot(n), (a - c).cross(spot.point - c).dot(n),
                   (b - a).cross(spot.point - a).dot(n));
  w = (w / n.squaredNorm()).max(kSplitMargin);
  w /= w.sum();
  const auto v = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back(w[0] * a + w[1] * b + w[2] * c);
  mesh.triangles[spot.triangle] = {t[0], t[1], v};
  mesh.triangles.push_back({t[1], t[2], v});
  mesh.triangles.push_back({t[2], t[0], v});
  return {v, t[0], t[1], t[2]};
}

// Collapses vertex v into its neighbour w (the two triangles on edge (v, w) go; v's slot takes
// the last vertex); returns w's index afterwards and its neighbours.
std::vector<std::uint32_t> collapseInto(TriangleMesh& mesh, std::uint32_t v, std::uint32_t w) {
  std::erase_if(mesh.triangles, [&](const Triangle& t) {
    return std::find(t.begin(), t.end(), v) != t.end() &&
           std::find(t.begin(), t.end(), w) != t.end();
  });
  const auto last = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
  for (Triangle& t : mesh.triangles) {
    for (std::uint32_t& x : t) {
      if (x == v) x = w;
    }
  }
  if (w == last) w = v;
  mesh.vertices[v] = mesh.vertices[last];
  mesh.vertices.pop_back();
  std::vector<std::uint32_t> around{w};
  for (Triangle& t : mesh.triangles) {
    for (std::uint32_t& x : t) {
      if (x == last) x = v;
    }
    if (std::find(t.begin(), t.end(), w) != t.end())
      around.insert(around.end(), t.begin(), t.end());
  }
  return around;
}

}  // namespace

PolishStats polishBoundingMesh(const TriangleMesh& original, TriangleMesh& result,
                               const PolishOptions& options) {
  if (original.triangles.empty() || result.triangles.empty()) return {};
  const auto begin = std::chrono::steady_clock::now();
  const double share = options.relocations > 0 ? 0.7 : 1.0;  // of the progress, for the sweeps
  PolishOptions sweeps = options;
  sweeps.progress = nullptr;
  if (options.progress) sweeps.progress = [&](double f) { options.progress(share * f); };
  PolishStats stats;
  std::array<Spot, 2> worst;  // their distances are the current maxima
  {
    Polisher polisher(original, result, sweeps);
    stats = polisher.run();
    worst = polisher.worstSpots();
  }
  // Relocations: a vertex goes from where the surfaces are closest to where they are farthest.
  sweeps.progress = nullptr;
  const double gain = 1e-12 * boundingBoxDiagonal(original);
  for (int r = 0; r < options.relocations; ++r) {
    if (options.progress) options.progress(share + (1.0 - share) * r / options.relocations);
    bool accepted = false;
    for (const Spot& spot : worst) {
      if (spot.triangle == kNone) continue;
      TriangleMesh candidate = result;
      std::optional<std::pair<std::uint32_t, std::uint32_t>> collapse;
      PolishStats first, second;
      {
        Polisher polisher(original, candidate, sweeps, splitAt(candidate, spot));
        first = polisher.run();
        collapse = polisher.cheapestCollapse();
      }
      if (!collapse) continue;
      Polisher polisher(original, candidate, sweeps,
                        collapseInto(candidate, collapse->first, collapse->second));
      second = polisher.run();
      const std::array<Spot, 2> now = polisher.worstSpots();
      const bool lower =
          now[0].distance < worst[0].distance - gain || now[1].distance < worst[1].distance - gain;
      if (!lower || now[0].distance > worst[0].distance || now[1].distance > worst[1].distance)
        continue;
      worst = now;
      stats.moves += first.moves + second.moves;
      stats.flips += first.flips + second.flips;
      ++stats.relocations;
      result = std::move(candidate);
      accepted = true;
      break;
    }
    if (!accepted) break;
  }
  if (options.progress) options.progress(1.0);
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return stats;
}

}  // namespace kaboum::geometry
