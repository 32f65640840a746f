// The placement predicates (seed 003 §III-B): isInside, isOnSupportSurface, resting faces and
// freeSpaceFound, on tests/data/placement-cell.yaml; placements checked on the original geometry
// (the objects' exact vertices, FCL on the original shapes).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/testing/data_paths.hpp"
#include "kaboum/verify/reference_geometry.hpp"
#include "kaboum/world/placement.hpp"

namespace kaboum::world {

using namespace kaboum::testing;

namespace {

const World& cell() {
  static const World world(readSceneFile(sourceFile("tests/data/placement-cell.yaml")));
  return world;
}

const PlacementGeometry& placements() {
  static const PlacementGeometry geometry(cell());
  return geometry;
}

const verify::ReferenceGeometry& reference() {
  static const verify::ReferenceGeometry geometry(cell());
  return geometry;
}

std::size_t id(const std::string& name) {
  return cell().find(name).value().index;
}

Pose at(double x, double y, double z, double yaw = 0) {
  Pose pose = Pose::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  pose.translation() = Vec3(x, y, z);
  return pose;
}

// The initial state with `object` at `pose`.
GeometricState with(std::size_t object, const Pose& pose,
                    GeometricState state = cell().initialState()) {
  state.placements[cell().scene().slot(object)].pose = pose;
  return state;
}

Support onObject(const std::string& name) {
  return {Support::Kind::Object, id(name)};
}

Support onLocation(const std::string& name) {
  return {Support::Kind::Location, id(name)};
}

// Points of an object's original geometry in its frame: a box's corners, the crate mesh's
// vertices, 64 points on each rim of the can.
std::vector<Vec3> originalPoints(const World& world, std::size_t object) {
  const CollisionShape& shape = world.description().objects[object].geometry.shape;
  std::vector<Vec3> points;
  switch (shape.kind) {
    case CollisionShape::Kind::Box:
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3 sign((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1, (corner & 4) ? 1 : -1);
        points.push_back(shape.origin * (0.5 * sign.cwiseProduct(shape.size)));
      }
      break;
    case CollisionShape::Kind::Mesh:
      for (const Vec3& v : io::readMesh(shape.meshPath).vertices) {
        points.push_back(shape.origin * v.cwiseProduct(shape.size));
      }
      break;
    case CollisionShape::Kind::Cylinder:
      for (int k = 0; k < 64; ++k) {
        const double angle = 2 * std::numbers::pi * k / 64;
        for (const double z : {-0.5, 0.5}) {
          points.push_back(shape.origin * Vec3(shape.radius * std::cos(angle),
                                               shape.radius * std::sin(angle), z * shape.length));
        }
      }
      break;
    case CollisionShape::Kind::Sphere:
      ADD_FAILURE() << "no sphere in the scene";
  }
  return points;
}

// Whether world point p lies in the region of location `location`: a box by its bounds, a hull
// by the facets of its points.
bool inRegion(const World& world, std::size_t location, const Vec3& p) {
  const auto& region = world.description().locations[location].region;
  if (const auto* box = std::get_if<BoxRegion>(&region)) {
    const Vec3 local = box->pose.inverse() * p;
    return (local.array() >= box->lower.array()).all() &&
           (local.array() <= box->upper.array()).all();
  }
  const auto& hull = std::get<HullRegion>(region);
  const Vec3 local = hull.pose.inverse() * p;
  const ConvexContainer container(hull.points);
  return std::all_of(
      container.planes().begin(), container.planes().end(),
      [&](const HullPlane& plane) { return plane.normal.dot(local) <= plane.offset; });
}

bool originalInside(const World& world, std::size_t object, const Pose& pose,
                    std::size_t location) {
  for (const Vec3& p : originalPoints(world, object)) {
    if (!inRegion(world, location, pose * p)) return false;
  }
  return true;
}

// The first collision of object `object` at `pose` with another present object or a robot link
// in `state`, by FCL on the original geometry; empty when there is none.
std::string exactCollision(const verify::ReferenceGeometry& reference, const GeometricState& state,
                           std::size_t object, const Pose& pose) {
  const World& world = reference.world();
  const std::size_t body = reference.objectBody(object);
  for (std::size_t other = 0; other < world.scene().size(); ++other) {
    if (other == object || !world.scene().present(other, state.placements)) continue;
    if (reference
            .proximity(body, pose, reference.objectBody(other),
                       world.scene().pose(other, state.placements), 0.0)
            .collides) {
      return world.scene().name(other);
    }
  }
  for (std::size_t r = 0; r < world.robots().size(); ++r) {
    const RobotCollisionModel& robot = world.robots()[r].collision;
    std::vector<Pose> links(robot.model().links().size());
    robot.model().linkPoses(state.robots[r].configuration, links);
    for (std::size_t link = 0; link < links.size(); ++link) {
      const auto linkBody = reference.linkBody(r, link);
      if (linkBody &&
          reference.proximity(body, pose, *linkBody, robot.basePose() * links[link], 0.0)
              .collides) {
        return robot.model().links()[link].name;
      }
    }
  }
  return {};
}

TEST(RestingFaces, ABoxHasSixAndACylinderItsTwoCaps) {
  const auto box = placements().restingFaces(id("box_b"));
  ASSERT_EQ(box.size(), 6U);
  Vec3 sum = Vec3::Zero();
  for (const RestingFace& face : box) {
    EXPECT_NEAR(face.normal.cwiseAbs().maxCoeff(), 1.0, 1e-9);
    EXPECT_NEAR(face.height, 0.03, 1e-9);
    EXPECT_EQ(face.bottom.size(), 4U);  // the face's corners
    sum += face.normal;
  }
  EXPECT_NEAR(sum.norm(), 0.0, 1e-9);  // opposite pairs
  const auto can = placements().restingFaces(id("can"));
  ASSERT_EQ(can.size(), 2U);
  EXPECT_NEAR(std::abs(can[0].normal.z()), 1.0, 1e-9);
  EXPECT_NEAR(can[0].normal.z() + can[1].normal.z(), 0.0, 1e-9);
  EXPECT_NEAR(can[0].height, 0.05, 1e-9);
  EXPECT_TRUE(placements().restingFaces(id("table")).empty()) << "static";
}

// A skewed tetrahedron (centroid (1, 1, 0.25) × 0.1): on its bottom face (0, 0, -1) the centroid
// falls outside the triangle x + y <= 1, so that face is not stable; the other three are.
TEST(RestingFaces, AFaceWhoseCentroidFallsOutsideIsNotStable) {
  const test::ScratchDir dir;
  dir.write("wedge.off",
            "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n3 3 1\n"
            "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
  const World world(parseSceneText("objects:\n"
                                   "  - name: wedge\n"
                                   "    geometry: {mesh: {file: wedge.off, scale: 0.1}}\n"
                                   "    movable: true\n",
                                   "wedge.yaml", dir.file("")),
                    {MeshPieces::Hulls, std::nullopt});
  const PlacementGeometry geometry(world);
  const auto faces = geometry.restingFaces(0);
  ASSERT_EQ(faces.size(), 3U);
  for (const RestingFace& face : faces) EXPECT_GT((face.normal - Vec3(0, 0, -1)).norm(), 0.1);
}

TEST(RestingFaces, ExplicitNormalsAreTakenAsGivenAndPutDown) {
  const auto crate = placements().restingFaces(id("crate"));
  ASSERT_EQ(crate.size(), 2U);
  EXPECT_TRUE(crate[0].normal.isApprox(Vec3(0, 0, -1)));
  EXPECT_TRUE(crate[1].normal.isApprox(Vec3(1, 0, 0)));
  for (const RestingFace& face : crate) {
    for (const double yaw : {0.0, 1.0}) {
      const Pose pose = restingPose(face, 0.2, -0.3, 0.5, yaw);
      EXPECT_TRUE((pose.linear() * face.normal).isApprox(Vec3(0, 0, -1)));
      double lowest = 1e9;
      for (const Vec3& p : originalPoints(cell(), id("crate")))
        lowest = std::min(lowest, (pose * p).z());
      EXPECT_NEAR(lowest, 0.5, 1e-9);
    }
  }
}

TEST(IsInside, AnObjectInTheTrayAndPartlyOut) {
  const PlacementGeometry& geometry = placements();
  const std::size_t box = id("box_b"), tray = id("tray");
  EXPECT_FALSE(geometry.isInside(cell().initialState(), box, tray));
  EXPECT_TRUE(geometry.isInside(with(box, at(0.65, 0, 0.7501)), box, tray));
  EXPECT_TRUE(geometry.isInside(box, at(0.65, 0, 0.7501, 0.7), tray));
  EXPECT_FALSE(geometry.isInside(box, at(0.74, 0, 0.7501), tray)) << "sticks out at x 0.77";
  EXPECT_FALSE(geometry.isInside(box, at(0.65, 0, 0.7499), tray)) << "its bottom below the tray";
  // A held object is placed nowhere.
  GeometricState state = with(box, at(0.65, 0, 0.7501));
  cell().hold(state, 0, cell().robots()[0].collision.model().findLink("left_flange").value(), box,
              Pose::Identity());
  EXPECT_FALSE(geometry.isInside(state, box, tray));
}

// Within ε of the boundary the answer may be "not inside": the can's bounding prism reaches
// r (1/cos(π/16) − 1) ≈ 0.88 mm beyond its side.
TEST(IsInside, MaySayNotInsideWithinTheObjectsEpsilonOfTheBoundary) {
  const std::size_t can = id("can"), tray = id("tray");
  const double wall = 0.75, radius = 0.045;
  const Pose close = at(wall - radius - 0.0004, 0, 0.7701);
  const Pose clear = at(wall - radius - 0.001, 0, 0.7701);
  EXPECT_TRUE(originalInside(cell(), can, close, tray));
  EXPECT_FALSE(placements().isInside(can, close, tray));
  EXPECT_TRUE(placements().isInside(can, clear, tray));
}

// Property: over random poses about the tray, "inside" implies every point of the original
// geometry inside; and both answers occur.
TEST(IsInside, InsideImpliesTheOriginalGeometryInside) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const char* name : {"crate", "can", "box_b"}) {
    const std::size_t object = id(name), tray = id("tray");
    int inside = 0;
    for (int trial = 0; trial < 500; ++trial) {
      Pose pose = at(0.5 + 0.3 * unit(rng), -0.15 + 0.3 * unit(rng), 0.72 + 0.2 * unit(rng));
      pose.linear() =
          Eigen::Quaterniond(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5)
              .normalized()
              .toRotationMatrix();
      if (!placements().isInside(object, pose, tray)) continue;
      ++inside;
      ASSERT_TRUE(originalInside(cell(), object, pose, tray)) << name << " trial " << trial;
    }
    EXPECT_GT(inside, 10) << name;
    EXPECT_LT(inside, 490) << name;
  }
}

TEST(IsOnSupportSurface, RestingOnTheTableNotFloatingNorOverTheEdge) {
  const PlacementGeometry& geometry = placements();
  QueryScratch scratch = cell().scratch();
  const GeometricState initial = cell().initialState();
  for (const char* name : {"box_a", "box_b", "can", "crate"}) {
    EXPECT_EQ(geometry.isOnSupportSurface(initial, id(name), scratch), onObject("table")) << name;
  }
  const std::size_t box = id("box_b");
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(0.45, 0.30, 0.77)), box, scratch))
      << "2 cm above the table";
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(0.79, 0.0, 0.7501)), box, scratch))
      << "half over the edge at x 0.80";
  EXPECT_TRUE(geometry.isOnSupportSurface(with(box, at(0.76, 0.0, 0.7501)), box, scratch))
      << "its bottom corners 1 cm from the edge";
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(0.45, 0.30, 0.745)), box, scratch))
      << "sunk into the table: colliding";
  EXPECT_EQ(geometry.isOnSupportSurface(with(box, at(0.45, 0.30, 0.7501, 0.4)), box, scratch),
            onObject("table"))
      << "turned";
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(2, 2, 0.7501)), box, scratch))
      << "beside the table";
}

// Stacking arises from the predicate (seed 003's MOVE AND STACK): a box on a box, a box on the can.
TEST(IsOnSupportSurface, StackedOnAnotherObject) {
  const PlacementGeometry& geometry = placements();
  QueryScratch scratch = cell().scratch();
  const GeometricState initial = cell().initialState();
  const std::size_t top = id("box_b");
  const Pose onBoxA =
      at(0.65, 0.30,
         initial.placements[cell().scene().slot(id("box_a"))].pose.translation().z() + 0.0702);
  EXPECT_EQ(geometry.isOnSupportSurface(with(top, onBoxA), top, scratch), onObject("box_a"));
  const double canTop =
      initial.placements[cell().scene().slot(id("can"))].pose.translation().z() + 0.05;
  const Pose onCan = at(0.65, -0.30, canTop + 0.0302, 0.3);
  EXPECT_EQ(geometry.isOnSupportSurface(with(top, onCan), top, scratch), onObject("can"));
  EXPECT_FALSE(
      geometry.isOnSupportSurface(with(top, at(0.65, -0.33, canTop + 0.0302)), top, scratch))
      << "over the can's rim";
}

TEST(IsOnSupportSurface, OnASupportSurfaceLocationsFloorAndNeverWhenHeldOrTouchingARobot) {
  const PlacementGeometry& geometry = placements();
  QueryScratch scratch = cell().scratch();
  const std::size_t box = id("box_b");
  EXPECT_EQ(geometry.isOnSupportSurface(with(box, at(1.15, 0, 0.4301)), box, scratch),
            onLocation("depot"));
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(1.15, 0, 0.45)), box, scratch));
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(1.15, 0, 0.4299)), box, scratch))
      << "below the floor";
  // Against the torso (x -0.15..0.15, y -0.2..0.2) on the floor of beside_torso.
  EXPECT_EQ(geometry.isOnSupportSurface(with(box, at(0, -0.25, 0.0301)), box, scratch),
            onLocation("beside_torso"));
  EXPECT_FALSE(geometry.isOnSupportSurface(with(box, at(0, -0.2, 0.0301)), box, scratch))
      << "in the torso";
  GeometricState held = cell().initialState();
  cell().hold(held, 0, cell().robots()[0].collision.model().findLink("left_flange").value(), box,
              Pose::Identity());
  EXPECT_FALSE(geometry.isOnSupportSurface(held, box, scratch));
}

struct Found {
  FreeSpace space;
  GeometricState state;
};

Found freeSpace(std::size_t object, const std::string& location, const FreeSpaceOptions& options,
                const GeometricState& state = cell().initialState()) {
  QueryScratch scratch = cell().scratch();
  Found found{placements().freeSpaceFound(state, object, id(location), options, scratch), state};
  if (found.space.pose) found.state = with(object, *found.space.pose, state);
  return found;
}

// A found placement (`found.state` holds it) is inside location `location` (the original
// geometry too), resting on `support` and free of every object and robot, by the bounded
// predicates and by FCL on the original geometry.
void expectValidPlacement(const PlacementGeometry& geometry, const verify::ReferenceGeometry& exact,
                          const Found& found, std::size_t object, std::size_t location,
                          const Support& support) {
  ASSERT_TRUE(found.space.pose);
  const World& world = geometry.world();
  const Pose& pose = *found.space.pose;
  QueryScratch scratch = world.scratch();
  EXPECT_TRUE(geometry.isInside(found.state, object, location));
  EXPECT_TRUE(originalInside(world, object, pose, location));
  EXPECT_EQ(geometry.isOnSupportSurface(found.state, object, scratch), support);
  const auto collision = world.firstCollision(found.state);
  EXPECT_FALSE(collision) << world.describe(*collision);
  EXPECT_EQ(exactCollision(exact, found.state, object, pose), "");
  const RestingFace& face = geometry.restingFaces(object)[found.space.face];
  EXPECT_TRUE((pose.linear() * face.normal).isApprox(Vec3(0, 0, -1)));
}

void expectValidPlacement(const Found& found, std::size_t object, const std::string& location,
                          const Support& support) {
  expectValidPlacement(placements(), reference(), found, object, id(location), support);
}

TEST(FreeSpaceFound, EachStrategyFindsAPlacementInTheTray) {
  for (const SearchStrategy strategy :
       {SearchStrategy::Linear, SearchStrategy::Quadtree, SearchStrategy::Random}) {
    for (const char* name : {"box_b", "can", "crate"}) {
      SCOPED_TRACE(std::string(name) + " strategy " + std::to_string(static_cast<int>(strategy)));
      FreeSpaceOptions options;
      options.strategy = strategy;
      const Found found = freeSpace(id(name), "tray", options);
      expectValidPlacement(found, id(name), "tray", onObject("table"));
      EXPECT_GE(found.space.samples, 1U);
    }
  }
}

TEST(FreeSpaceFound, QuadtreeTriesTheCentreFirstAndLinearTheLowerCorner) {
  FreeSpaceOptions options;
  const Found centre = freeSpace(id("box_b"), "tray", options);
  ASSERT_TRUE(centre.space.pose);
  EXPECT_EQ(centre.space.samples, 1U);
  EXPECT_TRUE(centre.space.pose->translation().head<2>().isApprox(Eigen::Vector2d(0.65, 0.0)));
  options.strategy = SearchStrategy::Linear;
  options.resolution = 0.05;  // a 5 x 5 grid over 0.2 m: x 0.55 .. 0.75
  const Found corner = freeSpace(id("box_b"), "tray", options);
  ASSERT_TRUE(corner.space.pose);
  // The first corners put the box out of the tray; the first inside is at (0.60, -0.05).
  EXPECT_NEAR(corner.space.pose->translation().x(), 0.60, 1e-9);
  EXPECT_NEAR(corner.space.pose->translation().y(), -0.05, 1e-9);
  EXPECT_EQ(corner.space.samples, 7U);
}

TEST(FreeSpaceFound, RandomIsDeterministicPerSeedAndVariesWithIt) {
  FreeSpaceOptions options;
  options.strategy = SearchStrategy::Random;
  std::vector<Pose> poses;
  for (const std::uint64_t seed : {1, 2, 3}) {
    options.seed = seed;
    const Found first = freeSpace(id("can"), "tray", options);
    const Found again = freeSpace(id("can"), "tray", options);
    ASSERT_TRUE(first.space.pose && again.space.pose);
    EXPECT_EQ(first.space.pose->matrix(), again.space.pose->matrix());
    EXPECT_EQ(first.space.samples, again.space.samples);
    poses.push_back(*first.space.pose);
  }
  EXPECT_FALSE(poses[0].isApprox(poses[1]));
  EXPECT_FALSE(poses[1].isApprox(poses[2]));
}

// Property: with random seeds, around obstacles moved into the tray, every placement found is
// valid on the original geometry.
TEST(FreeSpaceFound, RandomPlacementsAmongObstaclesAreValid) {
  GeometricState crowded = with(id("box_a"), at(0.60, 0.05, 0.7601, 0.3));
  crowded = with(id("can"), at(0.70, -0.05, 0.7701), crowded);
  FreeSpaceOptions options;
  options.strategy = SearchStrategy::Random;
  int found = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    options.seed = seed;
    const Found placement = freeSpace(id("box_b"), "tray", options, crowded);
    if (!placement.space.pose) continue;
    ++found;
    SCOPED_TRACE("seed " + std::to_string(seed));
    QueryScratch scratch = cell().scratch();
    const auto support = placements().isOnSupportSurface(placement.state, id("box_b"), scratch);
    ASSERT_TRUE(support);
    expectValidPlacement(placement, id("box_b"), "tray", *support);
  }
  EXPECT_GE(found, 25);
}

// Stacking arises from freeSpaceFound: the only room in stack_spot is on box_a.
TEST(FreeSpaceFound, StacksOnAnObjectWhenThatIsTheOnlyRoom) {
  for (const SearchStrategy strategy :
       {SearchStrategy::Linear, SearchStrategy::Quadtree, SearchStrategy::Random}) {
    FreeSpaceOptions options;
    options.strategy = strategy;
    options.resolution = 0.01;
    const Found found = freeSpace(id("box_b"), "stack_spot", options);
    expectValidPlacement(found, id("box_b"), "stack_spot", onObject("box_a"));
  }
}

TEST(FreeSpaceFound, RestsOnASupportSurfaceLocationAndAvoidsTheRobot) {
  const Found depot = freeSpace(id("crate"), "depot", {});
  expectValidPlacement(depot, id("crate"), "depot", onLocation("depot"));
  // The centre of beside_torso lies in the torso: the quadtree goes on to a quadrant.
  const Found beside = freeSpace(id("box_b"), "beside_torso", {});
  expectValidPlacement(beside, id("box_b"), "beside_torso", onLocation("beside_torso"));
  EXPECT_GT(beside.space.samples, 1U);
}

// On the bimanual cell: a hull location on a decomposed mesh tabletop (data/meshes).
TEST(FreeSpaceFound, PutsTheBearingInTheHullAreaOnTheMeshTabletop) {
  const World world(readSceneFile(exampleFile("scenes/bimanual-cell.yaml")));
  const PlacementGeometry geometry(world);
  const verify::ReferenceGeometry exact(world);
  const std::size_t bearing = world.find("bearing").value().index;
  const std::size_t area = world.find("assembly-area").value().index;
  const Support tabletop{Support::Kind::Object, world.find("tabletop").value().index};
  // The pipe's axis is its geometry's z turned to the object's x: its caps face ±x.
  const auto pipe = geometry.restingFaces(world.find("pipe").value().index);
  ASSERT_EQ(pipe.size(), 2U);
  EXPECT_NEAR(std::abs(pipe[0].normal.x()), 1.0, 1e-9);
  QueryScratch scratch = world.scratch();
  GeometricState state = world.initialState();
  EXPECT_EQ(geometry.isOnSupportSurface(state, bearing, scratch), tabletop);
  EXPECT_FALSE(geometry.isInside(state, bearing, area));
  for (const SearchStrategy strategy :
       {SearchStrategy::Linear, SearchStrategy::Quadtree, SearchStrategy::Random}) {
    FreeSpaceOptions options;
    options.strategy = strategy;
    const FreeSpace found = geometry.freeSpaceFound(state, bearing, area, options, scratch);
    ASSERT_TRUE(found.pose);
    EXPECT_EQ(found.support, tabletop);
    state.placements[world.scene().slot(bearing)].pose = *found.pose;
    EXPECT_TRUE(geometry.isInside(state, bearing, area));
    EXPECT_TRUE(originalInside(world, bearing, *found.pose, area));
    EXPECT_EQ(geometry.isOnSupportSurface(state, bearing, scratch), tabletop);
    EXPECT_FALSE(world.firstCollision(state));
    EXPECT_EQ(exactCollision(exact, state, bearing, *found.pose), "");
    state = world.initialState();
  }
}

TEST(FreeSpaceFound, NothingInALocationTooSmallOrFullyOccupied) {
  for (const char* location : {"slot", "occupied"}) {
    SCOPED_TRACE(location);
    // After the footprint, the top of the can in `occupied` is tried too (too low for box_b).
    const std::size_t supportFaces = std::string(location) == "slot" ? 0 : 1;
    FreeSpaceOptions options;
    options.maxSamples = 200;
    for (const SearchStrategy strategy : {SearchStrategy::Quadtree, SearchStrategy::Random}) {
      options.strategy = strategy;
      const Found found = freeSpace(id("box_b"), location, options);
      EXPECT_FALSE(found.space.pose);
      EXPECT_EQ(found.space.samples, 200U + supportFaces);
    }
    options.strategy = SearchStrategy::Linear;
    options.resolution = 0.01;
    const Found linear = freeSpace(id("box_b"), location, options);
    EXPECT_FALSE(linear.space.pose);
    EXPECT_EQ(linear.space.samples,
              (std::string(location) == "slot" ? 25U : 121U) + supportFaces);  // the grid
  }
}

TEST(FreeSpaceFound, ThrowsForAStaticObjectOrAnUnknownLocation) {
  QueryScratch scratch = cell().scratch();
  const GeometricState state = cell().initialState();
  EXPECT_THROW((void)placements().freeSpaceFound(state, id("table"), 0, {}, scratch),
               std::invalid_argument);
  EXPECT_THROW((void)placements().freeSpaceFound(state, id("box_a"), 99, {}, scratch),
               std::invalid_argument);
  FreeSpaceOptions options;
  options.resolution = 0;
  EXPECT_THROW((void)placements().freeSpaceFound(state, id("box_a"), 0, options, scratch),
               std::invalid_argument);
}

// Seed 003's MOVE AND STACK scene (examples/move-and-stack): a tray that holds the turquoise
// bottle and the can side by side but no third object beside them.
struct MoveAndStack {
  World world{readSceneFile(exampleFile("move-and-stack/scene.yaml")),
              {MeshPieces::Hulls, std::nullopt}};
  PlacementGeometry placements{world};
  verify::ReferenceGeometry exact{world};

  [[nodiscard]] std::size_t id(const std::string& name) const {
    return world.find(name).value().index;
  }
  // `state` with `object` standing upright at (x, y) on the table (top at z -0.10), turned by yaw.
  void stand(GeometricState& state, const std::string& object, double x, double y,
             double yaw = 0) const {
    const CollisionShape& shape = world.description().objects[id(object)].geometry.shape;
    state.placements[world.scene().slot(id(object))].pose =
        at(x, y, -0.10 + shape.length / 2 + 1.6e-3, yaw);
  }
  // The green bottle moved to the depot, the turquoise bottle and the can in the tray 1.5 cm
  // apart (the tray is 7 × 13 cm; the bottles 3 and 5 cm wide, the can 6 cm).
  [[nodiscard]] GeometricState traySideBySide() const {
    GeometricState state = world.initialState();
    stand(state, "greenbottle", 0.47, 0.10);
    stand(state, "turquoisebottle", 0.375, 0.168);
    stand(state, "can", 0.375, 0.238);
    return state;
  }
  [[nodiscard]] Found freeSpace(const GeometricState& state, const std::string& object,
                                const FreeSpaceOptions& options) const {
    QueryScratch scratch = world.scratch();
    Found found{placements.freeSpaceFound(state, id(object), id("tray"), options, scratch), state};
    if (found.space.pose) {
      found.state.placements[world.scene().slot(id(object))].pose = *found.space.pose;
    }
    return found;
  }
};

const MoveAndStack& moveAndStack() {
  static const MoveAndStack scene;
  return scene;
}

// Seed 003 Fig. 5 (G): the three objects do not fit in the tray side by side, so the small bottle
// is put on the can — "the top of the can is semantically the same as the tabletop".
TEST(FreeSpaceFound, StacksTheSmallBottleOnTheCanWhenTheTrayIsFullSideBySide) {
  const MoveAndStack& scene = moveAndStack();
  const GeometricState full = scene.traySideBySide();
  const Support onCan{Support::Kind::Object, scene.id("can")};
  for (const SearchStrategy strategy :
       {SearchStrategy::Linear, SearchStrategy::Quadtree, SearchStrategy::Random}) {
    SCOPED_TRACE(static_cast<int>(strategy));
    FreeSpaceOptions options;
    options.strategy = strategy;
    const Found found = scene.freeSpace(full, "bluebottle", options);
    expectValidPlacement(scene.placements, scene.exact, found, scene.id("bluebottle"),
                         scene.id("tray"), onCan);
    // Stable: the bottle's axis within the can's top (3 cm radius less the bottle's 1.5 cm).
    const Vec3 offset =
        found.space.pose->translation() -
        full.placements[scene.world.scene().slot(scene.id("can"))].pose.translation();
    EXPECT_LT(offset.head<2>().norm(), 0.015);
    // The can's top holds one bottle; the turquoise bottle's top is too high in the tray.
    EXPECT_FALSE(scene.freeSpace(found.state, "greenbottle", options).space.pose);
  }
}

// The support faces come after the footprint: with the tray's centre as the only footprint position
// (taken by the gap between the two objects), the turquoise bottle's top is tried (too high), then
// the can's.
TEST(FreeSpaceFound, TriesTheTopsOfTheObjectsInTheLocationAfterTheFootprint) {
  const MoveAndStack& scene = moveAndStack();
  FreeSpaceOptions options;
  options.strategy = SearchStrategy::Quadtree;
  options.maxSamples = 1;
  const Found found = scene.freeSpace(scene.traySideBySide(), "bluebottle", options);
  ASSERT_TRUE(found.space.pose);
  EXPECT_EQ(found.space.support, (Support{Support::Kind::Object, scene.id("can")}));
  EXPECT_EQ(found.space.samples, 3U);
  // Not the centre of the can's top when the footprint has room: the tray holding the can alone.
  GeometricState roomy = scene.world.initialState();
  scene.stand(roomy, "greenbottle", 0.47, 0.10);
  scene.stand(roomy, "can", 0.375, 0.238);
  const Found beside = scene.freeSpace(roomy, "bluebottle", {});
  ASSERT_TRUE(beside.space.pose);
  EXPECT_EQ(beside.space.support, (Support{Support::Kind::Object, scene.id("table")}));
}

// Stable on the can: centred it rests on it; 2 cm off its axis the bottle's rim hangs over the
// can's (3 cm radius) and some probes miss: not on a support.
TEST(IsOnSupportSurface, ABottleOnTheCanNotOverItsRim) {
  const MoveAndStack& scene = moveAndStack();
  QueryScratch scratch = scene.world.scratch();
  GeometricState state = scene.traySideBySide();
  const Pose can = state.placements[scene.world.scene().slot(scene.id("can"))].pose;
  const std::size_t bottle = scene.id("bluebottle");
  Pose& pose = state.placements[scene.world.scene().slot(bottle)].pose;
  pose = at(can.translation().x(), can.translation().y(), can.translation().z() + 0.095 + 1.6e-3);
  EXPECT_EQ(scene.placements.isOnSupportSurface(state, bottle, scratch),
            (Support{Support::Kind::Object, scene.id("can")}));
  pose.translation().y() += 0.02;
  EXPECT_FALSE(scene.placements.isOnSupportSurface(state, bottle, scratch));
}

TEST(ObjectOnTop, TheBottleOnTheCanAndNothingOnAnObjectBesideIt) {
  const MoveAndStack& scene = moveAndStack();
  QueryScratch scratch = scene.world.scratch();
  const GeometricState full = scene.traySideBySide();
  EXPECT_EQ(scene.placements.objectOnTop(full, scene.id("can")), std::nullopt);
  EXPECT_EQ(scene.placements.objectOnTop(full, scene.id("turquoisebottle")), std::nullopt)
      << "the can beside it does not stand on it";
  const Found stacked = scene.freeSpace(full, "bluebottle", {});
  ASSERT_TRUE(stacked.space.pose);
  EXPECT_EQ(scene.placements.objectOnTop(stacked.state, scene.id("can")), scene.id("bluebottle"));
  EXPECT_EQ(scene.placements.objectOnTop(stacked.state, scene.id("bluebottle")), std::nullopt);
  EXPECT_EQ(scene.placements.objectOnTop(stacked.state, scene.id("table")), scene.id("greenbottle"))
      << "the first movable object on the table";
  GeometricState held = stacked.state;
  scene.world.hold(held, 0, scene.world.robots()[0].collision.model().findLink("palm").value(),
                   scene.id("can"), Pose::Identity());
  EXPECT_EQ(scene.placements.objectOnTop(held, scene.id("can")), std::nullopt) << "held";
}

// Equal blocks stacked flush (the Stacked n Objects scenario): the probes from the upper block's
// corners run down the lower block's edges and still rest on it, and freeSpaceFound puts a third
// equal block flat on the stack (not on its side, which the edge used to leave as the only face).
TEST(FreeSpaceFound, StacksEqualBlocksFlush) {
  std::string text =
      "settings: {epsilon: 0.002}\n"
      "objects:\n"
      "  - {name: stand, geometry: {box: {size: [0.06, 0.06, 0.10]}}, pose: {position: [0.3, 0, "
      "0.05]}}\n";
  for (int level = 0; level < 3; ++level) {
    text += "  - {name: block" + std::to_string(level) +
            ", movable: true, geometry: {box: {size: [0.04, 0.04, 0.012]}}, pose: {position: [0.3, "
            "0, " +
            std::to_string(0.106 + 0.012 * level) + "]}}\n";
  }
  text +=
      "locations:\n"
      "  - {name: stack, region: {box: {min: [0.27, -0.03, 0.10], max: [0.33, 0.03, 0.20]}}}\n";
  const World world(parseSceneText(text, "stack.yaml", "."), {MeshPieces::Hulls, std::nullopt});
  const PlacementGeometry geometry(world);
  QueryScratch scratch = world.scratch();
  const auto block = [&](int level) {
    return world.find("block" + std::to_string(level)).value().index;
  };
  GeometricState state = world.initialState();
  EXPECT_EQ(geometry.isOnSupportSurface(state, block(1), scratch),
            (Support{Support::Kind::Object, block(0)}));
  EXPECT_EQ(geometry.objectOnTop(state, block(1)), block(2));
  // block2 taken off and put back by freeSpaceFound, flat (its bottom face only) and aligned.
  state.placements[world.scene().slot(block(2))].present = false;
  const std::span<const RestingFace> faces = geometry.restingFaces(block(2));
  FreeSpaceOptions options;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].normal.isApprox(Vec3(0, 0, -1))) options.faces = {f};
  }
  ASSERT_EQ(options.faces.size(), 1U);
  const FreeSpace found =
      geometry.freeSpaceFound(state, block(2), world.find("stack").value().index, options, scratch);
  ASSERT_TRUE(found.pose);
  EXPECT_EQ(found.support, (Support{Support::Kind::Object, block(1)}));
  EXPECT_EQ(found.samples, 1U) << "the location's centre, over the stack";
}

// The placement cell with box_b and the can written `place_in: tray` instead of at a pose, and
// `more` appended to its settings.
World cellPlacedInTheTray(const std::string& location = "tray", const std::string& more = "") {
  std::string text = test::slurp(sourceFile("tests/data/placement-cell.yaml"));
  for (const char* pose : {"    pose: {position: [0.45, 0.30, 0.75]}\n",
                           "    pose: {position: [0.65, -0.30, 0.77]}\n"}) {
    const std::size_t at = text.find(pose);
    EXPECT_NE(at, std::string::npos) << pose;
    text.replace(at, std::string(pose).size(), "    place_in: " + location + "\n");
  }
  text.replace(text.find("  seed: 3\n"), 10, "  seed: 3\n" + more);
  return World(parseSceneText(text, "cell.yaml", sourceFile("tests/data")));
}

// Objects with place_in start at free places in their location, on the table, in every layout;
// the layout follows placement_seed and nothing else.
TEST(PlaceIn, ObjectsStartAtRandomFreePlacesInTheirLocation) {
  std::vector<Pose> first;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("placement seed " + std::to_string(seed));
    const World world = cellPlacedInTheTray("tray", fmt::format("  placement_seed: {}\n", seed));
    const PlacementGeometry geometry(world);
    const verify::ReferenceGeometry exact(world);
    const GeometricState state = world.initialState();
    const std::size_t tray = world.find("tray").value().index;
    const std::size_t table = world.find("table").value().index;
    std::vector<Pose> poses;
    for (const char* name : {"box_b", "can"}) {
      const std::size_t object = world.find(name).value().index;
      const Pose pose = world.scene().pose(object, state.placements);
      poses.push_back(pose);
      const std::span<const RestingFace> faces = geometry.restingFaces(object);
      const auto down = std::find_if(faces.begin(), faces.end(), [&](const RestingFace& face) {
        return (pose.linear() * face.normal).isApprox(Vec3(0, 0, -1));
      });
      ASSERT_NE(down, faces.end()) << "not on a resting face";
      const FreeSpace placed{pose, {}, static_cast<std::size_t>(down - faces.begin()), 1};
      expectValidPlacement(geometry, exact, {placed, state}, object, tray,
                           {Support::Kind::Object, table});
    }
    if (seed == 1) {
      first = poses;
      const World again = cellPlacedInTheTray("tray", "  placement_seed: 1\n");
      for (std::size_t i = 0; i < 2; ++i) {
        const std::size_t object = again.find(i == 0 ? "box_b" : "can").value().index;
        EXPECT_TRUE(again.scene().pose(object, again.initialState().placements).isApprox(poses[i]));
      }
    } else {
      EXPECT_FALSE(poses[0].isApprox(first[0]));
    }
  }
}

TEST(PlaceIn, NoFreePlaceIsOneLineNamingThePlaceIn) {
  try {
    (void)cellPlacedInTheTray("slot");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "cell.yaml:26:15: objects[2].place_in: no free place for object 'box_b' in "
              "location 'slot' (2000 random samples)");
  }
}

}  // namespace

}  // namespace kaboum::world
