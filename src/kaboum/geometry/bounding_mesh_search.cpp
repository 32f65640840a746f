// Internal phase of the bounding mesh (docs/bounding-mesh.md, "What ε means"): the --epsilon
// search for the largest simplification whose measured distance stays within ε, over runs of
// Algorithm 2 with rising quadric-error limits.
#include <cmath>
#include <functional>
#include <utility>

#include "kaboum/geometry/bounding_mesh.hpp"
#include "kaboum/geometry/bounding_mesh_run.hpp"

namespace kaboum::geometry {

BoundingMeshResult simplifyBoundingWithin(const TriangleMesh& input, BoundingMeshOptions options,
                                          double epsilon, std::size_t samples,
                                          HausdorffReport& measured, int maxRuns) {
  const HausdorffMeter meter(input, samples, 1);
  // Every limit tried is above the largest one known to fit, so each run goes on from a copy of
  // that one's run instead of starting over (at first: after the contractions of cost 0).
  const std::function<void(double)> progress = std::move(options.progress);
  options.progress = nullptr;
  BoundingRun fitting = startRun(input, options);
  advanceRun(fitting, 0.0);
  fitting.options.progress = progress;  // where the runs below report
  int runs = 0;
  double fits = 0.0, fails = 0.0;  // largest scale known to fit, smallest known to fail (0: none)
  double scale = 1.0;
  while (runs < maxRuns) {
    ++runs;
    BoundingRun attempt = fitting;
    advanceRun(attempt, scale * epsilon);
    const BoundingMeshResult result = runResult(attempt);
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
  BoundingMeshResult best = runResult(fitting);  // nothing fitted: the contractions of cost 0 only
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
