// A robot's collision geometry (thesis §4.3): one body of convex pieces per link built from its
// URDF collision shapes, self-collision with adjacency filtering, and robot-vs-scene checks. The
// model is built once and shared; a state's configuration (link poses) and held objects are
// passed to every const query.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
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
  // While a decomposition stops at its piece limit with its estimated error above ε, the limit is
  // doubled and the mesh decomposed again, at most this many times (so that a scene's predicates
  // are ε-precise where the pieces allow it, §6.1.1); the result with the smallest error is kept.
  std::size_t pieceLimitDoublings = 0;
  // What computes decomposeBounding's result (e.g. io::DecompositionCache, which keeps them on
  // disk); empty: decomposeBounding itself.
  std::function<Decomposition(const TriangleMesh&, const DecompositionOptions&)> decomposer;
};

// Convex pieces that bound a shape (their union contains it), and how far they reach beyond it at
// most: for a decomposition its estimate (DecompositionStats::estimatedError), for a mesh's hull
// the distance measured on samples of the hull, for primitives the exact distance.
struct BoundingPieces {
  std::vector<std::vector<Vec3>> pieces;
  double boundingError = 0.0;
};

// The convex pieces that bound a link mesh and their bounding error. Throws InputError naming
// `what` for a mesh without volume.
BoundingPieces boundingMeshPieces(const TriangleMesh& mesh, const std::string& what,
                                  const LinkPieceOptions& options = {});
// boundingMeshPieces(...).pieces.
std::vector<std::vector<Vec3>> boundingConvexPieces(const TriangleMesh& mesh,
                                                    const std::string& what,
                                                    const LinkPieceOptions& options = {});

// The meshes that a robot's collision shapes name, by their path (CollisionShape::meshPath); the
// caller reads them (io::readCollisionMeshes), so that collision reads no files.
using LinkMeshes = std::map<std::string, TriangleMesh>;

// The mesh of a mesh shape, scaled by its `size`, in the shape's frame (its origin not applied):
// what boundingShapePieces decomposes. InputError naming the path when `meshes` lacks it.
TriangleMesh shapeMesh(const CollisionShape& shape, const LinkMeshes& meshes);

// Vertices of a polytope containing a URDF collision shape, in the link frame (the shape's origin
// applied): a box's corners, a cylinder's circumscribed 16-sided prism, a sphere's circumscribed
// 42-vertex geodesic polytope, a mesh's bounding convex pieces (the mesh taken from `meshes`;
// InputError naming the path when it is not there).
BoundingPieces boundingShapePieces(const CollisionShape& shape, const LinkMeshes& meshes,
                                   const LinkPieceOptions& options = {});
// boundingShapePieces(...).pieces.
std::vector<std::vector<Vec3>> shapeConvexPieces(const CollisionShape& shape,
                                                 const LinkMeshes& meshes,
                                                 const LinkPieceOptions& options = {});

// A body attached rigidly to a robot link, its frame at `inLink` in the link frame: a link's own
// collision geometry (RobotCollisionModel::part, inLink the identity), or an object the robot
// holds in one state (the `held` span of the queries). A held object is not checked against the
// parts of its link nor against the other objects that link holds.
struct Attachment {
  BodyPtr body;
  int link = -1;
  Pose inLink = Pose::Identity();
};

class RobotCollisionModel {
 public:
  // One part per link with collision geometry, mesh shapes taken from `meshes`. Parts of a link
  // and of its nearest ancestor with geometry are not checked against each other (adjacent
  // links). Throws InputError for a missing or degenerate link mesh.
  RobotCollisionModel(RobotModel model, const LinkMeshes& meshes,
                      const LinkPieceOptions& pieces = {});

  [[nodiscard]] const RobotModel& model() const { return model_; }
  // The bounding error of each collision shape of link `link` (BoundingPieces::boundingError), in
  // the order of Link::collisions.
  [[nodiscard]] const std::vector<double>& shapeBoundingErrors(std::size_t link) const {
    return shapeBoundingErrors_.at(link);
  }
  // The parts of the robot holding the objects `held`: its link parts (indices below
  // partCount()), then one part per held object.
  [[nodiscard]] std::size_t partCount(std::span<const Attachment> held = {}) const {
    return parts_.size() + held.size();
  }
  [[nodiscard]] const Attachment& part(std::size_t i, std::span<const Attachment> held = {}) const {
    return i < parts_.size() ? parts_[i] : held[i - parts_.size()];
  }
  // Pairs of link parts never checked for self-collision; add allowed pairs here while building.
  [[nodiscard]] CollisionFilter& filter() { return filter_; }
  [[nodiscard]] const CollisionFilter& filter() const { return filter_; }
  // Allows every pair of link parts within `margin` at these link poses and returns how many:
  // call it at a configuration known to be free (e.g. home), where the bounding pieces of links
  // around a short link (the KR5's forearm and palm around its wrist) overlap.
  std::size_t allowPairsCollidingAt(std::span<const Pose> linkPoses, double margin = 0.0);
  // Whether parts i != j of the robot holding `held` are checked against each other: two link
  // parts unless the filter allows the pair; a held object against the parts of other links.
  [[nodiscard]] bool checksPair(std::size_t i, std::size_t j,
                                std::span<const Attachment> held) const {
    if (i < parts_.size() && j < parts_.size()) return !filter_.allowed(i, j);
    return part(i, held).link != part(j, held).link;
  }
  // Throws std::out_of_range for a held object on a link the model does not have, and
  // std::invalid_argument for one without a body. Every query checks its `held` so.
  void checkHeld(std::span<const Attachment> held) const;

  // Pose of the model root in the world (identity by default); every query applies it.
  void setBasePose(const Pose& base) {
    base_ = base;
    baseIsIdentity_ = base.matrix() == Pose::Identity().matrix();
  }
  [[nodiscard]] const Pose& basePose() const { return base_; }

  // World pose of part i of the robot holding `held`, given the link poses from
  // RobotModel::linkPoses().
  [[nodiscard]] Pose partPose(std::size_t i, std::span<const Pose> linkPoses,
                              std::span<const Attachment> held = {}) const {
    const Attachment& part = this->part(i, held);
    Pose pose = linkPoses[static_cast<std::size_t>(part.link)];
    if (i >= parts_.size()) pose = pose * part.inLink;  // link parts are in their link frame
    if (!baseIsIdentity_) pose = base_ * pose;
    return pose;
  }

  // The first two checked parts (i < j) of the robot holding `held` within `margin` of each
  // other, if any. Allocates nothing.
  [[nodiscard]] std::optional<std::pair<std::size_t, std::size_t>> firstSelfCollision(
      std::span<const Pose> linkPoses, std::span<const Attachment> held, double margin) const;
  // Whether two checked parts of the robot holding `held` come within `margin`. Allocates nothing.
  [[nodiscard]] bool selfCollides(std::span<const Pose> linkPoses, std::span<const Attachment> held,
                                  double margin) const {
    return firstSelfCollision(linkPoses, held, margin).has_value();
  }
  // The first object of `scene` in `sceneState` within `margin` of a part of the robot holding
  // `held`, if any. Allocates nothing.
  [[nodiscard]] std::optional<std::size_t> firstSceneCollision(
      std::span<const Pose> linkPoses, std::span<const Attachment> held,
      const CollisionScene& scene, std::span<const Placement> sceneState, double margin) const;

 private:
  RobotModel model_;
  Pose base_ = Pose::Identity();
  bool baseIsIdentity_ = true;
  std::vector<Attachment> parts_;
  std::vector<std::vector<double>> shapeBoundingErrors_;  // by link, by collision shape
  CollisionFilter filter_;
};

}  // namespace kaboum::collision
