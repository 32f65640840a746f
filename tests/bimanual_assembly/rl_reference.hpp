// An independent reading of the Bimanual Assembly scenario's Robotics Library files (thesis
// §6.2.3; the scenario's README asks to check a conversion against them): forward kinematics of an
// rlmdl kinematics file (frames, fixed transforms, revolute and prismatic joints) and the poses at
// which a VRML scene graph places its inlined files. Shares no code with kaboum's URDF and VRML
// readers, so that the tests compare two separate derivations.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

namespace kaboum::rl {

using Pose = Eigen::Isometry3d;

// One joint or fixed transform of an rlmdl file: frame `a` to frame `b`.
struct MdlTransform {
  enum class Kind { Fixed, Revolute, Prismatic };
  Kind kind = Kind::Fixed;
  std::string id, a, b;
  Pose fixed = Pose::Identity();  // Fixed: rotation z·y·x (degrees in the file), then translation
  Eigen::Vector3d axis{0, 0, 1};  // Revolute, Prismatic (the Robotics Library's default is z)
};

// An rlmdl kinematic model: the world frame's pose and the transforms in file order (each
// transform's frame `a` is placed by an earlier one or is the world).
struct MdlModel {
  std::string worldId;
  Pose world = Pose::Identity();
  std::vector<MdlTransform> transforms;
  // The ids of the joints, in file order (the configuration's order).
  [[nodiscard]] std::vector<std::string> jointIds() const;
  // World pose of every frame and body at joint values `q` (radians, metres) by joint id.
  [[nodiscard]] std::map<std::string, Pose> framePoses(
      const std::map<std::string, double>& q) const;
};

// Reads an rlmdl file (`path`); throws std::runtime_error naming the file on what it cannot read.
MdlModel readMdl(const std::string& path);

// A file inlined by a VRML scene graph: the file name, its frame in the graph's root frame, and
// the nearest enclosing Transform with a DEF name (its name and its frame in the root frame). A
// Shape written in place is listed with url "Shape".
struct PlacedInline {
  std::string def;
  std::string url;
  Pose pose = Pose::Identity();
  Pose defPose = Pose::Identity();
};

// The inlines of VRML file `path`, following the inlines whose file name is in `expand` (their
// contents placed at their pose, their DEF names inherited).
std::vector<PlacedInline> readVrmlPlacements(const std::string& path,
                                             const std::vector<std::string>& expand = {});

}  // namespace kaboum::rl
