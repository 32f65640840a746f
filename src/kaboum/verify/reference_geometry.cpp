#include "kaboum/verify/reference_geometry.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/urdf_loader.hpp"

namespace kaboum::verify {

namespace {

// One collision shape of a body, its frame in the body frame, and a sphere (in the body frame)
// that contains it.
struct ReferenceShape {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  Pose inBody = Pose::Identity();
  Vec3 centre{0, 0, 0};
  double radius = 0;
  std::size_t triangles = 0;
};

struct ReferenceBody {
  std::vector<ReferenceShape> shapes;
};

std::shared_ptr<fcl::CollisionGeometryd> meshModel(const TriangleMesh& mesh, const Vec3& scale) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points;
  for (const Vec3& v : mesh.vertices) points.emplace_back(v.cwiseProduct(scale));
  std::vector<fcl::Triangle> triangles;
  for (const Triangle& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}

// The smallest sphere about the box centre of `mesh` scaled by `scale` that contains it.
std::pair<Vec3, double> meshSphere(const TriangleMesh& mesh, const Vec3& scale) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v.cwiseProduct(scale));
    hi = hi.cwiseMax(v.cwiseProduct(scale));
  }
  const Vec3 centre = (lo + hi) / 2;
  double radius = 0;
  for (const Vec3& v : mesh.vertices) {
    radius = std::max(radius, (v.cwiseProduct(scale) - centre).norm());
  }
  return {centre, radius};
}

// `shape` (a URDF or scene collision shape, its origin in the body frame) as FCL geometry; meshes
// taken from `meshes` by path.
ReferenceShape referenceShape(const CollisionShape& shape,
                              const std::map<std::string, TriangleMesh>& meshes) {
  ReferenceShape result;
  result.inBody = shape.origin;
  switch (shape.kind) {
    case CollisionShape::Kind::Box:
      result.geometry = std::make_shared<fcl::Boxd>(shape.size.x(), shape.size.y(), shape.size.z());
      result.radius = shape.size.norm() / 2;
      break;
    case CollisionShape::Kind::Cylinder:
      result.geometry = std::make_shared<fcl::Cylinderd>(shape.radius, shape.length);
      result.radius = std::hypot(shape.radius, shape.length / 2);
      break;
    case CollisionShape::Kind::Sphere:
      result.geometry = std::make_shared<fcl::Sphered>(shape.radius);
      result.radius = shape.radius;
      break;
    case CollisionShape::Kind::Mesh: {
      const TriangleMesh& mesh = meshes.at(shape.meshPath);
      result.geometry = meshModel(mesh, shape.size);
      const auto [centre, radius] = meshSphere(mesh, shape.size);
      result.centre = centre;
      result.radius = radius;
      result.triangles = mesh.triangles.size();
      break;
    }
  }
  result.centre = shape.origin * result.centre;
  return result;
}

double lowerBoundOfDistance(const ReferenceShape& a, const Pose& poseA, const ReferenceShape& b,
                            const Pose& poseB) {
  return ((poseA * a.centre) - (poseB * b.centre)).norm() - a.radius - b.radius;
}

bool shapesCollide(const ReferenceShape& a, const Pose& transformA, const ReferenceShape& b,
                   const Pose& transformB) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd collision;
  fcl::collide(a.geometry.get(), transformA, b.geometry.get(), transformB, request, collision);
  return collision.isCollision();
}

}  // namespace

struct ReferenceGeometry::Bodies {
  std::vector<ReferenceBody> bodies;
  std::vector<std::vector<std::optional<std::size_t>>> linkBodies;  // by robot, by link
  std::vector<std::size_t> objectBodies;                            // by object id
  double seconds = 0;
};

ReferenceGeometry::ReferenceGeometry(const World& world) : world_(world) {
  const auto start = std::chrono::steady_clock::now();
  auto bodies = std::make_unique<Bodies>();
  for (const WorldRobot& robot : world.robots()) {
    const RobotModel& model = robot.collision.model();
    const std::map<std::string, TriangleMesh> meshes = io::readCollisionMeshes(model);
    std::vector<std::optional<std::size_t>>& links = bodies->linkBodies.emplace_back();
    for (const Link& link : model.links()) {
      if (link.collisions.empty()) {
        links.emplace_back();
        continue;
      }
      ReferenceBody body;
      for (const CollisionShape& shape : link.collisions) {
        body.shapes.push_back(referenceShape(shape, meshes));
      }
      links.push_back(bodies->bodies.size());
      bodies->bodies.push_back(std::move(body));
    }
  }
  for (const ObjectSpec& object : world.description().objects) {
    std::map<std::string, TriangleMesh> meshes;
    const CollisionShape& shape = object.geometry.shape;
    if (shape.kind == CollisionShape::Kind::Mesh) {
      meshes.emplace(shape.meshPath, io::readMesh(shape.meshPath));
    }
    bodies->objectBodies.push_back(bodies->bodies.size());
    bodies->bodies.push_back({{referenceShape(shape, meshes)}});
  }
  bodies->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bodies_ = std::move(bodies);
}

ReferenceGeometry::~ReferenceGeometry() = default;

std::optional<std::size_t> ReferenceGeometry::linkBody(std::size_t robot, std::size_t link) const {
  return bodies_->linkBodies.at(robot).at(link);
}

std::size_t ReferenceGeometry::objectBody(std::size_t object) const {
  return bodies_->objectBodies.at(object);
}

Proximity ReferenceGeometry::proximity(std::size_t a, const Pose& poseA, std::size_t b,
                                       const Pose& poseB, double distanceOfInterest) const {
  Proximity result{false, std::numeric_limits<double>::infinity()};
  for (const ReferenceShape& shapeA : bodies_->bodies.at(a).shapes) {
    for (const ReferenceShape& shapeB : bodies_->bodies.at(b).shapes) {
      const double lowerBound = lowerBoundOfDistance(shapeA, poseA, shapeB, poseB);
      if (lowerBound > 0 && lowerBound >= std::min(distanceOfInterest, result.distance)) continue;
      const Pose transformA = poseA * shapeA.inBody, transformB = poseB * shapeB.inBody;
      if (lowerBound <= 0 && shapesCollide(shapeA, transformA, shapeB, transformB)) {
        return {true, 0.0};
      }
      if (lowerBound >= std::min(distanceOfInterest, result.distance)) continue;
      fcl::DistanceRequestd request;
      // Starting from the distance of interest, FCL's bounding-volume traversal prunes every pair
      // of nodes at least that far apart: a farther pair costs a few node tests, not a search.
      const double bound = std::min(distanceOfInterest, result.distance);
      fcl::DistanceResultd distance;
      distance.min_distance = bound;
      fcl::distance(shapeA.geometry.get(), transformA, shapeB.geometry.get(), transformB, request,
                    distance);
      if (distance.min_distance < bound) result.distance = std::max(0.0, distance.min_distance);
    }
  }
  return result;
}

bool ReferenceGeometry::collides(std::size_t a, const Pose& poseA, std::size_t b,
                                 const Pose& poseB) const {
  for (const ReferenceShape& shapeA : bodies_->bodies.at(a).shapes) {
    for (const ReferenceShape& shapeB : bodies_->bodies.at(b).shapes) {
      if (lowerBoundOfDistance(shapeA, poseA, shapeB, poseB) <= 0 &&
          shapesCollide(shapeA, poseA * shapeA.inBody, shapeB, poseB * shapeB.inBody)) {
        return true;
      }
    }
  }
  return false;
}

std::size_t ReferenceGeometry::triangleCount() const {
  std::size_t triangles = 0;
  for (const ReferenceBody& body : bodies_->bodies) {
    for (const ReferenceShape& shape : body.shapes) triangles += shape.triangles;
  }
  return triangles;
}

double ReferenceGeometry::buildSeconds() const {
  return bodies_->seconds;
}

}  // namespace kaboum::verify
