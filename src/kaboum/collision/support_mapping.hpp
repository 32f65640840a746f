// The support-mapping concept: any convex shape GJK can query, given by its support function
// (thesis §4.1: every geometric query of KABouM becomes a convex–convex query).
#pragma once

#include <concepts>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

// A convex shape S in world coordinates. `support(d, hint)` returns a point of S maximising d.x
// (d need not be unit length and may be zero); `hint` is the shape's own warm-start state (e.g.
// the last support vertex), default-constructed for a cold start and updated by every call.
// `center()` is any point of S, used for GJK's first search direction.
template <class Shape>
concept SupportMapping = std::default_initializable<typename Shape::Hint> &&
    std::copyable<typename Shape::Hint> &&
    requires(const Shape& shape, const Vec3& direction, typename Shape::Hint& hint) {
  { shape.support(direction, hint) } -> std::same_as<Vec3>;
  { shape.center() } -> std::same_as<Vec3>;
};

}  // namespace kaboum::collision
