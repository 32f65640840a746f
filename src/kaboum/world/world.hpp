// The world the integrated planner queries (thesis §6.1.1 pre-processing, §6.1.2 robotics
// components at planning time): a scene file turned once into collision geometry (robots with
// their hands, objects, locations), then shared const; every query takes a GeometricState.
// Format of the scene file: docs/scene-format.md; reference: docs/world.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/collision/robot_collision.hpp"
#include "kaboum/collision/scene.hpp"
#include "kaboum/io/decomposition_cache.hpp"
#include "kaboum/io/scene_file.hpp"
#include "kaboum/world/geometric_state.hpp"

namespace kaboum::world {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::collision;

// How mesh geometry (URDF link meshes, hand and object meshes) becomes convex pieces: one convex
// hull each, or the bounding convex decomposition of §4.4 at the scene's ε. Primitives are one
// bounding polytope either way.
enum class MeshPieces { Hulls, Decomposition };

struct WorldOptions {
  MeshPieces pieces = MeshPieces::Decomposition;
  // Where mesh decompositions are kept between runs (io::DecompositionCache); nullopt: nowhere.
  std::optional<std::filesystem::path> cacheDirectory;
  // Threads of the WorkerPool that decomposes the scene's distinct meshes (0: the hardware's,
  // std::thread::hardware_concurrency()). The World does not depend on it.
  unsigned threads = 0;
};

// One distinct mesh of the scene (by its vertex and triangle bytes, scaled as its shapes are):
// decomposed once per World however many link, hand or object shapes have it.
struct MeshDecomposition {
  std::string mesh;  // the file of its first shape
  std::size_t triangles = 0;
  std::size_t shapes = 0;    // link, hand and object shapes with this mesh
  std::size_t attempts = 0;  // decompositions made or read: one per piece limit tried
  double seconds = 0;        // wall time of its task (computed, or read from the cache)
};

// How a World decomposed its meshes: the threads, and the distinct meshes in the order the scene
// first names them (robots' links and hands, then objects); empty with MeshPieces::Hulls.
struct DecompositionSummary {
  unsigned threads = 1;
  std::vector<MeshDecomposition> meshes;
};

// The bounding error of a body's convex pieces: what the scene asks (its ε, or that percentage of
// the body's bounding-box diagonal) and what the pieces reach (the largest over the body's shapes,
// collision::BoundingPieces). A decomposition that its piece limit stops above ε is made again with
// up to 8 times the limit; where that does not reach ε either, `reached` says how far it got.
struct BodyEpsilon {
  double asked = 0;
  double reached = 0;
  [[nodiscard]] bool met() const { return reached <= asked; }
};

struct WorldRobot {
  std::string name;
  // Link parts from the URDF; a tool's hand shapes are further collision geometry of its tool
  // link. Pairs within twice the scene's sweep ε of each other at home are allowed
  // (allowPairsCollidingAt): the swept self-collision check of a motion queries at that margin.
  RobotCollisionModel collision;
  std::vector<double> home;
  // Its URDF read and its model built, plus the decomposition tasks of the distinct meshes it
  // names first (tasks run in parallel: the robots' and objects' seconds may add up to more than
  // World::preprocessingSeconds()).
  double preprocessingSeconds = 0;
  // By part (collision.part(i)); and by tool of the scene file, the bounding error of each of its
  // hand shapes.
  std::vector<BodyEpsilon> partEpsilon;
  std::vector<std::vector<double>> handShapeEpsilon;
};

// A name of the scene (compared without case, as the scene file does) and what it names: a robot
// (index into World::robots()), an object (its CollisionScene id, equal to its index in the scene
// file) or a location (index into the description's locations).
struct NamedEntity {
  enum class Kind { Robot, Object, Location };
  Kind kind = Kind::Object;
  std::size_t index = 0;
};

// One party of a collision: a robot's links (its own parts), or an object — a scene object, or
// one a robot holds.
struct Party {
  enum class Kind { Robot, Object };
  Kind kind = Kind::Object;
  std::size_t index = 0;  // robot index or object id
  int link = -1;          // a robot's: the link (RobotModel::links()) of the colliding part
  bool operator==(const Party&) const = default;
};

// Two parties within distance 0 of each other (two parties of one robot: its self-collision).
struct Collision {
  Party first;
  Party second;
};

// Per-caller buffers of the queries (link poses of every robot), reused across states so that
// queries allocate nothing; one per thread.
struct QueryScratch {
  std::vector<std::vector<Pose>> linkPoses;
  std::vector<std::uint8_t> againstRobots;  // one flag per robot
  // A state's placements without the objects joined to the one checked (GeometricState::joined).
  SceneState placements;
};

class StatePredicates;  // state_predicates.hpp

class World {
 public:
  // Builds the geometry of `scene`. Objects with place_in are put at a random free pose in their
  // location once the others stand (placeAtRandom). Movable objects resting on another object
  // (touching it, free once raised by at most the two bodies' bounding error, or nearer to it than
  // restingGap()) are raised until they are restingGap() clear of it, as placements are
  // (isOnSupportSurface), the lowest first so that a stack written touching rises as a whole.
  // Throws InputError with one line naming the entry (SourceLocation::message) when two objects
  // start in collision or a robot at home collides with an object or another robot.
  explicit World(SceneDescription scene, const WorldOptions& options = {});

  [[nodiscard]] const SceneDescription& description() const { return description_; }
  [[nodiscard]] const std::vector<WorldRobot>& robots() const { return robots_; }
  // Object ids are the indices of the scene file's objects.
  [[nodiscard]] const CollisionScene& scene() const { return scene_; }
  [[nodiscard]] std::optional<NamedEntity> find(const std::string& name) const;
  // Absolute ε of a body whose bounding-box diagonal is `diagonal` (the scene's ε in metres, or
  // its fraction of the diagonal).
  [[nodiscard]] double epsilonFor(double diagonal) const;

  // Seconds spent building each object's body (by object id; with the decomposition task of a
  // mesh it names first, as WorldRobot::preprocessingSeconds), and the whole World.
  [[nodiscard]] const std::vector<double>& objectSeconds() const { return objectSeconds_; }
  [[nodiscard]] double preprocessingSeconds() const { return preprocessingSeconds_; }
  // How far a resting object was raised off its support at load time (by object id; 0 if not).
  [[nodiscard]] const std::vector<double>& restingLift() const { return restingLift_; }
  // Metres: the clearance the World keeps between a resting object and its support — a quarter of
  // the scene's sweep ε, so that the certified motions that lift it off or set it down can start
  // and end there (motion::sweepEpsilonForEnds). Initial objects touching or nearer than this to
  // what they rest on are raised to it; placements are made at it.
  [[nodiscard]] double restingGap() const { return description_.settings.sweepEpsilon / 4; }
  // The bounding error of each object's pieces (by object id).
  [[nodiscard]] const std::vector<BodyEpsilon>& objectEpsilon() const { return objectEpsilon_; }
  // What the decomposition cache did while the World was built (all zero without one).
  [[nodiscard]] const DecompositionCacheReport& cacheReport() const { return cacheReport_; }
  // The distinct meshes decomposed and the threads that did it.
  [[nodiscard]] const DecompositionSummary& decompositions() const { return decompositions_; }

  // Every robot at home holding nothing, every movable object at its (raised) initial pose.
  [[nodiscard]] GeometricState initialState() const;
  [[nodiscard]] QueryScratch scratch() const;

  // Makes `robot` hold movable object `object` on `link` with the object frame at `objectInLink`:
  // the object's placement becomes absent and it moves with the link. Throws std::invalid_argument
  // for a fixed object or one not placed in `state`.
  void hold(GeometricState& state, std::size_t robot, int link, std::size_t object,
            const Pose& objectInLink) const;
  // Makes `robot` let go of `object` where it holds it: the object is placed at its pose at the
  // robot's configuration in `state`. Returns that pose. Throws std::invalid_argument when the
  // robot does not hold the object.
  Pose release(GeometricState& state, std::size_t robot, std::size_t object) const;

  // The first collision in `state`, checked through the bounded predicates at distance 0 (never
  // missed; may be reported up to the bodies' bounding error apart): each robot in turn (with what
  // it holds) against itself, the scene and the robots after it, then each present movable object
  // against every other object but those joined to it (GeometricState::joined). A held object is
  // not checked against the link holding it.
  // Throws std::invalid_argument for a state of the wrong shape. Allocates nothing.
  [[nodiscard]] std::optional<Collision> firstCollision(const GeometricState& state,
                                                        QueryScratch& scratch) const;
  // Every robot's link poses in `state` into `scratch.linkPoses`. Allocates nothing.
  void computeLinkPoses(const GeometricState& state, QueryScratch& scratch) const;
  // The first collision of robot `robot` (with what it holds) in `state`: with itself, the
  // scene's objects, and each other robot r with against[r] != 0 — the part of firstCollision that
  // changes when the robot moves — within `margin` of the scene's objects and 2 × `margin` of
  // robots (itself included): the clearances a swept volume bounded within `margin` is checked
  // at. `scratch.linkPoses` must hold the state's link poses (computeLinkPoses). Allocates nothing.
  [[nodiscard]] std::optional<Collision> firstCollisionOfRobot(
      const GeometricState& state, const QueryScratch& scratch, std::size_t robot,
      std::span<const std::uint8_t> against, double margin) const;
  // The same with buffers of its own (allocates them).
  [[nodiscard]] std::optional<Collision> firstCollision(const GeometricState& state) const;

  // Makes the collision queries (firstCollision, firstCollisionOfRobot, and the placements'
  // collision test) answer with `predicates` instead of the bounded predicates — their margins
  // then do not apply —, or with the bounded predicates again (nullptr). `predicates` must
  // outlive its use; install it before sharing the World between threads.
  void usePredicates(const StatePredicates* predicates) { predicates_ = predicates; }
  // The installed predicates, or nullptr for the bounded ones.
  [[nodiscard]] const StatePredicates* predicates() const { return predicates_; }

  // The party of part `part` of robot `robot` holding what it holds in `state`
  // (RobotCollisionModel::part: its links' parts, then the objects it holds).
  [[nodiscard]] Party partyOf(const GeometricState& state, std::size_t robot,
                              std::size_t part) const;

  // "robot 'twin' link 'left_link3'", "object 'bottle'": a party's name for messages.
  [[nodiscard]] std::string describe(const Party& party) const;
  // "robot 'twin' link 'left_flange' collides with object 'table'"; "robot 'twin' link
  // 'left_link3' collides with its link 'torso'".
  [[nodiscard]] std::string describe(const Collision& collision) const;

 private:
  // The URDF name of a robot party's link (party.link >= 0).
  [[nodiscard]] std::string linkName(const Party& party) const;
  void checkState(const GeometricState& state) const;
  // Puts each object with place_in, in file order, at a random free pose in its location
  // (PlacementGeometry::freeSpaceFound, random strategy, seeded by the scene's placement_seed and
  // the object's id), clear of the robots at home and the objects already standing, resting on a
  // static object or a support surface (a draw that stacks it on a movable object is redrawn with
  // the next seed, 20 times at most). Throws
  // InputError naming the object's place_in when no sample gives one.
  void placeAtRandom();
  void validateInitialState();

  SceneDescription description_;
  std::vector<WorldRobot> robots_;
  CollisionScene scene_;
  std::map<std::string, NamedEntity> names_;  // lower-case name
  std::vector<double> objectSeconds_;
  std::vector<double> restingLift_;
  std::vector<BodyEpsilon> objectEpsilon_;
  DecompositionCacheReport cacheReport_;
  DecompositionSummary decompositions_;
  SceneState initialPlacements_;  // the scene's initial placements, resting objects raised
  double preprocessingSeconds_ = 0;
  const StatePredicates* predicates_ = nullptr;
};

}  // namespace kaboum::world
