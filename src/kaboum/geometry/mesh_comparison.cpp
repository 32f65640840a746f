#include "kaboum/geometry/mesh_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <thread>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/core/worker_pool.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/surface_sampling.hpp"
#include "kaboum/geometry/triangle_bvh.hpp"

namespace kaboum::geometry {

namespace {

// The threads of the sample loops: the caller and one worker kept for the process (the caller
// alone on one core).
WorkerPool& sampleWorkers() {
  static WorkerPool workers(std::thread::hardware_concurrency() < 2 ? 1 : 2);
  return workers;
}

// Runs work(i) for every i in [0, count), split into two contiguous halves on two threads when
// there is enough work. Each call must only write its own output slot, so the split is invisible.
template <class Work>
void forEachIndex(std::size_t count, const Work& work) {
  constexpr std::size_t kMinimumPerThread = 4096;
  sampleWorkers().forEachIndex(count, kMinimumPerThread, work);
}

// A BVH whose input errors name the mesh's role ("original", "result").
TriangleBvh buildBvh(const TriangleMesh& mesh, const char* role) {
  try {
    return TriangleBvh(mesh);
  } catch (const InputError& error) {
    throw InputError(fmt::format("{} {}", role, error.what()));
  }
}

// Undirected edges whose two directions are not used equally often: border edges and edges
// whose triangles disagree on orientation. Zero for a closed, consistently oriented mesh.
std::size_t countUnbalancedEdges(const TriangleMesh& mesh) {
  std::vector<std::pair<std::uint64_t, int>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const Triangle& tri : mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      if (a == b) continue;
      edges.emplace_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b), a < b ? 1 : -1);
    }
  }
  std::sort(edges.begin(), edges.end());
  std::size_t unbalanced = 0;
  for (std::size_t i = 0; i < edges.size();) {
    int balance = 0;
    std::size_t j = i;
    for (; j < edges.size() && edges[j].first == edges[i].first; ++j) balance += edges[j].second;
    if (balance != 0) ++unbalanced;
    i = j;
  }
  return unbalanced;
}

// Distances of `samples` to `target`.
DistanceStats distanceStats(const std::vector<Vec3>& samples, const TriangleBvh& target) {
  std::vector<double> distances(samples.size());
  forEachIndex(samples.size(),
               [&](std::size_t i) { distances[i] = target.closest(samples[i]).distance; });
  if (distances.empty()) return DistanceStats{};
  DistanceStats stats{std::numeric_limits<double>::infinity(), 0.0, 0.0};
  double sum = 0.0;
  for (const double d : distances) {
    stats.min = std::min(stats.min, d);
    stats.max = std::max(stats.max, d);
    sum += d;
  }
  stats.mean = sum / static_cast<double>(distances.size());
  return stats;
}

// Whether every sample has a triangle of `target` within `limit`: the same answer as comparing
// each closest distance with it (both take the distance to a triangle's closest point).
bool allWithin(const std::vector<Vec3>& samples, const TriangleBvh& target, double limit) {
  std::atomic<bool> exceeded{false};
  forEachIndex(samples.size(), [&](std::size_t i) {
    if (exceeded.load(std::memory_order_relaxed)) return;
    if (!target.hasTriangleWithin(samples[i], limit)) {
      exceeded.store(true, std::memory_order_relaxed);
    }
  });
  return !exceeded;
}

std::size_t countSelfIntersections(const TriangleMesh& mesh, const TriangleBvh& bvh) {
  std::vector<std::uint32_t> laterPartners(mesh.triangles.size(), 0);
  forEachIndex(mesh.triangles.size(), [&](std::size_t i) {
    const Triangle& first = mesh.triangles[i];
    const Vec3 &a0 = mesh.vertices[first[0]], &a1 = mesh.vertices[first[1]],
               &a2 = mesh.vertices[first[2]];
    bvh.forEachTriangleOverlapping(
        a0.cwiseMin(a1).cwiseMin(a2), a0.cwiseMax(a1).cwiseMax(a2), [&](std::uint32_t j) {
          if (j <= i) return true;  // each pair once
          const Triangle& second = mesh.triangles[j];
          const std::array<Vec3, 3> firstCorners{a0, a1, a2};
          const std::array<Vec3, 3> secondCorners{
              mesh.vertices[second[0]], mesh.vertices[second[1]], mesh.vertices[second[2]]};
          const bool meet = meshTrianglesIntersect(firstCorners, first, secondCorners, second);
          if (meet) ++laterPartners[i];
          return true;
        });
  });
  std::size_t pairs = 0;
  for (const std::uint32_t count : laterPartners) pairs += count;
  return pairs;
}

}  // namespace

struct HausdorffMeter::Original {
  Original(const TriangleMesh& original, std::size_t randomSamples, std::uint64_t seed)
      : bvh(buildBvh(original, "original")),
        samples(sampleSurface(original, randomSamples, seed)),
        diagonal(boundingBoxDiagonal(original)) {}
  TriangleBvh bvh;
  std::vector<Vec3> samples;
  double diagonal;
};

HausdorffMeter::HausdorffMeter(const TriangleMesh& original, std::size_t randomSamples,
                               std::uint64_t seed)
    : original_(std::make_unique<const Original>(original, randomSamples, seed)),
      randomSamples_(randomSamples),
      seed_(seed) {}

HausdorffMeter::~HausdorffMeter() = default;

HausdorffReport HausdorffMeter::measure(const TriangleMesh& result) const {
  const TriangleBvh resultBvh = buildBvh(result, "result");
  const std::vector<Vec3> resultSamples = sampleSurface(result, randomSamples_, seed_);
  HausdorffReport report;
  report.originalToResult = distanceStats(original_->samples, resultBvh);
  report.resultToOriginal = distanceStats(resultSamples, original_->bvh);
  report.diagonal = original_->diagonal;
  report.samples = original_->samples.size() + resultSamples.size();
  return report;
}

bool HausdorffMeter::within(const TriangleMesh& result, double limit) const {
  const TriangleBvh resultBvh = buildBvh(result, "result");
  return allWithin(original_->samples, resultBvh, limit) &&
         allWithin(sampleSurface(result, randomSamples_, seed_), original_->bvh, limit);
}

HausdorffReport measureHausdorff(const TriangleMesh& original, const TriangleMesh& result,
                                 std::size_t randomSamples, std::uint64_t seed) {
  return HausdorffMeter(original, randomSamples, seed).measure(result);
}

ContainmentReport verifyContainment(const TriangleMesh& original, const TriangleMesh& result,
                                    BoundSide side, std::size_t randomSamples, std::uint64_t seed,
                                    double tolerance) {
  const TriangleBvh originalBvh = buildBvh(original, "original");
  const TriangleBvh resultBvh = buildBvh(result, "result");
  ContainmentReport report;
  report.selfIntersectingPairs = countSelfIntersections(result, resultBvh);

  const std::size_t openOriginal = countUnbalancedEdges(original);
  const std::size_t openResult = side == BoundSide::Outer ? countUnbalancedEdges(result) : 0;
  if (openOriginal > 0 || openResult > 0) {
    const std::string which = openOriginal > 0 && openResult > 0 ? "the original and the result are"
                              : openOriginal > 0                 ? "the original is"
                                                                 : "the result is";
    report.note = fmt::format(
        "{} not closed ({} border or inconsistently oriented edges): containment is only defined "
        "for closed meshes",
        which, openOriginal + openResult);
    return report;
  }
  report.defined = true;
  // A closed mesh whose faces point inward has negative signed volume; the winding-number inside
  // test would still call its interior "inside", so this must be caught here.
  const double originalVolume = analyzeMesh(original).volume;
  const double resultVolume = analyzeMesh(result).volume;
  const bool resultClosed = side == BoundSide::Outer || countUnbalancedEdges(result) == 0;
  if (originalVolume < 0.0 || (resultClosed && resultVolume < 0.0)) {
    report.insideOut = true;
    report.note = fmt::format(
        "the {} is inside out (negative signed volume: its faces point "
        "inward)",
        originalVolume < 0.0 ? "original" : "result");
    return report;
  }

  const double onSurface = tolerance < 0 ? 1e-9 * boundingBoxDiagonal(original) : tolerance;
  const bool outer = side == BoundSide::Outer;
  const TriangleBvh& container = outer ? resultBvh : originalBvh;
  const std::vector<Vec3> samples = sampleSurface(outer ? original : result, randomSamples, seed);
  std::vector<double> outsideDistance(samples.size(), 0.0);  // 0: contained
  forEachIndex(samples.size(), [&](std::size_t i) {
    const double distance = container.closest(samples[i]).distance;
    if (distance > onSurface && !container.contains(samples[i])) outsideDistance[i] = distance;
  });
  report.checked = samples.size();
  for (const double distance : outsideDistance) {
    if (distance > 0.0) {
      ++report.violations;
      report.worstViolation = std::max(report.worstViolation, distance);
    }
  }
  return report;
}

std::size_t countSelfIntersections(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return 0;
  return countSelfIntersections(mesh, TriangleBvh(mesh));
}

}  // namespace kaboum::geometry
