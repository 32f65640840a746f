// An independent verifier of planned paths (thesis §4.5, certified motion; §6.1.3, what execution
// relies on): a path file replayed densely in a World's scene and checked at every sample with FCL
// on the original meshes and primitives (ReferenceGeometry), not with the planner's bounding
// pieces. Reports every collision and the smallest clearance. Reference: docs/verify.md.
#pragma once

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/io/path_file.hpp"
#include "kaboum/verify/reference_geometry.hpp"

namespace kaboum::verify {

using namespace kaboum::world;

// An object a robot holds during the path, resolved against the World.
struct ResolvedHeld {
  std::size_t robot = 0;
  std::size_t object = 0;  // scene object id
  std::size_t link = 0;
  Pose objectInLink = Pose::Identity();
};

// A path file checked against a World (names, lengths, joint limits): the moving robots (World
// robot indices, each waypoint their configurations concatenated in this order) and what they
// hold; and the state it moves in: the configurations of the other robots and what they hold,
// and where the objects are (`context`; absent: the World's initial state, robots at home).
struct ScenePath {
  std::vector<std::size_t> robots;
  std::vector<std::vector<double>> waypoints;
  std::vector<ResolvedHeld> held;
  std::optional<GeometricState> context;
};

// Checks `path` against `world`. Bad input throws InputError with one line naming `fileName` and
// the key, e.g. "path.json: waypoints[3][1]: joint 'left_j2' of robot 'twin' at 2.5 is outside
// its limits [-2, 2]".
ScenePath resolvePath(const World& world, const io::PathFile& path, const std::string& fileName);

// What is wrong with one waypoint of `robots` (World robot indices, their configurations
// concatenated): its length or a value not finite or outside its joint's limits, as a key suffix
// and the reason ("[4]: joint 'a5' of robot 'kr5' at 3.2 is outside its limits [-2.1, 2.1]",
// ": 5 values, but robots 'kr5' have 6 joints"); "" when it is fine.
std::string waypointError(const World& world, std::span<const std::size_t> robots,
                          std::span<const double> waypoint);

struct VerifyOptions {
  // The largest motion of any revolute or continuous joint between two samples (radians); a
  // prismatic joint moves at most toolStep.
  double jointStep = 0.5 * std::numbers::pi / 180;
  // The largest motion of any link origin, tool centre point or held object frame between two
  // samples (metres).
  double toolStep = 0.001;
  // Called now and then with (samples checked, samples in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

// A sample of a path: waypoint `segment` moved `fraction` ∈ [0, 1] of the way to the next one
// (fraction 0 is the waypoint itself; the last waypoint is the last segment at fraction 1).
struct PathPlace {
  std::size_t segment = 0;
  double fraction = 0;
};

// The samples at which a path is checked, in path order: the waypoints, and between them every
// joint moving at most jointStep (a prismatic joint toolStep) and every link origin, tool centre
// point and held object frame moving at most toolStep (forward kinematics, subdividing further
// where a step moves them more).
std::vector<PathPlace> densify(const World& world, const ScenePath& path,
                               const VerifyOptions& options);

// A party of a check: a robot link, a held object (`robot` holds it on `link`) or a scene object
// (robot and link empty).
struct PartyName {
  std::string robot;
  std::string link;
  std::string object;
};
// "robot 'twin' link 'left_link3'", "object 'bottle' held by robot 'twin'", "object 'table'".
std::string describe(const PartyName& party);

// The smallest FCL distance over all samples and checked pairs, where it was found.
struct Clearance {
  double distance = 0;
  PartyName first;
  PartyName second;
  PathPlace where;
};

// Two parties colliding at consecutive samples `from` to `to` (`samples` of them).
struct PathCollision {
  PartyName first;
  PartyName second;
  PathPlace from;
  PathPlace to;
  std::size_t samples = 0;
};

struct PathVerification {
  std::size_t samples = 0;             // configurations checked
  std::size_t pairs = 0;               // pairs of parties checked at each sample
  std::optional<Clearance> clearance;  // absent when no pair is checked
  std::vector<PathCollision> collisions;
  double seconds = 0;

  [[nodiscard]] bool collisionFree() const { return collisions.empty(); }
};

// Replays `path` at the samples of densify() and checks at each, with FCL on the original
// geometry: every moving robot's links (hand shapes included) and held objects against every
// scene object not held, against the other robots (the robots not in the path at home, with what
// they hold) and against themselves, except the link pairs the World's robot collision filter
// allows (adjacent links, pairs overlapping at home); a held object is not checked against the
// link holding it nor the other objects on that link. Objects stand at the World's initial
// poses (resting objects raised as the World raises them).
PathVerification verifyPath(const ReferenceGeometry& geometry, const ScenePath& path,
                            const VerifyOptions& options = {});

// collision_free, samples, pairs, seconds, clearance (distance, first, second, segment, fraction;
// null when absent) and collisions (first, second, from, to, samples), a party as robot, link and
// object (null where empty) with its description.
nlohmann::json toJson(const PathVerification& verification);

}  // namespace kaboum::verify
