// Robot collision models as tests and benchmarks build them: the URDF's link meshes read through
// io, then bounded by collision (which reads no files).
#pragma once

#include <string>

#include "kaboum/collision/robot_collision.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::collision;

collision::RobotCollisionModel robotCollisionModel(RobotModel model,
                                                   const collision::LinkPieceOptions& pieces = {});
collision::RobotCollisionModel robotCollisionModel(const std::string& urdfPath,
                                                   const collision::LinkPieceOptions& pieces = {});

}  // namespace kaboum::testing
