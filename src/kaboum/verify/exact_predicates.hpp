// Exact collision predicates on the original scene geometry (thesis §6.2.3, Proposition 4; Table
// 6.7's variant "exact geometric predicates on the original scene geometry"): the World's state
// queries answered by FCL on the original triangle meshes and primitives (ReferenceGeometry)
// instead of the bounded predicates on the bounding convex decomposition. Installed with
// World::usePredicates (`kaboum solve --geometry exact`). Reference: docs/world.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "kaboum/verify/reference_geometry.hpp"
#include "kaboum/world/state_predicates.hpp"

namespace kaboum::verify {

// Two parties collide when FCL's collide finds their shapes intersecting (for meshes: two
// triangles intersecting; a mesh wholly inside another without touching its surface is not
// found). The same pairs as the bounded predicates are checked: a robot's link pairs its
// collision filter checks, a held object against the parts of other links.
class ExactPredicates final : public StatePredicates {
 public:
  // Builds the reference geometry of `world` (ReferenceGeometry: reads the original meshes).
  // `world` must outlive this object. Throws InputError naming an unreadable mesh.
  explicit ExactPredicates(const World& world);

  [[nodiscard]] const ReferenceGeometry& reference() const { return reference_; }

  [[nodiscard]] std::optional<Collision> firstCollisionOfRobot(
      const GeometricState& state, const QueryScratch& scratch, std::size_t robot,
      std::span<const std::uint8_t> against) const override;
  [[nodiscard]] std::optional<Party> firstCollisionOfObject(const GeometricState& state,
                                                            const QueryScratch& scratch,
                                                            std::size_t object, const Pose& pose,
                                                            bool withRobots) const override;

 private:
  // The reference body of part `part` of robot `robot` in `state` (a link's, or a held object's).
  [[nodiscard]] std::size_t bodyOf(const GeometricState& state, std::size_t robot,
                                   std::size_t part) const;

  ReferenceGeometry reference_;
};

}  // namespace kaboum::verify
