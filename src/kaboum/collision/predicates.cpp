#include "kaboum/collision/predicates.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;

bool isInside(const CollisionBody& object, const Pose& objectPose, const ConvexContainer& container,
              const Pose& containerPose) {
  const Pose toContainer = containerPose.inverse() * objectPose;
  for (std::size_t p = 0; p < object.pieceCount(); ++p) {
    for (const Vec3& v : object.piece(p).vertices()) {
      const Vec3 local = toContainer * v;
      for (const HullPlane& plane : container.planes()) {
        if (plane.normal.dot(local) > plane.offset) return false;
      }
    }
  }
  return true;
}

bool isOnSupportSurface(const CollisionScene& scene, std::span<const Placement> state,
                        std::size_t object, double drop, double band) {
  const CollisionBody& body = scene.body(object);
  const Pose& pose = scene.pose(object, state);
  if (scene.firstCollision(state, body, pose, 0.0, object)) return false;
  return allBottomProbes(body, pose, drop, band, [&](const SegmentSupport& segment) {
    return probeTouches(scene, state, segment, object).has_value();
  });
}

}  // namespace kaboum::collision
