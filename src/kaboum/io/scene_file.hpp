// The scene file: the one YAML file in which a user describes the world kaboum plans in (thesis
// §6.1, §6.2): robots with their tools and hands, objects with their grasps (Table 5.1 constraints,
// §5.2) and resting faces, locations (convex regions and support surfaces, seed 003 §III-B) and
// the planner's settings. Read into plain values; everything the file alone decides (keys, types,
// numbers, names against the URDF, files) is checked here. Format: docs/scene-format.md.
#pragma once

#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "kaboum/core/types.hpp"
#include "kaboum/kinematics/geometric_constraint.hpp"
#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::io {

using namespace kaboum::kinematics;

// Where an entry was written, so that checks made later (two objects start in collision, a home
// configuration collides) name the place: the file, the entry's key path ("objects[2].pose") and
// its 1-based line and column.
struct SourceLocation {
  std::string file;
  std::string key;
  long line = 0;
  long column = 0;

  // "scene.yaml:12:5: objects[2].pose: what", the one line of an InputError.
  [[nodiscard]] std::string message(const std::string& what) const;
};

// A box, cylinder, sphere or mesh in its owner's frame (CollisionShape::origin), as URDF collision
// geometry is: primitives centred on their frame, a cylinder along its z axis, a mesh's path
// resolved against the scene file's folder and its scale in CollisionShape::size.
struct Geometry {
  CollisionShape shape;
  SourceLocation source;
};

// The joints a robot's fingers are set to when its hand is open or closed (by joint name).
struct FingerStates {
  std::map<std::string, double> open;
  std::map<std::string, double> closed;
};

// A hand's collision geometry: links of the robot's URDF, and shapes attached to the tool link.
struct HandSpec {
  std::vector<std::string> links;
  std::vector<Geometry> shapes;         // in the tool link frame
  std::optional<FingerStates> fingers;  // nullopt for a hand without finger joints
};

enum class IkMethod { Auto, ClosedForm, Numeric };

// One arm of a robot: the kinematic chain from `baseLink` to `link`, its tool centre point and
// hand, and the inverse kinematics to use (Appendix A.3 closed form, or numeric).
struct ToolSpec {
  std::string name;
  std::string link;
  std::string baseLink;         // empty: the URDF root
  Pose tcp = Pose::Identity();  // the tool centre point in the tool link frame
  IkMethod ik = IkMethod::Auto;
  std::optional<HandSpec> hand;
  SourceLocation source;
};

// One configuration variable of a robot (a movable URDF joint), in RobotModel variable order.
struct JointSpec {
  std::string name;
  double home = 0;                        // radians or metres
  std::optional<double> maxVelocity;      // the joint's entry, the URDF's, the `default` entry's
  std::optional<double> maxAcceleration;  // the joint's entry, the `default` entry's
};

// Two links of a robot whose parts are never checked against each other for self-collision
// (MoveIt's allowed collision pairs: an SRDF's <disable_collisions>, a planning scene's
// allowed_collision_matrix), by URDF link name.
struct AllowedPair {
  std::string first;
  std::string second;
};

// Appends `pair` to `pairs` unless it is there already, in either order.
void addAllowedPair(std::vector<AllowedPair>& pairs, AllowedPair pair);

struct RobotSpec {
  std::string name;
  std::string urdf;              // resolved against the scene file's folder
  Pose base = Pose::Identity();  // the URDF root in the world
  std::vector<JointSpec> joints;
  std::vector<ToolSpec> tools;
  std::vector<AllowedPair> allowedCollisions;  // each unordered pair once, in file order
  SourceLocation source;
  SourceLocation homeSource;  // the `home` entry, or the robot's when it has none
};

// A Table 5.1 constraint between a feature of the hand (in the tool centre point's frame) and a
// feature of the object (in the object frame). Every relation is symmetric, so the pair may be
// defined by Table 5.1 in either order (costFunctionFor(type, hand, object) or the reverse).
struct GraspConstraint {
  ConstraintType type = ConstraintType::Coincident;
  PrimitiveShape hand;
  PrimitiveShape object;
  double distance = 0;  // metres, for ConstraintType::Distance
};

// A motion of a grasp pose that keeps the grasp valid: a translation along or rotation about an
// axis of the object frame, over [lower, upper] (metres or radians).
struct FreeMotion {
  enum class Kind { Translation, Rotation };
  Kind kind = Kind::Rotation;
  int axis = 2;  // 0, 1, 2: x, y, z of the object frame
  double lower = 0;
  double upper = 0;
};

// The tool centre point's pose in the object frame, and the motions that keep it a grasp.
struct GraspPose {
  Pose tcp = Pose::Identity();
  std::vector<FreeMotion> free;
};

struct GraspSpec {
  std::string name;
  std::variant<std::vector<GraspConstraint>, GraspPose> definition;
  SourceLocation source;
};

// The faces an object may rest on, as outward unit normals in the object frame; `automatic`
// leaves finding them (e.g. from the convex hull) to the world model.
struct RestingFaces {
  bool automatic = true;
  std::vector<Vec3> normals;
};

struct ObjectSpec {
  std::string name;
  Geometry geometry;
  Pose pose = Pose::Identity();  // initial pose in the world
  // `place_in`: the location (index into SceneDescription::locations) where the World puts the
  // object at a random free pose instead of `pose` (movable objects only; seeded by
  // SceneSettings::placementSeed).
  std::optional<std::size_t> placeIn;
  bool movable = false;
  std::vector<GraspSpec> grasps;  // empty for a static object
  RestingFaces restingFaces;
  SourceLocation source;
  SourceLocation poseSource;  // the `pose` or `place_in` entry, or the object's when it has none
};

// A convex region: the box [lower, upper] in the frame `pose`.
struct BoxRegion {
  Pose pose = Pose::Identity();
  Vec3 lower{0, 0, 0};
  Vec3 upper{0, 0, 0};
};

// A convex region: the convex hull of `points` (given in the frame `pose`; at least four, not
// coplanar).
struct HullRegion {
  Pose pose = Pose::Identity();
  std::vector<Vec3> points;
};

// A named convex region (seed 003 §III-B): a goal region, placement area or container, tested by
// inclusion. A support surface's bottom face (a box's lower z face in its frame, a hull's
// downward faces) also counts as a surface objects can rest on.
struct LocationSpec {
  std::string name;
  std::variant<BoxRegion, HullRegion> region;
  bool supportSurface = false;
  SourceLocation source;
};

// ε of the bounded predicates (Definition 1), and the resolution of discrete path checks.
struct SceneSettings {
  double epsilon = 0.01;        // metres, or a fraction of each body's diagonal if relative
  bool epsilonRelative = true;  // default: 1% of each body's bounding-box diagonal
  double jointStep = std::numbers::pi / 180;  // radians (1°)
  double toolStep = 0.005;                    // metres
  double sweepEpsilon = 0.005;                // metres: bound of the swept volumes of motions
  std::uint64_t seed = 1;
  std::uint64_t placementSeed = 1;  // of the objects placed at random (ObjectSpec::placeIn)
  SourceLocation source;
};

// The ε of `settings` as a scene file states it: "1%" (of each body's diagonal) or "0.005"
// (metres).
std::string epsilonSetting(const SceneSettings& settings);

struct SceneDescription {
  SceneSettings settings;
  std::vector<RobotSpec> robots;
  std::vector<ObjectSpec> objects;
  std::vector<LocationSpec> locations;
};

// Reads the scene file at `path`; relative paths in it resolve against its folder. Bad input
// throws InputError with one line naming the file, line, column and key, e.g.
// "scene.yaml:12:5: objects[2].pose.orientation: zero quaternion".
SceneDescription readSceneFile(const std::string& path);

// Parses scene text; `sourceName` names it in messages and relative paths resolve against
// `baseDir`.
SceneDescription parseSceneText(const std::string& text, const std::string& sourceName,
                                const std::string& baseDir);

}  // namespace kaboum::io
