// Loads a RobotModel from URDF with urdfdom: revolute, continuous, prismatic, fixed and planar
// (mobile base: x, y, θ) joints, limits, link frames and collision geometry (thesis §3.1).
#pragma once

#include <map>
#include <string>

#include "kaboum/geometry/triangle_mesh.hpp"
#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;

// Reads `path`. Bad input (malformed XML, unknown or floating joint types, kinematic loops,
// missing mesh files, missing limits) throws InputError naming the file and the element.
RobotModel loadUrdf(const std::string& path);

// Parses URDF text; `sourceName` names it in errors and mesh paths resolve against `baseDir`.
RobotModel parseUrdf(const std::string& xml, const std::string& sourceName,
                     const std::string& baseDir);

// Reads every mesh file that `model`'s collision shapes name, keyed by CollisionShape::meshPath
// (what collision::RobotCollisionModel takes). Throws InputError naming an unreadable file.
std::map<std::string, TriangleMesh> readCollisionMeshes(const RobotModel& model);

}  // namespace kaboum::io
