// The geometric placement predicates of the integrated planner (seed 003 §III-B: isInside,
// isOnSupportSurface, freeSpaceFound with its linear, quadtree and random strategies of Fig. 2;
// thesis §6.1.2): whether an object lies in a location, what it rests on, and where it can be put
// down. Evaluated on a const World and a GeometricState through the bodies' bounding convex
// pieces, single-sided as bounded predicates are (Definition 1). Reference: docs/placement.md.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kaboum/collision/predicates.hpp"
#include "kaboum/world/world.hpp"

namespace kaboum::world {

// What an object rests on: another scene object (its id), or a location flagged support_surface
// (its index), whose bottom face holds objects.
struct Support {
  enum class Kind { Object, Location };
  Kind kind = Kind::Object;
  std::size_t index = 0;
  bool operator==(const Support&) const = default;
};

// The probes of isOnSupportSurface for one object (metres): vertical segments of length `drop`
// down from the vertices of its pieces within `band` of their lowest one.
struct SupportTolerance {
  double band = 0;
  double drop = 0;
};

// A face an object may rest on (seed 003 §III-B, the scene file's resting_faces): its outward unit
// normal in the object frame, the orientation that turns it to −z, the height of the object frame
// above the plane its pieces then touch, the bottom vertices of its pieces in that orientation
// (within the support band of the lowest, frame origin at height 0 above them: z in [0, band]) and
// their mean (the face's centre, what freeSpaceFound puts over the centre of a support face).
struct RestingFace {
  Vec3 normal{0, 0, -1};
  Eigen::Quaterniond down = Eigen::Quaterniond::Identity();
  double height = 0;
  std::vector<Vec3> bottom;
  Vec3 centre{0, 0, 0};
};

// The object pose that puts `face` down on the horizontal plane at height `planeZ` (its pieces'
// lowest vertices there), turned by `yaw` about the vertical, the object frame above (x, y).
Pose restingPose(const RestingFace& face, double x, double y, double planeZ, double yaw);

// freeSpaceFound's sampling of a location's footprint (seed 003 Fig. 2), in the location's frame
// (its x and y axes; the box of its region there):
// * Linear: a grid of `resolution` spacing centred on the footprint, row by row along x from the
//   lower corner; it ends when the grid is exhausted (not complete: a subset of positions).
// * Quadtree: the centre, then the centres of the 4 quadrants, then of their 16 quadrants, …
//   (each level in Morton order): space-filling, so complete as samples grow.
// * Random: uniform positions and yaw offsets from std::mt19937_64 seeded with `seed`.
enum class SearchStrategy { Linear, Quadtree, Random };

struct FreeSpaceOptions {
  SearchStrategy strategy = SearchStrategy::Quadtree;
  double resolution = 0.02;       // metres, Linear
  std::size_t maxSamples = 1000;  // positions tried at most
  // Yaws tried per position and resting face: the location frame's yaw + offset + k·2π/yawCount
  // (k < yawCount; offset 0, or uniform for Random).
  std::size_t yawCount = 4;
  std::uint64_t seed = 1;  // Random
  // The resting faces tried (indices into restingFaces(object)), in this order; empty: all of
  // them, largest first. A caller holding the object passes those its grasp can reach.
  std::vector<std::size_t> faces;
};

// freeSpaceFound's answer: the pose (nullopt when no sample gave one), the support it rests on and
// the index of its resting face (meaningful with a pose), and the positions tried.
struct FreeSpace {
  std::optional<Pose> pose;
  Support support;
  std::size_t face = 0;
  std::size_t samples = 0;
};

// The placement geometry of one World, built once and then const like the World (which must
// outlive it): every location's convex region in the world frame, every object's pieces as facet
// planes (for the downward raycast) and every movable object's resting faces. The queries take a
// QueryScratch (World::scratch(), one per thread) for the robots' link poses; they allocate
// nothing. States must have the World's shape (World::firstCollision checks one).
class PlacementGeometry {
 public:
  explicit PlacementGeometry(const World& world);

  [[nodiscard]] const World& world() const { return world_; }
  // Location `location`'s region in the world frame.
  [[nodiscard]] const ConvexContainer& region(std::size_t location) const {
    return locations_.at(location).region;
  }
  // The resting faces of object `object`: the scene file's normals as given, or with
  // `resting_faces: auto` the stable faces of the convex hull of its pieces (those whose outward
  // normal turned to −z puts the hull's centroid strictly inside the face), largest first; a
  // cylinder's two caps only (its bounding prism's sides stand for the round side), none for a
  // sphere. Empty for a static object.
  [[nodiscard]] std::span<const RestingFace> restingFaces(std::size_t object) const {
    return objects_.at(object).faces;
  }
  // The probes of object `object`: band = ε_o, drop = 2 ε_o + ε_max + g + 0.1 mm, where ε_o is
  // the object's ε (the larger of asked and reached, World::objectEpsilon), ε_max the largest of
  // the scene's objects and g the World's resting gap. An object resting on another, its pieces
  // apart by at most both bodies' ε + g + 0.1 mm (as the World raises resting objects at load, and
  // placements found here lie), reaches it from every vertex in the band.
  [[nodiscard]] SupportTolerance supportTolerance(std::size_t object) const;

  // Seed 003's isInside(object, location): every vertex of the object's pieces inside the
  // location's region. Never true when the object is not contained (the pieces contain it); may
  // be false when the object is inside but within its ε of the boundary. False for an object a
  // robot holds (placed nowhere).
  [[nodiscard]] bool isInside(const GeometricState& state, std::size_t object,
                              std::size_t location) const;
  // The same for the object at `pose` (a placement not yet in a state, for samplers).
  [[nodiscard]] bool isInside(std::size_t object, const Pose& pose, std::size_t location) const;

  // Seed 003's isOnSupportSurface(object): the object collision-free (at distance 0 against every
  // other object and every robot with what it holds) and each probe of supportTolerance() from
  // its bottom vertices touching a support: another present object's pieces, or the bottom face
  // of a support-surface location (its lowest boundary under the probe). Returns the support of
  // the first probe (piece and vertex order), nullopt when not resting or held by a robot.
  [[nodiscard]] std::optional<Support> isOnSupportSurface(const GeometricState& state,
                                                          std::size_t object,
                                                          QueryScratch& scratch) const;
  // The same for the object at `pose` instead of where `state` has it (its own placement or hold
  // in `state` is ignored).
  [[nodiscard]] std::optional<Support> isOnSupportSurface(const GeometricState& state,
                                                          std::size_t object, const Pose& pose,
                                                          QueryScratch& scratch) const;

  // Seed 003's freeSpaceFound(object, location), the suggester: samples (x, y) positions over the
  // location's footprint by `options.strategy`, then (when those give nothing) the centres of the
  // upward horizontal faces of the objects standing in the location (the top of a can: stacking,
  // seed 003 §IV); at each, for every resting face and yaw, a downward raycast from the region's
  // top under the face's bottom vertices onto the supports (present objects' pieces,
  // support-surface locations' bottoms) gives the height, the pieces the World's resting gap above
  // the highest support hit; the first pose that is inside the location (isInside), collision-free
  // against every other object and every robot (the object's own placement or hold in `state`
  // ignored) and on a support (isOnSupportSurface) is returned. Never a colliding placement;
  // deterministic for the options. Throws std::invalid_argument for a static object or a location
  // out of range.
  [[nodiscard]] FreeSpace freeSpaceFound(const GeometricState& state, std::size_t object,
                                         std::size_t location, const FreeSpaceOptions& options,
                                         QueryScratch& scratch) const;

  // The first present movable object (in id order) standing on `object` in `state`: one of its
  // supportTolerance() probes touches `object`'s pieces. Nullopt when none does, or when `object`
  // is held. What a pick must not take away from under another object.
  [[nodiscard]] std::optional<std::size_t> objectOnTop(const GeometricState& state,
                                                       std::size_t object) const;

 private:
  struct LocationGeometry {
    ConvexContainer region;  // world frame
    Pose frame;              // the region's frame (its pose in the scene file)
    Vec3 lower{0, 0, 0};     // box of the region's points in `frame`
    Vec3 upper{0, 0, 0};
    double top = 0;  // highest and lowest world z of the region
    double bottom = 0;
    bool supportSurface = false;
  };
  // A facet of the convex hull of an object's pieces, in the object frame: its outward unit
  // normal and its centroid. Those facing up where the object stands are its support faces.
  struct HullFacet {
    Vec3 normal{0, 0, 1};
    Vec3 centroid{0, 0, 0};
  };
  struct ObjectGeometry {
    std::vector<std::vector<HullPlane>> piecePlanes;  // per piece, in the object frame
    std::vector<RestingFace> faces;
    std::vector<HullFacet> facets;
  };

  // The object's pose in `state`: its placement, or a static object's pose; nullopt when held.
  [[nodiscard]] std::optional<Pose> poseIn(const GeometricState& state, std::size_t object) const;
  // Whether object `object` at `pose` is within distance 0 of another object or a robot part
  // (scratch.linkPoses computed), ignoring its own placement and hold; with the World's installed
  // predicates (World::usePredicates) when it has them.
  [[nodiscard]] bool collides(const GeometricState& state, const QueryScratch& scratch,
                              std::size_t object, const Pose& pose) const;
  // isOnSupportSurface with scratch.linkPoses computed.
  [[nodiscard]] std::optional<Support> supportAt(const GeometricState& state,
                                                 const QueryScratch& scratch, std::size_t object,
                                                 const Pose& pose) const;
  // The support-surface location whose bottom lies on the downward `segment`.
  [[nodiscard]] std::optional<std::size_t> floorOn(const SegmentSupport& segment) const;
  // The highest support top under the world point (x, y) between heights `low` and `high`
  // (pieces of present objects but `object`, support-surface bottoms): nullopt when there is
  // none, or when `high` lies inside a piece there (the column is blocked).
  [[nodiscard]] std::optional<double> supportHeight(const GeometricState& state, std::size_t object,
                                                    double x, double y, double low,
                                                    double high) const;

  const World& world_;
  std::vector<LocationGeometry> locations_;
  std::vector<ObjectGeometry> objects_;
  double largestEpsilon_ = 0;
};

}  // namespace kaboum::world
