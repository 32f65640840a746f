#include "kaboum/collision/robot_collision.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "kaboum/core/error.hpp"
#include "kaboum/geometry/convex_hull.hpp"

namespace kaboum::collision {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

namespace {

constexpr int kCylinderSides = 16;
// Surface samples of a mesh's hull whose distance to the mesh is its bounding error.
constexpr std::size_t kHullErrorSamples = 1000;

// The 42 vertices of an icosahedron with every edge split at its midpoint, on the unit sphere.
std::vector<Vec3> geodesicSphere() {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> corners;
  for (double s : {-1.0, 1.0}) {
    for (double t : {-1.0, 1.0}) {
      corners.emplace_back(0, s, t * g);
      corners.emplace_back(s, t * g, 0);
      corners.emplace_back(t * g, 0, s);
    }
  }
  std::vector<Vec3> points;
  for (const Vec3& c : corners) points.push_back(c.normalized());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      if ((corners[i] - corners[j]).norm() < 2.001) {  // an icosahedron edge has length 2
        points.push_back((corners[i] + corners[j]).normalized());
      }
    }
  }
  return points;
}

// decomposeBounding (through options.decomposer), the piece limit doubled while it stops the
// splitting with the estimated error above ε; the result with the smallest error.
Decomposition decompositionReachingEpsilon(const TriangleMesh& mesh,
                                           const LinkPieceOptions& options) {
  const auto decompose = [&](const DecompositionOptions& attempt) {
    return options.decomposer ? options.decomposer(mesh, attempt)
                              : decomposeBounding(mesh, attempt);
  };
  DecompositionOptions attempt = options.decomposition;
  Decomposition best = decompose(attempt);
  for (std::size_t doubling = 0; doubling < options.pieceLimitDoublings; ++doubling) {
    if (best.stats.estimatedError <= best.stats.epsilon || best.pieces.size() < attempt.maxPieces) {
      break;
    }
    attempt.maxPieces *= 2;
    Decomposition larger = decompose(attempt);
    if (!(larger.stats.estimatedError < best.stats.estimatedError)) break;
    best = std::move(larger);
  }
  return best;
}

}  // namespace

BoundingPieces boundingMeshPieces(const TriangleMesh& mesh, const std::string& what,
                                  const LinkPieceOptions& options) {
  BoundingPieces bounding;
  if (!options.decompose) {
    ConvexHull hull = convexHull(mesh.vertices, what);
    const ConvexPiece piece{std::move(hull.mesh), std::move(hull.planes)};
    bounding.boundingError = measureDecomposition(mesh, std::span(&piece, 1), kHullErrorSamples,
                                                  options.decomposition.seed)
                                 .approximationToOriginal.max;
    bounding.pieces.push_back(piece.vertices());
    return bounding;
  }
  Decomposition decomposition;
  try {
    decomposition = decompositionReachingEpsilon(mesh, options);
  } catch (const InputError& error) {
    throw InputError(what + ": " + error.what());
  }
  for (const ConvexPiece& piece : decomposition.pieces) bounding.pieces.push_back(piece.vertices());
  bounding.boundingError = decomposition.stats.estimatedError;
  return bounding;
}

std::vector<std::vector<Vec3>> boundingConvexPieces(const TriangleMesh& mesh,
                                                    const std::string& what,
                                                    const LinkPieceOptions& options) {
  return boundingMeshPieces(mesh, what, options).pieces;
}

TriangleMesh shapeMesh(const CollisionShape& shape, const LinkMeshes& meshes) {
  const auto found = meshes.find(shape.meshPath);
  if (found == meshes.end()) {
    throw InputError(shape.meshPath + ": collision mesh not loaded (io::readCollisionMeshes)");
  }
  TriangleMesh mesh = found->second;
  for (Vec3& v : mesh.vertices) v = v.cwiseProduct(shape.size);
  return mesh;
}

BoundingPieces boundingShapePieces(const CollisionShape& shape, const LinkMeshes& meshes,
                                   const LinkPieceOptions& options) {
  BoundingPieces bounding;
  std::vector<std::vector<Vec3>>& pieces = bounding.pieces;
  switch (shape.kind) {
    case CollisionShape::Kind::Box: {
      std::vector<Vec3> corners;
      for (int i = 0; i < 8; ++i) {
        corners.emplace_back((i & 1 ? 0.5 : -0.5) * shape.size.x(),
                             (i & 2 ? 0.5 : -0.5) * shape.size.y(),
                             (i & 4 ? 0.5 : -0.5) * shape.size.z());
      }
      pieces.push_back(std::move(corners));
      break;
    }
    case CollisionShape::Kind::Cylinder: {
      const double r = shape.radius / std::cos(std::numbers::pi / kCylinderSides);
      std::vector<Vec3> prism;
      for (int i = 0; i < kCylinderSides; ++i) {
        const double a = 2 * std::numbers::pi * i / kCylinderSides;
        for (double z : {-0.5 * shape.length, 0.5 * shape.length}) {
          prism.emplace_back(r * std::cos(a), r * std::sin(a), z);
        }
      }
      pieces.push_back(std::move(prism));
      bounding.boundingError = r - shape.radius;  // at the prism's side edges
      break;
    }
    case CollisionShape::Kind::Sphere: {
      std::vector<Vec3> points = geodesicSphere();
      double inradius = 1;
      for (const HullPlane& plane : convexHull(points, "sphere").planes) {
        inradius = std::min(inradius, plane.offset);
      }
      for (Vec3& p : points) p *= shape.radius / inradius;
      pieces.push_back(std::move(points));
      bounding.boundingError = shape.radius / inradius - shape.radius;  // at the vertices
      break;
    }
    case CollisionShape::Kind::Mesh:
      bounding = boundingMeshPieces(shapeMesh(shape, meshes), shape.meshPath, options);
      break;
  }
  for (auto& piece : pieces) {
    for (Vec3& v : piece) v = shape.origin * v;
  }
  return bounding;
}

std::vector<std::vector<Vec3>> shapeConvexPieces(const CollisionShape& shape,
                                                 const LinkMeshes& meshes,
                                                 const LinkPieceOptions& options) {
  return boundingShapePieces(shape, meshes, options).pieces;
}

RobotCollisionModel::RobotCollisionModel(RobotModel model, const LinkMeshes& meshes,
                                         const LinkPieceOptions& pieceOptions)
    : model_(std::move(model)) {
  const auto& links = model_.links();
  std::vector<int> partOfLink(links.size(), -1);
  shapeBoundingErrors_.resize(links.size());
  for (std::size_t l = 0; l < links.size(); ++l) {
    std::vector<std::vector<Vec3>> pieces;
    for (const CollisionShape& shape : links[l].collisions) {
      BoundingPieces bounding = boundingShapePieces(shape, meshes, pieceOptions);
      for (auto& piece : bounding.pieces) pieces.push_back(std::move(piece));
      shapeBoundingErrors_[l].push_back(bounding.boundingError);
    }
    if (pieces.empty()) continue;
    partOfLink[l] = static_cast<int>(parts_.size());
    parts_.push_back({std::make_shared<const CollisionBody>(pieces, "link " + links[l].name),
                      static_cast<int>(l), Pose::Identity()});
  }
  filter_ = CollisionFilter(parts_.size());
  for (const Attachment& part : parts_) {
    int link = part.link;
    while (links[static_cast<std::size_t>(link)].parentJoint >= 0) {
      link =
          model_
              .joints()[static_cast<std::size_t>(links[static_cast<std::size_t>(link)].parentJoint)]
              .parentLink;
      if (partOfLink[static_cast<std::size_t>(link)] >= 0) {
        filter_.allow(static_cast<std::size_t>(partOfLink[static_cast<std::size_t>(part.link)]),
                      static_cast<std::size_t>(partOfLink[static_cast<std::size_t>(link)]));
        break;
      }
    }
  }
}

void RobotCollisionModel::checkHeld(std::span<const Attachment> held) const {
  for (const Attachment& object : held) {
    if (object.link < 0 || static_cast<std::size_t>(object.link) >= model_.links().size()) {
      throw std::out_of_range("held object on no link " + std::to_string(object.link));
    }
    if (!object.body) throw std::invalid_argument("held object without a body");
  }
}

std::size_t RobotCollisionModel::allowPairsCollidingAt(std::span<const Pose> linkPoses,
                                                       double margin) {
  std::size_t allowed = 0;
  for (std::size_t i = 0; i < parts_.size(); ++i) {
    for (std::size_t j = i + 1; j < parts_.size(); ++j) {
      if (!filter_.allowed(i, j) &&
          bodiesCollide(*parts_[i].body, partPose(i, linkPoses), *parts_[j].body,
                        partPose(j, linkPoses), margin)) {
        filter_.allow(i, j);
        ++allowed;
      }
    }
  }
  return allowed;
}

std::optional<std::pair<std::size_t, std::size_t>> RobotCollisionModel::firstSelfCollision(
    std::span<const Pose> linkPoses, std::span<const Attachment> held, double margin) const {
  checkHeld(held);
  const std::size_t count = partCount(held);
  for (std::size_t i = 0; i < count; ++i) {
    const CollisionBody& bodyI = *part(i, held).body;
    const Pose poseI = partPose(i, linkPoses, held);
    for (std::size_t j = i + 1; j < count; ++j) {
      if (checksPair(i, j, held) &&
          bodiesCollide(bodyI, poseI, *part(j, held).body, partPose(j, linkPoses, held), margin)) {
        return std::pair{i, j};
      }
    }
  }
  return std::nullopt;
}

std::optional<std::size_t> RobotCollisionModel::firstSceneCollision(
    std::span<const Pose> linkPoses, std::span<const Attachment> held, const CollisionScene& scene,
    std::span<const Placement> sceneState, double margin) const {
  checkHeld(held);
  for (std::size_t i = 0; i < partCount(held); ++i) {
    if (auto hit = scene.firstCollision(sceneState, *part(i, held).body,
                                        partPose(i, linkPoses, held), margin)) {
      return hit;
    }
  }
  return std::nullopt;
}

}  // namespace kaboum::collision
