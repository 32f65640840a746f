// The independent reference geometry of a World (thesis §4.5, certified motion): every robot link,
// hand shape and object of the scene as FCL sees it — the ORIGINAL triangle meshes as FCL BVH
// models (OBBRSS) and primitives as FCL shapes — not kaboum's bounding convex pieces nor its GJK.
// Built once per World; `kaboum verify-path` checks paths against it (docs/verify.md).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>

#include "kaboum/world/world.hpp"

namespace kaboum::verify {

using namespace kaboum::world;

// Two bodies at given poses: whether they collide (FCL collide), and their distance (FCL
// distance) where it is below the distance of interest; +infinity where it is not, 0 where they
// collide.
struct Proximity {
  bool collides = false;
  double distance = 0;
};

class ReferenceGeometry {
 public:
  // Reads the original meshes of every robot link (io::readCollisionMeshes of the World's robot
  // models, hand shapes included) and object (io::readMesh). `world` must outlive this object.
  // Throws InputError naming an unreadable mesh.
  explicit ReferenceGeometry(const World& world);
  ~ReferenceGeometry();
  ReferenceGeometry(const ReferenceGeometry&) = delete;
  ReferenceGeometry& operator=(const ReferenceGeometry&) = delete;

  [[nodiscard]] const World& world() const { return world_; }

  // The body of link `link` of robot `robot` (its collision shapes in the link frame), nullopt
  // for a link without collision geometry.
  [[nodiscard]] std::optional<std::size_t> linkBody(std::size_t robot, std::size_t link) const;
  // The body of scene object `object` (its geometry in the object frame).
  [[nodiscard]] std::size_t objectBody(std::size_t object) const;

  // Bodies a and b at these world poses. The distance (smallest over their shape pairs) is
  // computed where it is below `distanceOfInterest`: bounding spheres, then FCL's traversal
  // started from that bound, skip what lies farther.
  [[nodiscard]] Proximity proximity(std::size_t a, const Pose& poseA, std::size_t b,
                                    const Pose& poseB, double distanceOfInterest) const;

  // Whether bodies a and b at these world poses collide (FCL collide on each shape pair whose
  // bounding spheres meet; no distance is computed).
  [[nodiscard]] bool collides(std::size_t a, const Pose& poseA, std::size_t b,
                              const Pose& poseB) const;

  // Triangles of the original meshes over all bodies, and the seconds taken to build them.
  [[nodiscard]] std::size_t triangleCount() const;
  [[nodiscard]] double buildSeconds() const;

 private:
  struct Bodies;  // the FCL objects (reference_geometry.cpp)
  const World& world_;
  std::unique_ptr<const Bodies> bodies_;
};

}  // namespace kaboum::verify
