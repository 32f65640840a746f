#include "kaboum/world/placement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <variant>

#include "kaboum/kinematics/random_configuration.hpp"
#include "kaboum/world/state_predicates.hpp"

namespace kaboum::world {

namespace {

// The resolution (metres) of the bisection that finds the lowest free height of a placement.
constexpr double kBisectionStep = 1e-4;

// How far (metres) a support probe may pass beside a piece and still rest on it: the probes from
// the corners of a block stacked flush on an equal block run down the edges of the lower one.
constexpr double kProbeMargin = 1e-5;

// A hull facet whose world normal has at least this z faces up: a support face (within 1°).
const double kUpwardFacet = std::cos(std::numbers::pi / 180);

const Vec3 kUp{0, 0, 1};

// Metres: a line parallel to a facet plane this close to it lies on it (a raycast down the edge of
// a block's side).
constexpr double kOnPlane = 1e-9;

// The parameters t where origin + t·direction lies in every half-space n·x <= offset, as
// [low, high]; nullopt when none.
std::optional<std::pair<double, double>> lineInterval(std::span<const HullPlane> planes,
                                                      const Vec3& origin, const Vec3& direction) {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  for (const HullPlane& plane : planes) {
    const double along = plane.normal.dot(direction);
    const double room = plane.offset - plane.normal.dot(origin);
    if (std::abs(along) < 1e-12) {
      if (room < -kOnPlane) return std::nullopt;  // parallel: on the plane counts as inside
    } else if (along > 0) {
      high = std::min(high, room / along);
    } else {
      low = std::max(low, room / along);
    }
  }
  if (low > high) return std::nullopt;
  return std::pair{low, high};
}

// The vertical line through world (x, y) as an interval of world heights in `planes`, given in
// the frame `pose` of their body.
std::optional<std::pair<double, double>> verticalInterval(std::span<const HullPlane> planes,
                                                          const Pose& pose, double x, double y) {
  const Eigen::Matrix3d toBody = pose.linear().transpose();
  return lineInterval(planes, toBody * (Vec3(x, y, 0) - pose.translation()), toBody * kUp);
}

// A box region's eight corners, or a hull region's points, in the world frame.
std::vector<Vec3> regionPoints(const std::variant<BoxRegion, HullRegion>& region) {
  std::vector<Vec3> points;
  if (const auto* box = std::get_if<BoxRegion>(&region)) {
    for (int corner = 0; corner < 8; ++corner) {
      points.push_back(box->pose * Vec3((corner & 1) ? box->upper.x() : box->lower.x(),
                                        (corner & 2) ? box->upper.y() : box->lower.y(),
                                        (corner & 4) ? box->upper.z() : box->lower.z()));
    }
  } else {
    const auto& hull = std::get<HullRegion>(region);
    for (const Vec3& p : hull.points) points.push_back(hull.pose * p);
  }
  return points;
}

const Pose& regionFrame(const std::variant<BoxRegion, HullRegion>& region) {
  return std::visit([](const auto& r) -> const Pose& { return r.pose; }, region);
}

std::vector<Vec3> pieceVertices(const CollisionBody& body) {
  std::vector<Vec3> vertices;
  for (std::size_t p = 0; p < body.pieceCount(); ++p) {
    const auto& piece = body.piece(p).vertices();
    vertices.insert(vertices.end(), piece.begin(), piece.end());
  }
  return vertices;
}

// The centroid of the solid a closed, outward-oriented mesh bounds.
Vec3 solidCentroid(const TriangleMesh& mesh) {
  const Vec3 reference = mesh.vertices.front();
  Vec3 weighted = Vec3::Zero();
  double volume = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const double tetra = (a - reference).dot((b - reference).cross(c - reference)) / 6;
    weighted += tetra * (reference + a + b + c) / 4;
    volume += tetra;
  }
  return weighted / volume;
}

// One facet of a convex hull: its plane, area and centroid, and its triangles' directed edges.
struct Facet {
  HullPlane plane;
  double area = 0;
  Vec3 centroid{0, 0, 0};
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
};

// The facets of `hull`, one per plane: the triangles whose normal is the plane's.
std::vector<Facet> hullFacets(const ConvexHull& hull) {
  std::vector<Facet> facets;
  for (const HullPlane& plane : hull.planes) {
    Facet& facet = facets.emplace_back();
    facet.plane = plane;
    Vec3 weighted = Vec3::Zero();
    for (const Triangle& t : hull.mesh.triangles) {
      const Vec3& a = hull.mesh.vertices[t[0]];
      const Vec3& b = hull.mesh.vertices[t[1]];
      const Vec3& c = hull.mesh.vertices[t[2]];
      const Vec3 cross = (b - a).cross(c - a);
      if (cross.norm() == 0 || cross.normalized().dot(plane.normal) < 1 - 1e-9) continue;
      facet.area += 0.5 * cross.norm();
      weighted += 0.5 * cross.norm() * (a + b + c) / 3;
      for (int k = 0; k < 3; ++k) facet.edges.emplace(t[k], t[(k + 1) % 3]);
    }
    if (facet.area > 0) facet.centroid = weighted / facet.area;
  }
  return facets;
}

// A hull facet whose outward normal, turned to −z, rests the hull's centroid strictly inside it.
struct StableFacet {
  Vec3 normal;
  double area = 0;
};

// The stable facets of the convex hull of `points`, largest first (ties in facet order).
std::vector<StableFacet> stableFacets(std::span<const Vec3> points, const std::string& what) {
  const ConvexHull hull = convexHull(points, what);
  const Vec3 centroid = solidCentroid(hull.mesh);
  const double size = (hull.mesh.vertices.front() - centroid).norm();
  std::vector<StableFacet> stable;
  for (const Facet& facet : hullFacets(hull)) {
    const HullPlane& plane = facet.plane;
    const Vec3 foot = centroid - (plane.normal.dot(centroid) - plane.offset) * plane.normal;
    bool inside = true;
    for (const auto& [from, to] : facet.edges) {
      if (facet.edges.contains({to, from})) continue;  // inside the facet, not on its boundary
      const Vec3& a = hull.mesh.vertices[from];
      const Vec3& b = hull.mesh.vertices[to];
      // Outward triangles turn counter-clockwise about the normal: the inside is to the left.
      inside = inside && (b - a).cross(foot - a).dot(plane.normal) > 1e-9 * size * size;
    }
    if (inside) stable.push_back({plane.normal, facet.area});
  }
  std::stable_sort(stable.begin(), stable.end(),
                   [](const StableFacet& a, const StableFacet& b) { return a.area > b.area; });
  return stable;
}

// The outward normals of an object's resting faces (see PlacementGeometry::restingFaces).
std::vector<Vec3> restingNormals(const ObjectSpec& spec, const CollisionBody& body) {
  if (!spec.restingFaces.automatic) return spec.restingFaces.normals;
  const CollisionShape& shape = spec.geometry.shape;
  if (shape.kind == CollisionShape::Kind::Sphere) return {};
  const Vec3 axis = shape.origin.linear() * kUp;
  std::vector<Vec3> normals;
  for (const StableFacet& facet : stableFacets(pieceVertices(body), "object " + spec.name)) {
    if (shape.kind == CollisionShape::Kind::Cylinder &&
        std::abs(facet.normal.dot(axis)) < 1 - 1e-9) {
      continue;
    }
    normals.push_back(facet.normal);
  }
  return normals;
}

RestingFace restingFace(const CollisionBody& body, const Vec3& normal, double band) {
  RestingFace face;
  face.normal = normal.normalized();
  face.down = Eigen::Quaterniond::FromTwoVectors(face.normal, -kUp);
  const std::vector<Vec3> vertices = pieceVertices(body);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : vertices) lowest = std::min(lowest, (face.down * v).z());
  face.height = -lowest;
  for (const Vec3& v : vertices) {
    const Vec3 turned = face.down * v + Vec3(0, 0, face.height);
    if (turned.z() <= band) face.bottom.push_back(turned);
  }
  for (const Vec3& b : face.bottom) face.centre += b / static_cast<double>(face.bottom.size());
  return face;
}

// The positions freeSpaceFound samples over a footprint of width × depth (SearchStrategy).
class FootprintSampler {
 public:
  FootprintSampler(const FreeSpaceOptions& options, double width, double depth)
      : options_(options), rng_(options.seed) {
    const auto gridOf = [&](double extent) {
      const auto count =
          static_cast<std::size_t>(std::floor(extent / options.resolution + 1e-9)) + 1;
      return std::pair{count, (extent - static_cast<double>(count - 1) * options.resolution) / 2};
    };
    std::tie(columns_, marginX_) = gridOf(width);
    std::tie(rows_, marginY_) = gridOf(depth);
    width_ = width;
    depth_ = depth;
  }

  // The k-th position (k counting from 0) in the footprint's box [0, width] × [0, depth], with
  // its yaw offset.
  [[nodiscard]] std::optional<std::array<double, 3>> next(std::size_t k) {
    switch (options_.strategy) {
      case SearchStrategy::Linear: {
        if (k >= columns_ * rows_) return std::nullopt;
        const auto step = [&](std::size_t i) {
          return static_cast<double>(i) * options_.resolution;
        };
        return std::array{marginX_ + step(k % columns_), marginY_ + step(k / columns_), 0.0};
      }
      case SearchStrategy::Quadtree: {
        std::size_t level = 0, first = 0;
        while (k - first >= (std::size_t{1} << (2 * level))) {
          first += std::size_t{1} << (2 * level);
          ++level;
        }
        std::size_t cell = k - first, i = 0, j = 0;
        for (std::size_t bit = 0; bit < level; ++bit) {  // Morton order: x bits even, y bits odd
          i |= ((cell >> (2 * bit)) & 1) << bit;
          j |= ((cell >> (2 * bit + 1)) & 1) << bit;
        }
        const double cells = std::ldexp(1.0, static_cast<int>(level));
        return std::array{(static_cast<double>(i) + 0.5) / cells * width_,
                          (static_cast<double>(j) + 0.5) / cells * depth_, 0.0};
      }
      case SearchStrategy::Random: {
        const double u = kinematics::uniformUnit(rng_);
        const double v = kinematics::uniformUnit(rng_);
        return std::array{u * width_, v * depth_,
                          2 * std::numbers::pi * kinematics::uniformUnit(rng_)};
      }
    }
    return std::nullopt;
  }

 private:
  const FreeSpaceOptions& options_;
  std::mt19937_64 rng_;
  std::size_t columns_ = 1, rows_ = 1;
  double marginX_ = 0, marginY_ = 0, width_ = 0, depth_ = 0;
};

}  // namespace

Pose restingPose(const RestingFace& face, double x, double y, double planeZ, double yaw) {
  Pose pose = Pose::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, kUp) * face.down).toRotationMatrix();
  pose.translation() = Vec3(x, y, planeZ + face.height);
  return pose;
}

PlacementGeometry::PlacementGeometry(const World& world) : world_(world) {
  for (const LocationSpec& spec : world.description().locations) {
    const std::vector<Vec3> points = regionPoints(spec.region);
    LocationGeometry location{ConvexContainer(points, "location " + spec.name),
                              regionFrame(spec.region),
                              Vec3::Constant(std::numeric_limits<double>::infinity()),
                              Vec3::Constant(-std::numeric_limits<double>::infinity()),
                              -std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::infinity(),
                              spec.supportSurface};
    for (const Vec3& p : points) {
      const Vec3 local = location.frame.inverse() * p;
      location.lower = location.lower.cwiseMin(local);
      location.upper = location.upper.cwiseMax(local);
      location.top = std::max(location.top, p.z());
      location.bottom = std::min(location.bottom, p.z());
    }
    locations_.push_back(std::move(location));
  }
  const CollisionScene& scene = world.scene();
  for (const BodyEpsilon& epsilon : world.objectEpsilon()) {
    largestEpsilon_ = std::max({largestEpsilon_, epsilon.asked, epsilon.reached});
  }
  for (std::size_t o = 0; o < scene.size(); ++o) {
    const CollisionBody& body = scene.body(o);
    ObjectGeometry& object = objects_.emplace_back();
    for (std::size_t p = 0; p < body.pieceCount(); ++p) {
      object.piecePlanes.push_back(
          convexHull(body.piece(p).vertices(), "object " + scene.name(o)).planes);
    }
    for (const Facet& facet :
         hullFacets(convexHull(pieceVertices(body), "object " + scene.name(o)))) {
      object.facets.push_back({facet.plane.normal, facet.centroid});
    }
    if (!scene.movable(o)) continue;
    for (const Vec3& normal : restingNormals(world.description().objects[o], body)) {
      object.faces.push_back(restingFace(body, normal, supportTolerance(o).band));
    }
  }
}

SupportTolerance PlacementGeometry::supportTolerance(std::size_t object) const {
  const BodyEpsilon& epsilon = world_.objectEpsilon().at(object);
  const double own = std::max(epsilon.asked, epsilon.reached);
  return {own, 2 * own + largestEpsilon_ + world_.restingGap() + kBisectionStep};
}

std::optional<Pose> PlacementGeometry::poseIn(const GeometricState& state,
                                              std::size_t object) const {
  const CollisionScene& scene = world_.scene();
  if (!scene.present(object, state.placements)) return std::nullopt;
  return scene.pose(object, state.placements);
}

bool PlacementGeometry::isInside(const GeometricState& state, std::size_t object,
                                 std::size_t location) const {
  const std::optional<Pose> pose = poseIn(state, object);
  return pose && isInside(object, *pose, location);
}

bool PlacementGeometry::isInside(std::size_t object, const Pose& pose, std::size_t location) const {
  return collision::isInside(world_.scene().body(object), pose, region(location), Pose::Identity());
}

bool PlacementGeometry::collides(const GeometricState& state, const QueryScratch& scratch,
                                 std::size_t object, const Pose& pose) const {
  if (const StatePredicates* predicates = world_.predicates()) {
    return predicates->firstCollisionOfObject(state, scratch, object, pose, true).has_value();
  }
  const CollisionBody& body = world_.scene().body(object);
  if (world_.scene().firstCollision(state.placements, body, pose, 0.0, object)) return true;
  const Vec3 centre = pose * body.bounds().centre;
  for (std::size_t r = 0; r < world_.robots().size(); ++r) {
    const RobotCollisionModel& model = world_.robots()[r].collision;
    const RobotState& robot = state.robots[r];
    for (std::size_t i = 0; i < model.partCount(robot.held); ++i) {
      if (i >= model.partCount() && robot.heldObjects[i - model.partCount()] == object) continue;
      const Attachment& part = model.part(i, robot.held);
      const Pose partPose = model.partPose(i, scratch.linkPoses[r], robot.held);
      if (spheresWithin(centre, body.bounds().radius, partPose * part.body->bounds().centre,
                        part.body->bounds().radius, 0.0) &&
          bodiesCollide(body, pose, *part.body, partPose, 0.0)) {
        return true;
      }
    }
  }
  return false;
}

std::optional<std::size_t> PlacementGeometry::floorOn(const SegmentSupport& segment) const {
  for (std::size_t l = 0; l < locations_.size(); ++l) {
    if (!locations_[l].supportSurface) continue;
    const auto interval = verticalInterval(locations_[l].region.planes(), Pose::Identity(),
                                           segment.a.x(), segment.a.y());
    if (interval && interval->first >= segment.b.z() && interval->first <= segment.a.z()) return l;
  }
  return std::nullopt;
}

std::optional<Support> PlacementGeometry::supportAt(const GeometricState& state,
                                                    const QueryScratch& scratch, std::size_t object,
                                                    const Pose& pose) const {
  if (collides(state, scratch, object, pose)) return std::nullopt;
  const SupportTolerance tolerance = supportTolerance(object);
  std::optional<Support> first;
  const bool supported =
      allBottomProbes(world_.scene().body(object), pose, tolerance.drop, tolerance.band,
                      [&](const SegmentSupport& segment) {
                        std::optional<Support> support;
                        if (const auto hit = probeTouches(world_.scene(), state.placements, segment,
                                                          object, kProbeMargin)) {
                          support = Support{Support::Kind::Object, *hit};
                        } else if (const auto floor = floorOn(segment)) {
                          support = Support{Support::Kind::Location, *floor};
                        }
                        if (!first) first = support;
                        return support.has_value();
                      });
  return supported ? first : std::nullopt;
}

std::optional<Support> PlacementGeometry::isOnSupportSurface(const GeometricState& state,
                                                             std::size_t object,
                                                             QueryScratch& scratch) const {
  const std::optional<Pose> pose = poseIn(state, object);
  if (!pose) return std::nullopt;
  return isOnSupportSurface(state, object, *pose, scratch);
}

std::optional<Support> PlacementGeometry::isOnSupportSurface(const GeometricState& state,
                                                             std::size_t object, const Pose& pose,
                                                             QueryScratch& scratch) const {
  world_.computeLinkPoses(state, scratch);
  return supportAt(state, scratch, object, pose);
}

std::optional<double> PlacementGeometry::supportHeight(const GeometricState& state,
                                                       std::size_t object, double x, double y,
                                                       double low, double high) const {
  double highest = -std::numeric_limits<double>::infinity();
  bool blocked = false;
  const Aabb column{Vec3(x, y, low), Vec3(x, y, high)};
  world_.scene().forEachPieceNear(
      state.placements, column, Vec3(x, y, 0.5 * (low + high)), 0.5 * (high - low), 0.0, object,
      [&](std::size_t other, std::size_t piece, const Pose& pose) {
        const auto interval = verticalInterval(objects_[other].piecePlanes[piece], pose, x, y);
        if (!interval || interval->second < low || interval->first > high) return true;
        blocked = interval->second > high;
        highest = std::max(highest, interval->second);
        return !blocked;
      });
  if (blocked) return std::nullopt;
  for (const LocationGeometry& location : locations_) {
    if (!location.supportSurface) continue;
    const auto interval = verticalInterval(location.region.planes(), Pose::Identity(), x, y);
    if (interval && interval->first >= low && interval->first <= high) {
      highest = std::max(highest, interval->first);
    }
  }
  if (highest == -std::numeric_limits<double>::infinity()) return std::nullopt;
  return highest;
}

FreeSpace PlacementGeometry::freeSpaceFound(const GeometricState& state, std::size_t object,
                                            std::size_t location, const FreeSpaceOptions& options,
                                            QueryScratch& scratch) const {
  if (object >= objects_.size() || !world_.scene().movable(object)) {
    throw std::invalid_argument("freeSpaceFound: object " + std::to_string(object) +
                                " is not a movable object");
  }
  if (!(options.resolution > 0) || options.yawCount == 0) {
    throw std::invalid_argument("freeSpaceFound: the resolution and yaw count must be positive");
  }
  if (location >= locations_.size()) {
    throw std::invalid_argument("freeSpaceFound: no location " + std::to_string(location));
  }
  world_.computeLinkPoses(state, scratch);
  const LocationGeometry& where = locations_[location];
  const std::span<const RestingFace> faces = restingFaces(object);
  const double low = where.bottom - supportTolerance(object).drop;
  const Vec3 axisX = where.frame.linear().col(0);
  const double frameYaw = std::atan2(axisX.y(), axisX.x());
  FootprintSampler sampler(options, where.upper.x() - where.lower.x(),
                           where.upper.y() - where.lower.y());
  // The downward raycast: the highest support under the face's bottom vertices turned by `turn`
  // about `position`; nullopt when one of them has none.
  const auto restingPlane = [&](const RestingFace& face, const Vec3& position,
                                const Eigen::Matrix2d& turn) -> std::optional<double> {
    double plane = -std::numeric_limits<double>::infinity();
    for (const Vec3& b : face.bottom) {
      const Eigen::Vector2d at = position.head<2>() + turn * b.head<2>();
      const std::optional<double> height =
          supportHeight(state, object, at.x(), at.y(), low, where.top);
      if (!height) return std::nullopt;
      plane = std::max(plane, *height);
    }
    return plane;
  };
  // The face down at `position` turned by `yaw`, its pieces the World's resting gap above
  // `plane`; where that collides (a support between the raycast's columns), the resting gap above
  // the lowest height found free by bisection to kBisectionStep between there and the face on the
  // region's top (nullopt when that collides too).
  const auto settled = [&](const RestingFace& face, const Vec3& position, double yaw,
                           double plane) -> std::optional<Pose> {
    const auto posed = [&](double height) {
      return restingPose(face, position.x(), position.y(), height, yaw);
    };
    const double gap = world_.restingGap();
    double below = plane + gap;
    if (!collides(state, scratch, object, posed(below))) return posed(below);
    double above = std::max(below, where.top);
    if (collides(state, scratch, object, posed(above))) return std::nullopt;
    while (above - below > kBisectionStep) {
      const double middle = 0.5 * (above + below);
      (collides(state, scratch, object, posed(middle)) ? below : above) = middle;
    }
    return posed(above + gap);
  };
  FreeSpace result;
  // Every resting face and yaw at one position: the object frame over `position`, or with
  // `centred` the face's centre; true when one of them is a placement (in `result`).
  const auto placeAt = [&](const Vec3& position, double yawOffset, bool centred) {
    const std::size_t faceCount = options.faces.empty() ? faces.size() : options.faces.size();
    for (std::size_t i = 0; i < faceCount; ++i) {
      const std::size_t f = options.faces.empty() ? i : options.faces[i];
      if (f >= faces.size()) {
        throw std::invalid_argument("object '" + world_.scene().name(object) + "' has no face " +
                                    std::to_string(f));
      }
      for (std::size_t k = 0; k < options.yawCount; ++k) {
        const double yaw =
            frameYaw + yawOffset +
            2 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(options.yawCount);
        const Eigen::Matrix2d turn = Eigen::Rotation2Dd(yaw).toRotationMatrix();
        Vec3 origin = position;
        if (centred) origin.head<2>() -= turn * faces[f].centre.head<2>();
        const std::optional<double> plane = restingPlane(faces[f], origin, turn);
        if (!plane) continue;
        const std::optional<Pose> pose = settled(faces[f], origin, yaw, *plane);
        if (!pose || !isInside(object, *pose, location)) continue;
        if (const auto support = supportAt(state, scratch, object, *pose)) {
          result.pose = *pose;
          result.support = *support;
          result.face = f;
          return true;
        }
      }
    }
    return false;
  };
  for (; result.samples < options.maxSamples; ++result.samples) {
    const auto sample = sampler.next(result.samples);
    if (!sample) break;
    const Vec3 position =
        where.frame * Vec3(where.lower.x() + (*sample)[0], where.lower.y() + (*sample)[1], 0);
    if (placeAt(position, (*sample)[2], false)) {
      ++result.samples;
      return result;
    }
  }
  // The support faces of the objects standing in the location: facets of their hulls facing up
  // whose centroid lies in the region's column (the top of a can, of a block).
  const double drop = supportTolerance(object).drop;
  for (std::size_t other = 0; other < objects_.size(); ++other) {
    const std::optional<Pose> pose = other == object ? std::nullopt : poseIn(state, other);
    if (!pose) continue;
    for (const HullFacet& facet : objects_[other].facets) {
      if ((pose->linear() * facet.normal).z() < kUpwardFacet) continue;
      const Vec3 centre = *pose * facet.centroid;
      const auto column =
          verticalInterval(where.region.planes(), Pose::Identity(), centre.x(), centre.y());
      if (!column || centre.z() < column->first - drop || centre.z() > column->second) continue;
      ++result.samples;
      if (placeAt(centre, 0, true)) return result;
    }
  }
  return result;
}

std::optional<std::size_t> PlacementGeometry::objectOnTop(const GeometricState& state,
                                                          std::size_t object) const {
  const std::optional<Pose> below = poseIn(state, object);
  if (!below) return std::nullopt;
  const CollisionScene& scene = world_.scene();
  const CollisionBody& base = scene.body(object);
  const Vec3 baseCentre = *below * base.bounds().centre;
  for (std::size_t other = 0; other < scene.size(); ++other) {
    if (other == object || !scene.movable(other)) continue;
    const std::optional<Pose> pose = poseIn(state, other);
    if (!pose) continue;
    const CollisionBody& body = scene.body(other);
    const SupportTolerance tolerance = supportTolerance(other);
    if (!spheresWithin(*pose * body.bounds().centre, body.bounds().radius, baseCentre,
                       base.bounds().radius, tolerance.drop)) {
      continue;
    }
    bool touches = false;
    allBottomProbes(body, *pose, tolerance.drop, tolerance.band, [&](const SegmentSupport& probe) {
      for (std::size_t p = 0; p < base.pieceCount() && !touches; ++p) {
        touches = intersects(probe, TransformedSupport(base.piece(p), *below), kProbeMargin);
      }
      return !touches;
    });
    if (touches) return other;
  }
  return std::nullopt;
}

}  // namespace kaboum::world
