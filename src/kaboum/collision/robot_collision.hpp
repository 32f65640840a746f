// A robot's collision geometry (issue 3, "robots plug in"): one body of convex pieces per link
// built from its URDF collision shapes, attached (grasped) objects that move with a link,
// self-collision with adjacency filtering, and robot-vs-scene checks.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/body.hpp"
#include "kaboum/collision/collision_filter.hpp"
#include "kaboum/collision/scene.hpp"
#include "kaboum/geometry/convex_decomposition.hpp"
#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

// How link meshes become convex pieces: one convex hull each (fast to build, loose for concave
// links), or the bounding convex decomposition of §4.4 (seconds per link, within ε).
struct LinkPieceOptions {
  bool decompose = false;
  DecompositionOptions decomposition;  // used when `decompose`
};

// The convex pieces that bound a link mesh (their union contains it). Throws InputError naming
// `what` for a mesh without volume.
std::vector<std::vector<Vec3>> boundingConvexPieces(const TriangleMesh& mesh,
                                                    const std::string& what,
                                                    const LinkPieceOptions& options = {});

// The meshes that a robot's collision shapes name, by their path (CollisionShape::meshPath); the
// caller reads them (io::readCollisionMeshes), so that collision reads no files.
using LinkMeshes = std::map<std::string, TriangleMesh>;

// Vertices of a polytope containing a URDF collision shape, in the link frame (the shape's origin
// applied): a box's corners, a cylinder's circumscribed 16-sided prism, a sphere's circumscribed
// 42-vertex geodesic polytope, a mesh's bounding convex pieces (the mesh taken from `meshes`;
// InputError naming the path when it is not there).
std::vector<std::vector<Vec3>> shapeConvexPieces(const CollisionShape& shape,
                                                 const LinkMeshes& meshes,
                                                 const LinkPieceOptions& options = {});

class RobotCollisionModel {
 public:
  // One part per link with collision geometry, mesh shapes taken from `meshes`. Parts of a link
  // and of its nearest ancestor with geometry are not checked against each other (adjacent
  // links). Throws InputError for a missing or degenerate link mesh.
  RobotCollisionModel(RobotModel model, const LinkMeshes& meshes,
                      const LinkPieceOptions& pieces = {});

  struct Part {
    BodyPtr body;
    int link = -1;                   // the link whose pose moves it
    Pose inLink = Pose::Identity();  // body frame in the link frame
    bool active = true;              // detached objects stay as inactive parts
    bool offset = false;             // inLink is not the identity
  };

  [[nodiscard]] const RobotModel& model() const { return model_; }
  [[nodiscard]] std::size_t partCount() const { return parts_.size(); }
  [[nodiscard]] const Part& part(std::size_t i) const { return parts_[i]; }
  // Pairs of parts never checked for self-collision; add allowed pairs here.
  [[nodiscard]] CollisionFilter& filter() { return filter_; }
  [[nodiscard]] const CollisionFilter& filter() const { return filter_; }
  // Allows every active pair within `margin` at these link poses and returns how many: call it at
  // a configuration known to be free (e.g. home), where the bounding pieces of links around a
  // short link (the KR5's forearm and palm around its wrist) overlap.
  std::size_t allowPairsCollidingAt(std::span<const Pose> linkPoses, double margin = 0.0);
  // Largest vertex distance from the link origin over the link's active parts (Eq. 4.19's r).
  [[nodiscard]] double linkReach(int link) const;

  // Attaches a grasped object to `link` at `inLink`; it is not checked against that link.
  // Returns its part index. Throws std::out_of_range for an unknown link.
  std::size_t attach(BodyPtr object, int link, const Pose& inLink);
  void detach(std::size_t part) { parts_.at(part).active = false; }

  // Pose of the model root in the world (identity by default); every query applies it.
  void setBasePose(const Pose& base) {
    base_ = base;
    baseIsIdentity_ = base.matrix() == Pose::Identity().matrix();
  }
  [[nodiscard]] const Pose& basePose() const { return base_; }

  // World pose of a part given the link poses from RobotModel::linkPoses().
  [[nodiscard]] Pose partPose(std::size_t i, std::span<const Pose> linkPoses) const {
    const Part& part = parts_[i];
    Pose pose = linkPoses[static_cast<std::size_t>(part.link)];
    if (part.offset) pose = pose * part.inLink;
    if (!baseIsIdentity_) pose = base_ * pose;
    return pose;
  }

  // Whether two unfiltered active parts come within `margin`. Allocates nothing.
  [[nodiscard]] bool selfCollides(std::span<const Pose> linkPoses, double margin) const;
  // The first scene object within `margin` of an active part, if any. Allocates nothing.
  [[nodiscard]] std::optional<std::size_t> firstSceneCollision(std::span<const Pose> linkPoses,
                                                               const CollisionScene& scene,
                                                               double margin) const;

 private:
  RobotModel model_;
  Pose base_ = Pose::Identity();
  bool baseIsIdentity_ = true;
  std::vector<Part> parts_;
  CollisionFilter filter_;
};

}  // namespace kaboum::collision
