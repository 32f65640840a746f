// The collision predicates a World's state queries may be delegated to (thesis §6.2.3,
// Proposition 4 and Table 6.7's variant "exact geometric predicates on the original scene
// geometry"): by default the World answers with the bounded predicates on the bounding convex
// decomposition; an implementation of this interface installed with World::usePredicates answers
// instead (verify::ExactPredicates: FCL on the original triangle meshes). Reference: docs/world.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "kaboum/world/world.hpp"

namespace kaboum::world {

class StatePredicates {
 public:
  virtual ~StatePredicates() = default;

  // What World::firstCollisionOfRobot answers at margin 0: the first collision of robot `robot`
  // (with what it holds) with itself (the pairs its collision filter checks), the present scene
  // objects, and each other robot r with against[r] != 0. `scratch.linkPoses` holds the state's
  // link poses.
  [[nodiscard]] virtual std::optional<Collision> firstCollisionOfRobot(
      const GeometricState& state, const QueryScratch& scratch, std::size_t robot,
      std::span<const std::uint8_t> against) const = 0;

  // The first party that scene object `object` at `pose` collides with in `state`: a present
  // scene object other than itself, then, with `withRobots`, a robot's part (not the object
  // itself when a robot holds it). `scratch.linkPoses` holds the state's link poses when
  // `withRobots`.
  [[nodiscard]] virtual std::optional<Party> firstCollisionOfObject(const GeometricState& state,
                                                                    const QueryScratch& scratch,
                                                                    std::size_t object,
                                                                    const Pose& pose,
                                                                    bool withRobots) const = 0;
};

}  // namespace kaboum::world
