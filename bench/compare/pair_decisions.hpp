// How kaboum's cold boolean pair query decides pairs, step by step in its own order (bounding
// spheres apart, inner balls overlapping, the fan test, the portal test, else GJK), counted for the
// benchmarks' `*_decided_by` figures.
#pragma once

#include <nlohmann/json.hpp>

#include "kaboum/collision/convex_polytope.hpp"

namespace kaboum::cli {

using namespace kaboum::collision;

class PairDecisionCounts {
 public:
  // Counts the step that decides a with b placed in a's frame (margin 0).
  void add(const collision::ConvexPolytope& a, const collision::TransformedSupport& bInA);
  // {"bounding_spheres_apart", "inner_balls_overlap", "fan", "portal", "gjk"}
  [[nodiscard]] nlohmann::json toJson() const;

 private:
  long spheresApart_ = 0, innerBallsOverlap_ = 0, fan_ = 0, portal_ = 0, gjk_ = 0;
};

}  // namespace kaboum::cli
