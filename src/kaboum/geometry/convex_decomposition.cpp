#include "kaboum/geometry/convex_decomposition.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>
#include <unordered_map>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/hole_filling.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/geometry/quick_hull.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"

namespace kaboum::geometry {
namespace {

// How ε is shared between the three steps of §4.4.2 (the distances add up by the triangle
// inequality): the outer bound of step 1, the concavity left by step 2, the growth in step 3.
constexpr double kBoundShare = 0.1;
constexpr double kConcavityShare = 0.55;
constexpr double kSimplifyShare = 0.35;
static_assert(kBoundShare + kConcavityShare + kSimplifyShare <= 1.0);

constexpr int kCutsPerAxis = 5;  // evenly spaced candidate planes per axis, plus one at the worst
                                 // concavity sample
constexpr std::size_t kSplitBeyondLimit = 3;  // split up to this many times the piece limit
// A cell whose concavity survived this many splits in a row (each keeping more than kStallRatio
// of it) is not split further: the splits are better spent elsewhere (a round pocket, say, needs
// more cuts through it than the piece limit allows).
constexpr int kMaxStalls = 8;
constexpr double kStallRatio = 0.9;
constexpr std::size_t kShortlist = 1;  // least-volume cuts whose children's concavity is measured
constexpr int kPocketNormals = 6;  // cut planes through the worst sample, turned about its depth
constexpr std::size_t kRefineNeighbours = 4;  // neighbours a re-cut of the worst piece tries

double meshVolume(const TriangleMesh& mesh) {
  double sixVolume = 0.0;
  for (const Triangle& t : mesh.triangles) {
    sixVolume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return sixVolume / 6.0;
}

// The largest distance from a piece's hull samples to the solid (0 when every sample is inside)
// and the first sample where it occurs; `complete` is false when the measurement stopped early
// because the distance reached the caller's limit (then `distance` is only a lower bound).
struct Farthest {
  double distance = 0.0;
  Vec3 where = Vec3::Zero();
  bool complete = true;
};

// The solid enclosed by the closed bound: inside tests and distances to its surface.
class Solid {
 public:
  Solid(const TriangleMesh& surface, double tolerance)
      : bvh_(surface), tolerance_(tolerance), closed_(isClosedAndOriented(surface)) {}

  // Inside, or on the surface up to the tolerance (a corner there is kept, which is harmless).
  [[nodiscard]] bool contains(const Vec3& p) const {
    return bvh_.hasTriangleWithin(p, tolerance_) || inside(p);
  }
  [[nodiscard]] Vec3 closestPoint(const Vec3& p) const { return bvh_.closest(p).point; }

  // Continues `farthest` (started at a lower bound, 0 for none) over the samples `samples` has
  // left, samples inside counting 0, until its distance reaches `stopAt` (then `complete` is
  // false and the measurement can resume with a higher limit). A sample only matters when it is
  // farther than the largest distance so far, so most samples are settled by finding one triangle
  // that close instead of the closest one; the result is bit for bit the one of a closest-point
  // query per sample.
  void largestDistance(SurfaceSampler& samples, double stopAt, Farthest& farthest) const {
    farthest.complete = farthest.distance < stopAt;
    if (!farthest.complete) return;
    for (Vec3 p; samples.next(p);) {
      if (samples.produced() == 1) farthest.where = p;
      // Beyond the largest distance so far: it counts unless it is inside (many samples on cut
      // faces are, and then need no closest point).
      if (bvh_.hasTriangleWithin(p, farthest.distance) || inside(p)) continue;
      farthest.distance = bvh_.closest(p).distance;
      farthest.where = p;
      if (farthest.distance >= stopAt) {
        farthest.complete = false;
        return;
      }
    }
  }

 private:
  static bool isClosedAndOriented(const TriangleMesh& surface) {
    const MeshAnalysis analysis = analyzeMesh(surface);
    return analysis.closed && analysis.edgeManifold && analysis.consistentlyOriented;
  }
  // One ray decides where every ray gives the same winding number, else the rays vote.
  [[nodiscard]] bool inside(const Vec3& p) const {
    return closed_ ? bvh_.containsInClosedMesh(p) : bvh_.contains(p);
  }

  TriangleBvh bvh_;
  double tolerance_;
  bool closed_;  // closed, edge-manifold and consistently oriented
};

// The part of the bound inside one convex cell of the hierarchical split: the bound's triangles
// clipped to the cell (convex polygons, stored flat) and the cell's walls and corners.
struct Cell {
  std::vector<Vec3> points;  // the distinct polygon corners (sorted by sortPoints)
  std::vector<Vec3> polygonPoints;
  std::vector<std::uint32_t> polygonEnds;  // end offset of every polygon in polygonPoints
  std::vector<HullPlane> walls;            // n.x <= d inside
  std::vector<Vec3> corners;               // cell corners inside the solid
  // A candidate's has no planes (buildCandidateHull), a kept cell's has (keepHull).
  ConvexHull hull;
  double hullVolume = 0.0;
  double concavity = 0.0;  // largest sampled distance from the hull to the solid
  Vec3 worstPoint = Vec3::Zero();
  int stalls = 0;  // splits in a row, up to this cell, that left the concavity nearly unchanged
};

bool lexicographicLess(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

void sortPoints(std::vector<Vec3>& points) {
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
}

// Where the edge pq crosses the plane (signed distances sp, sq of opposite signs), computed from
// the lexicographically smaller end so that both triangles of an edge give the same bits.
Vec3 crossing(const Vec3& p, const Vec3& q, double sp, double sq) {
  if (lexicographicLess(q, p)) return q + (p - q) * (sq / (sq - sp));
  return p + (q - p) * (sp / (sp - sq));
}

bool crosses(double sp, double sq, double tolerance) {
  return (sp < -tolerance && sq > tolerance) || (sp > tolerance && sq < -tolerance);
}

// Keeps the part of every polygon of `from` with n.x <= d + tolerance (Sutherland-Hodgman).
void clipPolygons(const Cell& from, const HullPlane& plane, double tolerance, Cell& to) {
  to.polygonPoints.clear();
  to.polygonEnds.clear();
  std::uint32_t begin = 0;
  for (const std::uint32_t end : from.polygonEnds) {
    const std::size_t before = to.polygonPoints.size();
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3& p = from.polygonPoints[i];
      const Vec3& q = from.polygonPoints[i + 1 < end ? i + 1 : begin];
      const double sp = plane.normal.dot(p) - plane.offset;
      const double sq = plane.normal.dot(q) - plane.offset;
      if (sp <= tolerance) to.polygonPoints.push_back(p);
      if (crosses(sp, sq, tolerance)) to.polygonPoints.push_back(crossing(p, q, sp, sq));
    }
    if (to.polygonPoints.size() > before) {
      to.polygonEnds.push_back(static_cast<std::uint32_t>(to.polygonPoints.size()));
    }
    begin = end;
  }
}

// The distinct corners the clipped polygons of `from` would have on the side n.x <= d +
// tolerance: its own points on that side and the crossings of its polygon edges (without
// building the polygons, which only the chosen split needs).
void clipPoints(const Cell& from, const HullPlane& plane, double tolerance, Cell& to) {
  to.points.clear();
  const auto side = [&](const Vec3& p) { return plane.normal.dot(p) - plane.offset; };
  for (const Vec3& p : from.points) {
    if (side(p) <= tolerance) to.points.push_back(p);
  }
  const auto kept = static_cast<std::ptrdiff_t>(to.points.size());
  std::uint32_t begin = 0;
  for (const std::uint32_t end : from.polygonEnds) {
    const double first = side(from.polygonPoints[begin]);
    double sp = first;  // of the edge's start, carried over from the previous edge's end
    for (std::uint32_t i = begin; i < end; ++i) {
      const bool closing = i + 1 == end;
      const Vec3& p = from.polygonPoints[i];
      const Vec3& q = from.polygonPoints[closing ? begin : i + 1];
      const double sq = closing ? first : side(q);
      if (crosses(sp, sq, tolerance)) to.points.push_back(crossing(p, q, sp, sq));
      sp = sq;
    }
    begin = end;
  }
  std::sort(to.points.begin() + kept, to.points.end(), lexicographicLess);
  std::inplace_merge(to.points.begin(), to.points.begin() + kept, to.points.end(),
                     lexicographicLess);
  to.points.erase(std::unique(to.points.begin(), to.points.end()), to.points.end());
}

// The corners of the child cell `walls` (the parent's walls and the cut, last) that lie in the
// solid: the parent's inside corners on the kept side, and the new corners where the cut meets
// two other walls. The walls include the bound's enlarged bounding box, so every cell is bounded.
std::vector<Vec3> childCorners(const std::vector<Vec3>& parentCorners,
                               const std::vector<HullPlane>& walls, const Solid& solid,
                               double tolerance) {
  const HullPlane& cut = walls.back();
  std::vector<Vec3> corners;
  for (const Vec3& c : parentCorners) {
    if (cut.normal.dot(c) <= cut.offset + tolerance) corners.push_back(c);
  }
  const std::size_t n = walls.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      Eigen::Matrix3d normals;
      normals << walls[i].normal.transpose(), walls[j].normal.transpose(), cut.normal.transpose();
      if (std::abs(normals.determinant()) < 1e-9) continue;
      const Vec3 corner =
          normals.partialPivLu().solve(Vec3(walls[i].offset, walls[j].offset, cut.offset));
      const bool feasible = std::all_of(walls.begin(), walls.end(), [&](const HullPlane& w) {
        return w.normal.dot(corner) <= w.offset + tolerance;
      });
      if (feasible && solid.contains(corner)) corners.push_back(corner);
    }
  }
  return corners;
}

// Drops points closer than `snap` to an earlier kept point; `points` are sorted by x first.
std::vector<Vec3> thinOut(const std::vector<Vec3>& points, double snap) {
  std::vector<Vec3> kept;
  for (const Vec3& p : points) {
    bool near = false;
    for (auto k = kept.rbegin(); k != kept.rend() && p.x() - k->x() <= snap && !near; ++k) {
      near = (p - *k).norm() <= snap;
    }
    if (!near) kept.push_back(p);
  }
  return kept;
}

// The points a cell's piece is the hull of: its polygon corners and its inside corners.
std::vector<Vec3> hullPoints(const Cell& cell) {
  std::vector<Vec3> points = cell.points;
  points.insert(points.end(), cell.corners.begin(), cell.corners.end());
  return points;
}

// The hull of the cell's polygons and inside corners; false when it has no volume. qhull rejects
// some inputs with points a rounding error apart (clip points next to vertices); those are
// retried without points closer than `snap` to another, which moves the hull by at most `snap`.
bool buildHull(Cell& cell, double snap) {
  std::vector<Vec3> points = hullPoints(cell);
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1) {
      sortPoints(points);
      points = thinOut(points, snap);
    }
    if (points.size() < 4) return false;
    try {
      cell.hull = convexHull(points, "piece");
      cell.hullVolume = meshVolume(cell.hull.mesh);
      return cell.hullVolume > 0.0;
    } catch (const InputError&) {
      // flat (the cell holds a sliver of the surface only) or qhull's precision check failed
    }
  }
  return false;
}

// The hull of a candidate child of a cut or of a merged pair, to rank and measure it: quickHull (a
// point within `snap` of the hull counts as inside), or buildHull where quickHull gives none. Its
// `planes` stay empty until keepHull.
bool buildCandidateHull(Cell& cell, double snap) {
  std::optional<TriangleMesh> mesh = quickHull(hullPoints(cell), snap);
  if (!mesh) return buildHull(cell, snap);
  cell.hull = ConvexHull{std::move(*mesh), {}, {}};
  cell.hullVolume = meshVolume(cell.hull.mesh);
  return cell.hullVolume > 0.0;
}

// Gives a candidate that is kept (a chosen child or an executed merge) the hull of buildHull, which
// contains every point; where qhull fails on them, the candidate hull with the planes of its
// triangles. Its concavity, measured on the candidate hull, stays: both hulls cover the same
// points up to `snap`.
void keepHull(Cell& cell, double snap) {
  if (!cell.hull.planes.empty()) return;  // built by buildHull already
  ConvexHull candidate = cell.hull;
  if (buildHull(cell, snap)) return;
  cell.hull = std::move(candidate);
  const TriangleMesh& mesh = cell.hull.mesh;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 normal = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                            .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                            .normalized();
    cell.hull.planes.push_back({normal, normal.dot(mesh.vertices[t[0]])});
  }
  cell.hullVolume = meshVolume(mesh);
}

// Lets the workers of decomposeBoundingEach that have no mesh left help the others: a worker
// hands out independent tasks (the candidate cuts of a split) and idle workers take some. Who
// runs which task does not change any result.
class WorkSharing {
 public:
  explicit WorkSharing(unsigned workers) : busy_(workers) {}

  // Runs task(i) for every i < count, on this thread and on idle workers; returns when all are
  // done (rethrowing the first exception of a task).
  void run(std::size_t count, const std::function<void(std::size_t)>& task) {
    Job job{&task, count, 0, 0, nullptr};
    std::unique_lock lock(mutex_);
    if (count == 0) return;
    jobs_.push_back(&job);
    changed_.notify_all();
    while (job.next < job.count) execute(job, lock);
    changed_.wait(lock, [&] { return job.running == 0; });
    if (job.error) std::rethrow_exception(job.error);
  }

  // Called by a worker with no mesh left: runs other workers' tasks until no worker is busy.
  void help() {
    std::unique_lock lock(mutex_);
    --busy_;
    changed_.notify_all();
    while (true) {
      changed_.wait(lock, [&] { return busy_ == 0 || !jobs_.empty(); });
      if (jobs_.empty()) return;
      execute(*jobs_.front(), lock);
    }
  }

 private:
  struct Job {
    const std::function<void(std::size_t)>* task;
    std::size_t count;
    std::size_t next = 0;     // the next task to hand out
    std::size_t running = 0;  // tasks handed out and not finished
    std::exception_ptr error;
  };

  // Takes the job's next task and runs it without the lock; a job whose last task is handed out
  // leaves the list (its owner waits for the running ones).
  void execute(Job& job, std::unique_lock<std::mutex>& lock) {
    const std::size_t i = job.next++;
    if (job.next == job.count) jobs_.erase(std::find(jobs_.begin(), jobs_.end(), &job));
    ++job.running;
    lock.unlock();
    std::exception_ptr error;
    try {
      (*job.task)(i);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !job.error) job.error = error;
    --job.running;
    changed_.notify_all();
  }

  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Job*> jobs_;  // jobs with tasks left to hand out
  unsigned busy_;           // workers still decomposing a mesh
};

// Runs task(i) for every i < count, with idle workers' help when `sharing` is given.
void runTasks(WorkSharing* sharing, std::size_t count,
              const std::function<void(std::size_t)>& task) {
  if (sharing != nullptr) {
    sharing->run(count, task);
    return;
  }
  for (std::size_t i = 0; i < count; ++i) task(i);
}

struct Context {
  WorkSharing* sharing;  // nothing when decomposing one mesh alone
  const Solid& solid;
  double tolerance;           // geometric tolerance, a tiny fraction of the diagonal
  double snap;                // largest distance a hull may lose points by (see buildHull)
  std::size_t samples;        // random samples per hull for its concavity
  std::size_t bridgeSamples;  // random samples on the bridge of a merged hull
  std::uint64_t seed;
};

// The seed of the random samples a measurement with `salt` draws.
std::uint64_t sampleSeed(const Context& context, std::uint64_t salt) {
  return context.seed * 1000003u + salt;
}

// The piece's concavity on samples of its hull (`salt` picks the random ones). The measurement
// stops once the concavity reaches `stopAt`; returns false then (the concavity is at least that).
bool measureConcavity(Cell& cell, const Context& context, std::uint64_t salt,
                      double stopAt = std::numeric_limits<double>::infinity()) {
  SurfaceSampler samples(cell.hull.mesh, context.samples, sampleSeed(context, salt));
  Farthest farthest;
  context.solid.largestDistance(samples, stopAt, farthest);
  cell.concavity = farthest.distance;
  cell.worstPoint = farthest.where;
  return farthest.complete;
}

// The triangles of the merged hull of pieces a and b that bridge them: those whose corners are not
// all vertices of one part (a triangle spanned by one part's vertices lies in that part's hull).
TriangleMesh bridgeTriangles(const Cell& merged, const Cell& a, const Cell& b) {
  const auto sorted = [](const Cell& c) {
    std::vector<Vec3> points = c.hull.mesh.vertices;
    std::sort(points.begin(), points.end(), lexicographicLess);
    return points;
  };
  const std::vector<Vec3> first = sorted(a), second = sorted(b);
  const auto allIn = [&](const std::vector<Vec3>& part, const Triangle& t) {
    return std::all_of(t.begin(), t.end(), [&](std::uint32_t v) {
      return std::binary_search(part.begin(), part.end(), merged.hull.mesh.vertices[v],
                                lexicographicLess);
    });
  };
  TriangleMesh bridge;
  bridge.vertices = merged.hull.mesh.vertices;
  for (const Triangle& t : merged.hull.mesh.triangles) {
    if (!allIn(first, t) && !allIn(second, t)) bridge.triangles.push_back(t);
  }
  return bridge;
}

// The measurement of the concavity of the merged hull of pieces a and b: the larger of theirs and
// of the samples of the bridge between them (every random sample goes where the merge adds
// concavity, so a narrow gap between the parts is rarely missed). It stops like measureConcavity
// and resumes where it stopped when asked again with a higher limit, which gives what measuring
// afresh would: the parts are alive pieces, whose concavities are measured and do not change.
class MergedConcavity {
 public:
  MergedConcavity(const Cell& merged, const Cell& a, const Cell& b, const Context& context,
                  std::uint64_t salt)
      : bridge_(bridgeTriangles(merged, a, b)),
        samples_(bridge_, context.bridgeSamples, sampleSeed(context, salt)) {
    farthest_.distance = std::max(a.concavity, b.concavity);
  }
  MergedConcavity(const MergedConcavity&) = delete;
  MergedConcavity& operator=(const MergedConcavity&) = delete;

  // Measures on until the concavity reaches `stopAt` and writes it to `merged`; true when complete.
  bool measure(Cell& merged, const Solid& solid, double stopAt) {
    solid.largestDistance(samples_, stopAt, farthest_);
    merged.concavity = farthest_.distance;
    merged.worstPoint = farthest_.where;
    return farthest_.complete;
  }

 private:
  TriangleMesh bridge_;
  SurfaceSampler samples_;  // on bridge_
  Farthest farthest_;
};

// The part of `parent` on the side n.x <= d of `cut` with its candidate hull, or nothing when it
// has no volume.
std::optional<Cell> childCell(const Cell& parent, const HullPlane& cut, const Context& context) {
  Cell child;
  clipPoints(parent, cut, context.tolerance, child);
  if (child.points.empty()) return std::nullopt;
  child.walls = parent.walls;
  child.walls.push_back(cut);
  child.corners = childCorners(parent.corners, child.walls, context.solid, context.tolerance);
  if (!buildCandidateHull(child, context.snap)) return std::nullopt;
  return child;
}

// Candidate cut directions: the coordinate axes and the principal axes of the hull's vertices.
std::vector<Vec3> cutAxes(const Cell& cell) {
  std::vector<Vec3> axes{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  const auto& vertices = cell.hull.mesh.vertices;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : vertices) mean += v;
  mean /= static_cast<double>(vertices.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& v : vertices) covariance += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  for (int i = 2; i >= 0; --i) {
    const Vec3 axis = solver.eigenvectors().col(i).normalized();
    const bool coordinateAxis = std::any_of(axes.begin(), axes.begin() + 3, [&](const Vec3& a) {
      return std::abs(a.dot(axis)) > 1.0 - 1e-6;
    });
    if (!coordinateAxis && axis.allFinite()) axes.push_back(axis);
  }
  return axes;
}

// Normals of planes through the cell's worst concavity sample w that contain its depth direction
// (from w to the nearest point of the solid), kPocketNormals of them evenly turned about it: one of
// them cuts the pocket or bore under w through its middle, whatever its orientation (V-HACD and
// CoACD search cut planes through the most concave points in the same spirit).
std::vector<Vec3> pocketNormals(const Cell& cell, const Solid& solid) {
  const Vec3 depth = solid.closestPoint(cell.worstPoint) - cell.worstPoint;
  if (!(depth.norm() > 0.0)) return {};
  const Vec3 d = depth.normalized();
  const Vec3 u = d.unitOrthogonal(), v = d.cross(u);
  std::vector<Vec3> normals;
  for (int k = 0; k < kPocketNormals; ++k) {
    const double angle = M_PI * k / kPocketNormals;
    normals.push_back(std::cos(angle) * u + std::sin(angle) * v);
  }
  return normals;
}

// The plane of `plane` with the other side as below.
HullPlane otherSide(const HullPlane& plane) {
  return {-plane.normal, -plane.offset};
}

// A candidate cut (its below side n.x <= d) and whether it passes through the worst sample.
struct Cut {
  HullPlane plane;
  bool throughWorst;
};

// The candidate cuts of a piece with the hull vertices and worst sample w of `cell`:
// axis-parallel and principal-axis planes at evenly spaced positions and through w (unless w is
// within 2% of the ends), and the pocket planes through w.
std::vector<Cut> candidateCuts(const Cell& cell, const Solid& solid) {
  std::vector<Cut> cuts;
  for (const Vec3& axis : cutAxes(cell)) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Vec3& v : cell.hull.mesh.vertices) {
      lo = std::min(lo, axis.dot(v));
      hi = std::max(hi, axis.dot(v));
    }
    for (int k = 1; k <= kCutsPerAxis; ++k) {
      cuts.push_back({{axis, lo + (hi - lo) * k / (kCutsPerAxis + 1)}, false});
    }
    const double worst = axis.dot(cell.worstPoint);
    if (worst > lo + 0.02 * (hi - lo) && worst < hi - 0.02 * (hi - lo)) {
      cuts.push_back({{axis, worst}, true});
    }
  }
  for (const Vec3& normal : pocketNormals(cell, solid)) {
    cuts.push_back({{normal, normal.dot(cell.worstPoint)}, true});
  }
  return cuts;
}

// A cut with the candidate pieces on its two sides.
struct Candidate {
  Cut cut;
  Cell below, above;
};

// The cut whose two pieces' larger concavity is smallest and below `bar`, among the kShortlist
// cuts with the smallest total hull volume (the hull volume beyond the solid's is what concavity
// grows with, and it is cheap to compare) and the cuts through the worst sample; nothing when none
// is below `bar`. `below(plane)` gives the candidate piece on the side n.x <= d of a plane, or
// nothing when that side has none (the cut is no candidate then); the pieces of all cuts are
// independent tasks, shared with idle workers. The chosen pieces come with their concavity
// measured (salts from `measured`).
template <typename Below>
std::optional<Candidate> chooseCandidate(const std::vector<Cut>& cuts, Below below, double bar,
                                         const Context& context, std::uint64_t& measured) {
  std::vector<std::optional<Candidate>> children(cuts.size());
  runTasks(context.sharing, cuts.size(), [&](std::size_t k) {
    auto under = below(cuts[k].plane);
    if (!under) return;
    auto over = below(otherSide(cuts[k].plane));
    if (!over) return;
    children[k] = Candidate{cuts[k], std::move(*under), std::move(*over)};
  });
  std::vector<Candidate> candidates;
  for (auto& c : children) {
    if (c) candidates.push_back(std::move(*c));
  }
  if (candidates.empty()) return std::nullopt;
  const auto volume = [](const Candidate& c) { return c.below.hullVolume + c.above.hullVolume; };
  const std::size_t shortlist = std::min(kShortlist, candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(shortlist),
                    candidates.end(),
                    [&](const auto& a, const auto& b) { return volume(a) < volume(b); });
  // The measured candidates (the shortlist and the cuts through the worst sample), each with the
  // salt of its children's samples. They are measured least total volume first, which tends to
  // set a low bar early so that the others stop sooner; the winner is the one whose larger child
  // concavity is smallest, the first in candidate order among equals, whatever the order of
  // measurement.
  struct ToMeasure {
    std::size_t index;
    std::uint64_t salt;
  };
  std::vector<ToMeasure> toMeasure;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i >= shortlist && !candidates[i].cut.throughWorst) continue;
    toMeasure.push_back({i, measured});
    measured += 2;
  }
  std::stable_sort(toMeasure.begin(), toMeasure.end(), [&](const auto& a, const auto& b) {
    return volume(candidates[a.index]) < volume(candidates[b.index]);
  });
  std::size_t best = candidates.size();
  double bestConcavity = bar;
  for (const ToMeasure& m : toMeasure) {
    Candidate& c = candidates[m.index];
    // A candidate loses as soon as one child reaches the best concavity so far (passes it, for a
    // candidate earlier in candidate order than the best, which wins a tie).
    const double stopAt =
        best < candidates.size() && m.index < best
            ? std::nextafter(bestConcavity, std::numeric_limits<double>::infinity())
            : bestConcavity;
    if (!measureConcavity(c.below, context, m.salt, stopAt) ||
        !measureConcavity(c.above, context, m.salt + 1, stopAt)) {
      continue;
    }
    bestConcavity = std::max(c.below.concavity, c.above.concavity);
    best = m.index;
  }
  if (best == candidates.size()) return std::nullopt;
  return std::move(candidates[best]);
}

// The split of `cell` chosen by chooseCandidate among its candidate cuts; nothing when no
// candidate cuts it in two (a side without volume). The children come with their concavity
// measured and their polygons clipped. They are ranked and measured on quickHull's hulls; only
// the chosen children get qhull's (keepHull).
std::optional<std::pair<Cell, Cell>> bestSplit(const Cell& cell, const Context& context,
                                               std::uint64_t& measured) {
  std::optional<Candidate> chosen = chooseCandidate(
      candidateCuts(cell, context.solid),
      [&](const HullPlane& plane) { return childCell(cell, plane, context); },
      std::numeric_limits<double>::infinity(), context, measured);
  if (!chosen) return std::nullopt;
  keepHull(chosen->below, context.snap);
  keepHull(chosen->above, context.snap);
  clipPolygons(cell, chosen->cut.plane, context.tolerance, chosen->below);
  clipPolygons(cell, otherSide(chosen->cut.plane), context.tolerance, chosen->above);
  return std::pair{std::move(chosen->below), std::move(chosen->above)};
}

// The hull of two pieces together (pieces' vertices only: cells are not needed after splitting).
std::optional<Cell> mergedCell(const Cell& a, const Cell& b, double snap) {
  Cell merged;
  merged.points = a.hull.mesh.vertices;
  merged.points.insert(merged.points.end(), b.hull.mesh.vertices.begin(),
                       b.hull.mesh.vertices.end());
  sortPoints(merged.points);
  if (!buildCandidateHull(merged, snap)) return std::nullopt;
  return merged;
}

bool boxesTouch(const Cell& a, const Cell& b, double tolerance) {
  const auto box = [](const Cell& c) {
    Eigen::AlignedBox3d result;
    for (const Vec3& v : c.hull.mesh.vertices) result.extend(v);
    return result;
  };
  Eigen::AlignedBox3d first = box(a);
  first.extend(first.min() - Vec3::Constant(tolerance))
      .extend(first.max() + Vec3::Constant(tolerance));
  return first.intersects(box(b));
}

// A piece with the leaf cells it covers (their polygons, walls and inside corners).
struct Piece {
  Cell cell;
  std::vector<Cell> region;
};

// Merging of neighbouring pieces (touching bounding boxes) down to `maxPieces`, then on while the
// merged concavity stays within `budget`. Greedy takes the pair whose merged piece has the
// smallest concavity. While at most kLookaheadWindow forced merges are left, each of the
// kLookaheadWidth cheapest pairs is scored instead by the largest concavity at the piece limit
// after completing the remaining merges greedily, and the best score wins (greedy's own pair among
// equals, so the result is never worse than greedy's by this estimate). A piece is identified by
// the leaves it covers and a state by its pieces, so every merged piece is built and measured
// once and every greedy completion followed once, however many look-aheads meet them.
// Concavities are measured lazily: a merged piece starts with its parts' larger concavity as a
// lower bound; its hull is built (by quickHull) and measured only when that bound could win, and
// the measurement stops once it passes the best pair's (or a completion's bar). An executed merge
// gets qhull's hull (keepHull).
class MergeSearch {
 public:
  MergeSearch(std::vector<Cell>& leaves, const Context& context, double tolerance,
              std::uint64_t& measured)
      : context_(context), tolerance_(tolerance), measured_(measured) {
    for (std::uint32_t i = 0; i < leaves.size(); ++i) {
      nodes_.push_back(Node{std::move(leaves[i]), {i}, kNone, kNone, 0, true, true, true, nullptr});
      byLeaves_.emplace(std::vector<std::uint32_t>{i}, i);
      alive_.push_back(i);
    }
  }

  // Merges as described above; returns the pieces left.
  std::vector<Piece> run(std::size_t maxPieces, double budget) {
    constexpr double kNoBar = std::numeric_limits<double>::infinity();
    while (alive_.size() > 1) {
      const std::size_t forcedLeft = alive_.size() > maxPieces ? alive_.size() - maxPieces : 0;
      std::optional<Choice> chosen = cheapest(alive_, {}, kNoBar);
      if (!chosen) break;
      if (forcedLeft == 0 && concavity(chosen->node) > budget) break;
      if (forcedLeft > 1 && forcedLeft <= kLookaheadWindow) chosen = lookahead(*chosen, maxPieces);
      apply(alive_, *chosen);
      keepHull(nodes_[chosen->node].cell, context_.snap);
    }
    std::vector<Piece> pieces;
    for (const std::uint32_t id : alive_) {
      Piece piece;
      for (const std::uint32_t leaf : nodes_[id].leaves) {
        // The leaves of a merged piece are needed only in its region; a leaf piece is its own.
        if (leaf == id) {
          piece.region.push_back(nodes_[leaf].cell);
        } else {
          piece.region.push_back(std::move(nodes_[leaf].cell));
        }
      }
      piece.cell = std::move(nodes_[id].cell);
      pieces.push_back(std::move(piece));
    }
    return pieces;
  }

 private:
  static constexpr std::size_t kLookaheadWindow = 6;
  static constexpr std::size_t kLookaheadWidth = 12;
  static constexpr std::uint32_t kNone = 0xffffffffu;

  // A piece: a leaf, or the hull of two pieces (`first`, `second`) covering `leaves` (sorted).
  struct Node {
    Cell cell;
    std::vector<std::uint32_t> leaves;
    std::uint32_t first, second;
    std::uint64_t salt;                            // of the bridge samples
    bool built;                                    // the hull is built
    bool usable;                                   // false when the hull has no volume
    bool exact;                                    // cell.concavity is measured, else a lower bound
    std::unique_ptr<MergedConcavity> measurement;  // while built and not exact
  };
  // A merge: the positions of its two pieces in a list of pieces and the merged piece.
  struct Choice {
    std::size_t i, j;
    std::uint32_t node;
  };
  // The largest concavity at the piece limit when greedy merging goes on from a state, or a
  // lower bound of it.
  struct Outcome {
    double concavity;
    bool exact;
  };

  [[nodiscard]] double concavity(std::uint32_t node) const { return nodes_[node].cell.concavity; }

  // The merged piece of nodes a and b (its hull not built yet), or kNone when they do not touch.
  std::uint32_t pairNode(std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    const auto [entry, inserted] = pairs_.try_emplace(key, kNone);
    if (!inserted) return entry->second;
    if (!boxesTouch(nodes_[a].cell, nodes_[b].cell, tolerance_)) return kNone;
    std::vector<std::uint32_t> leaves;
    std::merge(nodes_[a].leaves.begin(), nodes_[a].leaves.end(), nodes_[b].leaves.begin(),
               nodes_[b].leaves.end(), std::back_inserter(leaves));
    if (const auto known = byLeaves_.find(leaves); known != byLeaves_.end()) {
      return entry->second = known->second;
    }
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    Node node{Cell{}, leaves, a, b, measured_++, false, true, false, nullptr};
    node.cell.concavity = std::max(concavity(a), concavity(b));  // a lower bound
    nodes_.push_back(std::move(node));
    byLeaves_.emplace(std::move(leaves), id);
    return entry->second = id;
  }

  // Measures the merged piece until its concavity passes `limit`.
  void measure(Node& node, double limit) {
    const Cell& first = nodes_[node.first].cell;
    const Cell& second = nodes_[node.second].cell;
    if (!node.built) {
      node.built = true;
      std::optional<Cell> merged = mergedCell(first, second, context_.snap);
      if (!merged) {
        node.usable = false;
        return;
      }
      merged->concavity = node.cell.concavity;
      node.cell = std::move(*merged);
      node.measurement =
          std::make_unique<MergedConcavity>(node.cell, first, second, context_, node.salt);
    }
    node.exact = node.measurement->measure(
        node.cell, context_.solid, std::nextafter(limit, std::numeric_limits<double>::infinity()));
    if (node.exact) node.measurement.reset();
  }

  // The pair of `alive` whose merged piece has the smallest concavity (the first of equals in
  // pair order), skipping merged pieces in `excluded`; nothing when no pair can merge. When that
  // concavity is at least `bar`, a pair whose concavity (or lower bound) is at least `bar`.
  std::optional<Choice> cheapest(const std::vector<std::uint32_t>& alive,
                                 std::span<const Choice> excluded, double bar) {
    while (true) {
      std::optional<Choice> best, bound;
      for (std::size_t i = 0; i < alive.size(); ++i) {
        for (std::size_t j = i + 1; j < alive.size(); ++j) {
          const std::uint32_t id = pairNode(alive[i], alive[j]);
          if (id == kNone || !nodes_[id].usable ||
              std::any_of(excluded.begin(), excluded.end(),
                          [&](const Choice& c) { return c.node == id; })) {
            continue;
          }
          std::optional<Choice>& current = nodes_[id].exact ? best : bound;
          if (!current || concavity(id) < concavity(current->node)) current = Choice{i, j, id};
        }
      }
      const double limit =
          std::min(best ? concavity(best->node) : std::numeric_limits<double>::infinity(), bar);
      if (!bound || concavity(bound->node) > limit) return best ? best : bound;
      measure(nodes_[bound->node], limit);
    }
  }

  static void apply(std::vector<std::uint32_t>& alive, const Choice& choice) {
    alive[choice.i] = choice.node;
    alive.erase(alive.begin() + static_cast<std::ptrdiff_t>(choice.j));
  }

  // The largest concavity at the piece limit after `choice` and greedy merges, or infinity when
  // it is at least `bar` (no better than a score already found).
  double completion(Choice choice, std::size_t maxPieces, double bar) {
    constexpr double kAbove = std::numeric_limits<double>::infinity();
    std::vector<std::uint32_t> alive = alive_;
    std::vector<std::vector<std::uint32_t>> path;  // the states passed
    std::optional<double> result;
    while (concavity(choice.node) < bar) {
      apply(alive, choice);
      std::vector<std::uint32_t> state = alive;
      std::sort(state.begin(), state.end());
      if (const auto known = outcomes_.find(state); known != outcomes_.end()) {
        if (known->second.exact) result = known->second.concavity;
        if (result || known->second.concavity >= bar) break;
      }
      path.push_back(std::move(state));
      const std::optional<Choice> next =
          alive.size() > maxPieces ? cheapest(alive, {}, bar) : std::nullopt;
      if (!next) {
        result = 0.0;
        for (const std::uint32_t id : alive) *result = std::max(*result, concavity(id));
        break;
      }
      choice = *next;
    }
    for (auto& state : path) {
      Outcome& outcome = outcomes_.try_emplace(std::move(state), Outcome{0.0, false}).first->second;
      if (result) {
        outcome = {*result, true};
      } else if (!outcome.exact) {
        outcome.concavity = std::max(outcome.concavity, bar);
      }
    }
    return result && *result < bar ? *result : kAbove;
  }

  // Among the kLookaheadWidth cheapest pairs (`greedy` first), the one with the best completion.
  Choice lookahead(const Choice& greedy, std::size_t maxPieces) {
    std::vector<Choice> candidates{greedy};
    while (candidates.size() < kLookaheadWidth) {
      const std::optional<Choice> next =
          cheapest(alive_, candidates, std::numeric_limits<double>::infinity());
      if (!next) break;
      candidates.push_back(*next);
    }
    Choice best = greedy;
    double bestScore = completion(greedy, maxPieces, std::numeric_limits<double>::infinity());
    for (std::size_t k = 1; k < candidates.size(); ++k) {
      const double score = completion(candidates[k], maxPieces, bestScore);
      if (score < bestScore) {
        bestScore = score;
        best = candidates[k];
      }
    }
    return best;
  }

  const Context& context_;
  double tolerance_;
  std::uint64_t& measured_;
  std::deque<Node> nodes_;  // stable references while new pieces are added
  std::map<std::vector<std::uint32_t>, std::uint32_t> byLeaves_;
  std::unordered_map<std::uint64_t, std::uint32_t> pairs_;  // (smaller, larger id) -> merged
  std::map<std::vector<std::uint32_t>, Outcome> outcomes_;  // by a state's sorted pieces
  std::vector<std::uint32_t> alive_;                        // the current pieces, in leaf order
};

// The part of a region on the side n.x <= d of `cut`: every cell clipped to it (its polygons only
// when `polygons`), cells left with neither surface nor inside corners dropped.
std::vector<Cell> clipRegion(const std::vector<Cell>& region, const HullPlane& cut,
                             const Context& context, bool polygons) {
  std::vector<Cell> clipped;
  const auto side = [&](const Vec3& p) { return cut.normal.dot(p) - cut.offset; };
  for (const Cell& cell : region) {
    // A cell whose surface and inside corners all lie clearly on one side is not crossed where it
    // holds solid: it stays whole on that side (the cut adds no corner in the solid) and is left
    // out on the other.
    const auto clearly = [&](auto test) {
      return std::all_of(cell.points.begin(), cell.points.end(), test) &&
             std::all_of(cell.corners.begin(), cell.corners.end(), test);
    };
    if (clearly([&](const Vec3& p) { return side(p) > context.tolerance; })) continue;
    if (clearly([&](const Vec3& p) { return side(p) < -context.tolerance; })) {
      clipped.push_back(cell);
      continue;
    }
    Cell child;
    clipPoints(cell, cut, context.tolerance, child);
    child.walls = cell.walls;
    child.walls.push_back(cut);
    child.corners = childCorners(cell.corners, child.walls, context.solid, context.tolerance);
    if (child.points.empty() && child.corners.empty()) continue;
    if (polygons) {
      clipPolygons(cell, cut, context.tolerance, child);
      if (!buildCandidateHull(child, context.snap)) child.hull = {};
    }
    clipped.push_back(std::move(child));
  }
  return clipped;
}

// The candidate hull of a region's points: its cells' hull vertices, or for a cell without a hull
// its polygon corners and inside corners.
std::optional<Cell> regionHull(const std::vector<Cell>& region, const Context& context) {
  Cell hull;
  for (const Cell& cell : region) {
    const std::vector<Vec3>& vertices = cell.hull.mesh.vertices;
    if (!vertices.empty()) {
      hull.points.insert(hull.points.end(), vertices.begin(), vertices.end());
      continue;
    }
    hull.points.insert(hull.points.end(), cell.points.begin(), cell.points.end());
    hull.points.insert(hull.points.end(), cell.corners.begin(), cell.corners.end());
  }
  sortPoints(hull.points);
  if (!buildCandidateHull(hull, context.snap)) return std::nullopt;
  return hull;
}

// The cut of a region chosen by chooseCandidate among the candidate cuts of the hull `vertices`
// with the worst sample `worstPoint`, with its parts' larger concavity; nothing when none is below
// `bar`.
std::optional<std::pair<HullPlane, double>> bestRegionCut(const std::vector<Cell>& region,
                                                          const std::vector<Vec3>& vertices,
                                                          const Vec3& worstPoint, double bar,
                                                          const Context& context,
                                                          std::uint64_t& measured) {
  Cell shape;
  shape.hull.mesh.vertices = vertices;
  shape.worstPoint = worstPoint;
  const std::optional<Candidate> chosen = chooseCandidate(
      candidateCuts(shape, context.solid),
      [&](const HullPlane& plane) {
        return regionHull(clipRegion(region, plane, context, false), context);
      },
      bar, context, measured);
  if (!chosen) return std::nullopt;
  return std::pair{chosen->cut.plane, std::max(chosen->below.concavity, chosen->above.concavity)};
}

// The two pieces `cut` makes of a region, measured again on more samples; nothing unless both are
// below `bar`.
std::optional<std::pair<Piece, Piece>> cutPieces(const std::vector<Cell>& region,
                                                 const HullPlane& cut, double bar,
                                                 const Context& context, std::uint64_t& measured) {
  Piece below, above;
  below.region = clipRegion(region, cut, context, true);
  above.region = clipRegion(region, otherSide(cut), context, true);
  auto belowHull = regionHull(below.region, context);
  auto aboveHull = regionHull(above.region, context);
  if (!belowHull || !aboveHull) return std::nullopt;
  below.cell = std::move(*belowHull);
  above.cell = std::move(*aboveHull);
  Context thorough = context;
  thorough.samples = context.bridgeSamples;
  const std::uint64_t salt = measured;
  measured += 2;
  if (!measureConcavity(below.cell, thorough, salt, bar) ||
      !measureConcavity(above.cell, thorough, salt + 1, bar)) {
    return std::nullopt;
  }
  keepHull(below.cell, context.snap);
  keepHull(above.cell, context.snap);
  return std::pair{std::move(below), std::move(above)};
}

std::vector<Cell> joinedRegion(const Piece& a, const Piece& b) {
  std::vector<Cell> region = a.region;
  region.insert(region.end(), b.region.begin(), b.region.end());
  return region;
}

std::vector<Vec3> joinedVertices(const Piece& a, const Piece& b) {
  std::vector<Vec3> vertices = a.cell.hull.mesh.vertices;
  vertices.insert(vertices.end(), b.cell.hull.mesh.vertices.begin(),
                  b.cell.hull.mesh.vertices.end());
  return vertices;
}

// The pieces touching piece `worst`, nearest its worst sample first (by how far that sample lies
// beyond their facet planes), at most kRefineNeighbours of them.
std::vector<std::size_t> nearestNeighbours(const std::vector<Piece>& pieces, std::size_t worst,
                                           double touchTolerance) {
  const Cell& cell = pieces[worst].cell;
  std::vector<std::pair<double, std::size_t>> byExcess;
  for (std::size_t q = 0; q < pieces.size(); ++q) {
    if (q == worst || !boxesTouch(cell, pieces[q].cell, touchTolerance)) continue;
    double excess = 0.0;
    for (const HullPlane& h : pieces[q].cell.hull.planes) {
      excess = std::max(excess, h.normal.dot(cell.worstPoint) - h.offset);
    }
    byExcess.emplace_back(excess, q);
  }
  std::sort(byExcess.begin(), byExcess.end());
  std::vector<std::size_t> nearest;
  for (const auto& [excess, q] : byExcess) {
    if (nearest.size() == kRefineNeighbours) break;
    nearest.push_back(q);
  }
  return nearest;
}

// The touching pair of `pieces` whose merged piece has the smallest concavity below `bar` (bridge
// measure, as in MergeSearch), with that piece; nothing when none is below `bar`.
std::optional<std::pair<std::pair<std::size_t, std::size_t>, Cell>> cheapestMergeBelow(
    const std::vector<Piece>& pieces, double bar, const Context& context, double touchTolerance,
    std::uint64_t& measured) {
  std::optional<std::pair<std::pair<std::size_t, std::size_t>, Cell>> best;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const Cell& a = pieces[i].cell;
      const Cell& b = pieces[j].cell;
      if (std::max(a.concavity, b.concavity) >= bar || !boxesTouch(a, b, touchTolerance)) continue;
      std::optional<Cell> merged = mergedCell(a, b, context.snap);
      if (!merged) continue;
      MergedConcavity measurement(*merged, a, b, context, measured++);
      if (!measurement.measure(*merged, context.solid, bar)) continue;
      bar = merged->concavity;
      best = std::pair{std::pair{i, j}, std::move(*merged)};
    }
  }
  return best;
}

// Lowers the largest concavity left by merging with two moves on the worst piece: re-cut it and a
// neighbour with one plane (the plane may cross their cells, so the border between them leaves
// the cuts of the split; the nearest neighbours are tried in turn, up to the first whose best
// cut gets below the bar), or else cut it in two and merge the cheapest touching pair instead. A
// move is kept when every piece it makes, measured again on more samples, is below the worst
// piece's concavity. Repeated until no move helps the worst piece or `rounds` moves are made;
// returns how many.
std::size_t refinePieces(std::vector<Piece>& pieces, std::size_t rounds, const Context& context,
                         double touchTolerance, std::uint64_t& measured) {
  const auto byConcavity = [](const Piece& a, const Piece& b) {
    return a.cell.concavity < b.cell.concavity;
  };
  std::size_t moves = 0;
  for (; moves < rounds; ++moves) {
    const auto worstIt = std::max_element(pieces.begin(), pieces.end(), byConcavity);
    const auto worst = static_cast<std::size_t>(worstIt - pieces.begin());
    const Piece& piece = *worstIt;
    const double bar = piece.cell.concavity;
    // Move 1: re-cut with a neighbour.
    bool moved = false;
    for (const std::size_t q : nearestNeighbours(pieces, worst, touchTolerance)) {
      const std::vector<Cell> region = joinedRegion(piece, pieces[q]);
      const auto found = bestRegionCut(region, joinedVertices(piece, pieces[q]),
                                       piece.cell.worstPoint, bar, context, measured);
      if (!found) continue;
      auto made = cutPieces(region, found->first, bar, context, measured);
      if (!made) break;
      pieces[worst] = std::move(made->first);
      pieces[q] = std::move(made->second);
      moved = true;
      break;
    }
    if (moved) continue;
    // Move 2: cut the worst piece in two, merge the cheapest touching pair.
    const auto own = bestRegionCut(piece.region, piece.cell.hull.mesh.vertices,
                                   piece.cell.worstPoint, bar, context, measured);
    if (!own) break;
    auto made = cutPieces(piece.region, own->first, bar, context, measured);
    if (!made) break;
    std::vector<Piece> next;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (i != worst) next.push_back(pieces[i]);
    }
    next.push_back(std::move(made->first));
    next.push_back(std::move(made->second));
    auto merge = cheapestMergeBelow(next, bar, context, touchTolerance, measured);
    if (!merge) break;
    const auto [i, j] = merge->first;
    Piece joined{std::move(merge->second), joinedRegion(next[i], next[j])};
    keepHull(joined.cell, context.snap);
    next[i] = std::move(joined);
    next.erase(next.begin() + static_cast<std::ptrdiff_t>(j));
    pieces = std::move(next);
  }
  return moves;
}

// Largest distance from the points to the convex piece (0 inside), exact.
double largestDistanceToConvex(const std::vector<Vec3>& points, const ConvexHull& piece) {
  double worst = 0.0;
  for (const Vec3& p : points) {
    const bool inside =
        std::all_of(piece.planes.begin(), piece.planes.end(),
                    [&](const HullPlane& h) { return h.normal.dot(p) <= h.offset; });
    if (inside) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Triangle& t : piece.mesh.triangles) {
      const Vec3 c = closestPointOnTriangle(p, piece.mesh.vertices[t[0]], piece.mesh.vertices[t[1]],
                                            piece.mesh.vertices[t[2]]);
      nearest = std::min(nearest, (c - p).norm());
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

// §4.4.2 step 3: the convex hull of an outer bounding mesh of `piece`. It contains the piece and is
// convex; as the distance to a convex set is a convex function, its largest distance to the piece
// is attained at its vertices, which is measured exactly. The quadric-error limit of the bounding
// mesh algorithm only estimates that distance, so it is searched: halved from 8·budget until the
// result is within `budget`, then bisected towards the failing limit; the result with the fewest
// vertices within `budget` is kept, the piece itself if there is none.
std::pair<ConvexHull, double> simplifyPiece(const ConvexHull& piece, double budget) {
  std::pair<ConvexHull, double> best{piece, 0.0};
  const auto attempt = [&](double limit) {
    BoundingMeshOptions options;
    options.side = BoundSide::Outer;
    options.maxError = limit;
    ConvexHull simplified;
    try {
      simplified = convexHull(simplifyBounding(piece.mesh, options).mesh.vertices, "piece");
    } catch (const InputError&) {
      return false;
    }
    const double growth = largestDistanceToConvex(simplified.mesh.vertices, piece);
    if (growth > budget) return false;
    if (simplified.mesh.vertexCount() < best.first.mesh.vertexCount()) {
      best = {std::move(simplified), growth};
    }
    return true;
  };
  double failing = 8.0 * budget;
  if (attempt(failing)) return best;
  double passing = failing;
  for (int halvings = 0; halvings < 5; ++halvings) {
    passing *= 0.5;
    if (attempt(passing)) break;
    failing = passing;
  }
  for (int bisections = 0; bisections < 3; ++bisections) {
    const double middle = 0.5 * (passing + failing);
    (attempt(middle) ? passing : failing) = middle;
  }
  return best;
}

// The edge-connected components of `mesh` as separate meshes, each with a flag: closed (every
// edge has exactly two triangles).
std::vector<std::pair<TriangleMesh, bool>> splitComponents(const TriangleMesh& mesh) {
  const EdgeNeighbors neighbors = findEdgeNeighbors(mesh);
  const std::size_t count = mesh.triangles.size();
  constexpr std::uint32_t kUnset = 0xffffffffu;
  std::vector<std::uint32_t> component(count, kUnset);
  std::vector<std::pair<TriangleMesh, bool>> components;
  std::vector<std::uint32_t> vertexMap(mesh.vertices.size(), kUnset);
  std::vector<std::uint32_t> stack, touched;
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (component[seed] != kUnset) continue;
    auto& [part, closed] = components.emplace_back(TriangleMesh{}, true);
    const auto id = static_cast<std::uint32_t>(components.size() - 1);
    component[seed] = id;
    stack.assign(1, static_cast<std::uint32_t>(seed));
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      Triangle local{};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.triangles[t][k];
        if (vertexMap[v] == kUnset) {
          vertexMap[v] = static_cast<std::uint32_t>(part.vertices.size());
          part.vertices.push_back(mesh.vertices[v]);
          touched.push_back(v);
        }
        local[k] = vertexMap[v];
        const std::uint32_t other = neighbors.across[3 * t + k];
        if (other >= count) {
          closed = false;  // border, non-manifold edge or repeated index
        } else if (component[other] == kUnset) {
          component[other] = id;
          stack.push_back(other);
        }
      }
      part.triangles.push_back(local);
    }
    for (const std::uint32_t v : touched) vertexMap[v] = kUnset;  // shared with later components
    touched.clear();
  }
  return components;
}

// Welded, outward, hole-filled copy of the input; InputError for unusable input.
TriangleMesh closedInput(const TriangleMesh& mesh, DecompositionStats& stats) {
  if (mesh.triangles.empty()) throw InputError("mesh has no triangles");
  for (const Vec3& v : mesh.vertices) {
    if (!v.allFinite()) throw InputError("mesh has a non-finite vertex coordinate");
  }
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t i : t) {
      if (i >= mesh.vertices.size()) throw InputError("mesh has a vertex index out of range");
    }
  }
  TriangleMesh closed = mesh;
  weldVertices(closed);
  bool flipped = false;
  if (!orientOutward(closed, flipped)) {
    throw InputError(
        "mesh cannot be oriented consistently (non-orientable or non-manifold surface)");
  }
  stats.holesFilled = fillHoles(closed).loops;
  if (!(meshVolume(closed) > 1e-12 * std::pow(boundingBoxDiagonal(closed), 3))) {
    throw InputError("mesh encloses no volume (flat, or its holes could not be closed outward)");
  }
  return closed;
}

}  // namespace

bool ConvexPiece::contains(const Vec3& p, double tolerance) const {
  return std::all_of(planes.begin(), planes.end(),
                     [&](const HullPlane& h) { return h.normal.dot(p) <= h.offset + tolerance; });
}

namespace {

// decomposeBounding, with the candidate cuts' hulls shared with idle workers when `sharing`
// is given.
Decomposition decomposeSharing(const TriangleMesh& mesh, const DecompositionOptions& options,
                               WorkSharing* sharing) {
  const auto start = std::chrono::steady_clock::now();
  if (std::isnan(options.epsilon) || options.epsilon < 0.0) {
    throw InputError("epsilon must be a positive distance");
  }
  Decomposition result;
  DecompositionStats& stats = result.stats;
  stats.inputVertices = mesh.vertexCount();
  stats.inputTriangles = mesh.triangleCount();
  result.closedInput = closedInput(mesh, stats);
  const TriangleMesh& closed = result.closedInput;
  stats.diagonal = boundingBoxDiagonal(closed);
  stats.epsilon =
      options.epsilon > 0.0 ? options.epsilon : options.epsilonPercent / 100.0 * stats.diagonal;
  if (!(stats.epsilon > 0.0) || !std::isfinite(stats.epsilon)) {
    throw InputError("epsilon must be a positive distance");
  }
  if (options.maxPieces == 0) throw InputError("the piece limit must be at least 1");
  const double tolerance = 1e-12 * stats.diagonal;

  // Step 1: an outer bounding mesh at about ε/10 (Hausdorff distance measured on samples), for
  // every edge-connected component on its own (components may overlap; the solid is their union).
  // The bounding mesh algorithm keeps its result outside an embedded closed input; a component
  // that is open (non-manifold edges) or self-intersecting (common in CAD exports; hole caps can
  // fold) has no well-defined outside and is kept as it is: step 2 contains its whole surface.
  TriangleMesh bound;
  double boundError = 0.0;
  for (auto& [part, partClosed] : splitComponents(closed)) {
    if (partClosed && countSelfIntersections(part) == 0) {
      BoundingMeshOptions boundOptions;
      boundOptions.side = BoundSide::Outer;
      HausdorffReport boundDistance;
      part = simplifyBoundingWithin(part, boundOptions, kBoundShare * stats.epsilon, 2000,
                                    boundDistance, 3)
                 .mesh;
      boundError = std::max(boundError, boundDistance.resultToOriginal.max);
    } else {
      ++stats.componentsKept;
    }
    const auto offset = static_cast<std::uint32_t>(bound.vertices.size());
    bound.vertices.insert(bound.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const Triangle& t : part.triangles) {
      bound.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }
  stats.boundedVertices = bound.vertexCount();

  // Step 2: hierarchical plane splits, the worst concavity first.
  const Solid solid(bound, 1e-9 * stats.diagonal);
  const Context context{sharing,
                        solid,
                        tolerance,
                        1e-8 * stats.diagonal,
                        options.concavitySamples,
                        options.bridgeSamples,
                        options.seed};
  const double concavityBudget = kConcavityShare * stats.epsilon;
  Cell root;
  for (const Triangle& t : bound.triangles) {
    for (const std::uint32_t v : t) root.polygonPoints.push_back(bound.vertices[v]);
    root.polygonEnds.push_back(static_cast<std::uint32_t>(root.polygonPoints.size()));
  }
  root.points = root.polygonPoints;
  sortPoints(root.points);
  const MeshAnalysis boundAnalysis = analyzeMesh(bound);
  const Vec3 margin = Vec3::Constant(0.01 * stats.diagonal);
  const Vec3 lo = boundAnalysis.boxMin - margin, hi = boundAnalysis.boxMax + margin;
  for (int axis = 0; axis < 3; ++axis) {
    root.walls.push_back({Vec3::Unit(axis), hi[axis]});
    root.walls.push_back({-Vec3::Unit(axis), -lo[axis]});
  }
  if (!buildHull(root, context.snap)) throw InputError("mesh encloses no volume");
  std::uint64_t measured = 0;
  measureConcavity(root, context, measured++);

  // Splitting goes past the piece limit; merging brings the count back (better cuts than a
  // top-down split stopped early).
  const std::size_t splitLimit = std::max<std::size_t>(kSplitBeyondLimit * options.maxPieces, 2);
  std::vector<Cell> leaves;
  std::vector<Cell> open{std::move(root)};  // cells that may still be split
  const auto byConcavity = [](const Cell& a, const Cell& b) { return a.concavity < b.concavity; };
  while (!open.empty()) {
    const auto worst = std::max_element(open.begin(), open.end(), byConcavity);
    if (worst->concavity <= concavityBudget) break;
    if (leaves.size() + open.size() >= splitLimit) break;
    Cell cell = std::move(*worst);
    open.erase(worst);
    auto split = bestSplit(cell, context, measured);
    if (!split) {
      leaves.push_back(std::move(cell));
      continue;
    }
    ++stats.splits;
    for (Cell* child : {&split->first, &split->second}) {
      child->stalls = child->concavity > kStallRatio * cell.concavity ? cell.stalls + 1 : 0;
      (child->stalls >= kMaxStalls ? leaves : open).push_back(std::move(*child));
    }
  }
  for (Cell& cell : open) leaves.push_back(std::move(cell));
  const std::size_t leafCount = leaves.size();
  std::vector<Piece> merged = MergeSearch(leaves, context, 1e-6 * stats.diagonal, measured)
                                  .run(options.maxPieces, concavityBudget);
  stats.refinements =
      refinePieces(merged, options.refineRounds, context, 1e-6 * stats.diagonal, measured);
  leaves.clear();
  for (Piece& piece : merged) leaves.push_back(std::move(piece.cell));
  stats.merges = leafCount - leaves.size();
  const bool limited = std::any_of(leaves.begin(), leaves.end(),
                                   [&](const Cell& c) { return c.concavity > concavityBudget; });
  const bool atLimit = stats.splits + 1 >= splitLimit || leaves.size() >= options.maxPieces;
  stats.stopReason = !limited  ? "within epsilon"
                     : atLimit ? "piece limit reached"
                               : "cuts stopped reducing the concavity";

  // Step 3: fewer vertices per piece, staying outside it and convex (pieces shared with idle
  // workers).
  std::vector<std::pair<ConvexHull, double>> simplified(leaves.size());
  runTasks(sharing, leaves.size(), [&](std::size_t i) {
    simplified[i] = simplifyPiece(leaves[i].hull, kSimplifyShare * stats.epsilon);
  });
  double worstConcavity = 0.0, worstGrowth = 0.0;
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    stats.hullVertices += leaves[i].hull.mesh.vertexCount();
    worstConcavity = std::max(worstConcavity, leaves[i].concavity);
    auto& [hull, growth] = simplified[i];
    worstGrowth = std::max(worstGrowth, growth);
    stats.totalVertices += hull.mesh.vertexCount();
    result.pieces.push_back({std::move(hull.mesh), std::move(hull.planes)});
  }
  stats.estimatedError = boundError + worstConcavity + worstGrowth;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

Decomposition decomposeBounding(const TriangleMesh& mesh, const DecompositionOptions& options) {
  return decomposeSharing(mesh, options, nullptr);
}

std::vector<Decomposition> decomposeBoundingEach(std::span<const TriangleMesh> meshes,
                                                 const DecompositionOptions& options,
                                                 unsigned threads) {
  std::vector<Decomposition> results(meshes.size());
  std::vector<std::exception_ptr> errors(meshes.size());
  // Largest meshes first, so that no thread is left with a large one at the end.
  std::vector<std::size_t> order(meshes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return meshes[a].triangleCount() > meshes[b].triangleCount();
  });
  std::atomic<std::size_t> next{0};
  const unsigned workers = std::max(threads, 1u);
  WorkSharing sharing(workers);
  const auto work = [&] {
    for (std::size_t k = next++; k < meshes.size(); k = next++) {
      const std::size_t i = order[k];
      try {
        results[i] = decomposeSharing(meshes[i], options, &sharing);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
    sharing.help();
  };
  {
    std::vector<std::jthread> helpers;
    for (unsigned t = 1; t < workers; ++t) helpers.emplace_back(work);
    work();
  }
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    if (!errors[i]) continue;
    try {
      std::rethrow_exception(errors[i]);
    } catch (const InputError& error) {
      throw InputError(fmt::format("mesh {}: {}", i, error.what()));
    }
  }
  return results;
}

TriangleMesh mergePieces(std::span<const ConvexPiece> pieces) {
  TriangleMesh merged;
  for (const ConvexPiece& piece : pieces) {
    const auto offset = static_cast<std::uint32_t>(merged.vertices.size());
    merged.vertices.insert(merged.vertices.end(), piece.mesh.vertices.begin(),
                           piece.mesh.vertices.end());
    for (const Triangle& t : piece.mesh.triangles) {
      merged.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }
  return merged;
}

DecompositionQuality measureDecomposition(const TriangleMesh& original,
                                          std::span<const ConvexPiece> pieces,
                                          std::size_t randomSamples, std::uint64_t seed) {
  if (pieces.empty()) throw InputError("no convex pieces to measure");
  DecompositionQuality quality;
  quality.diagonal = boundingBoxDiagonal(original);
  const double tolerance = 1e-7 * quality.diagonal;
  const TriangleBvh originalBvh(original);
  const TriangleBvh piecesBvh(mergePieces(pieces));
  const auto accumulate = [](DistanceStats& stats, double d, std::size_t& count) {
    stats.min = count == 0 ? d : std::min(stats.min, d);
    stats.max = std::max(stats.max, d);
    stats.mean += d;
    ++count;
  };

  std::size_t count = 0;
  for (const Vec3& p : sampleSurface(original, randomSamples, seed)) {
    accumulate(quality.originalToApproximation, piecesBvh.closest(p).distance, count);
    double outside = std::numeric_limits<double>::infinity();  // least plane violation
    for (const ConvexPiece& piece : pieces) {
      double violation = 0.0;
      for (const HullPlane& h : piece.planes) {
        violation = std::max(violation, h.normal.dot(p) - h.offset);
      }
      outside = std::min(outside, violation);
    }
    if (outside > tolerance) {
      ++quality.uncovered;
      quality.worstUncovered = std::max(quality.worstUncovered, outside);
    }
  }
  quality.originalToApproximation.mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  quality.samples = count;

  count = 0;
  const std::size_t perPiece = randomSamples / pieces.size() + 1;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (const Vec3& p : sampleSurface(pieces[i].mesh, perPiece, seed + i + 1)) {
      bool inOther = false;
      for (std::size_t j = 0; j < pieces.size() && !inOther; ++j) {
        inOther = j != i && pieces[j].contains(p, tolerance);
      }
      if (!inOther)
        accumulate(quality.approximationToOriginal, originalBvh.closest(p).distance, count);
    }
  }
  quality.approximationToOriginal.mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  quality.samples += count;
  return quality;
}

}  // namespace kaboum::geometry
