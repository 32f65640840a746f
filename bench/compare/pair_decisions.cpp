#include "pair_decisions.hpp"

#include "kaboum/collision/gjk.hpp"

namespace kaboum::cli {

using namespace kaboum::collision;

void PairDecisionCounts::add(const collision::ConvexPolytope& a,
                             const collision::TransformedSupport& bInA) {
  using collision::PairVerdict;
  const PairVerdict spheres = collision::sphereVerdict(a, bInA);
  if (spheres == PairVerdict::separated) {
    ++spheresApart_;
  } else if (spheres == PairVerdict::intersecting) {
    ++innerBallsOverlap_;
  } else if (collision::detail::fanPretest(a, bInA, 0.0, {}) != PairVerdict::unknown) {
    ++fan_;
  } else if (collision::portalIntersects(a, bInA) != PairVerdict::unknown) {
    ++portal_;
  } else {
    ++gjk_;
  }
}

nlohmann::json PairDecisionCounts::toJson() const {
  return {{"bounding_spheres_apart", spheresApart_},
          {"inner_balls_overlap", innerBallsOverlap_},
          {"fan", fan_},
          {"portal", portal_},
          {"gjk", gjk_}};
}

}  // namespace kaboum::cli
