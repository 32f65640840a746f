#include "kaboum/testing/robot_collision_models.hpp"

#include "kaboum/io/urdf_loader.hpp"

namespace kaboum::testing {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::io;
using namespace kaboum::collision;

collision::RobotCollisionModel robotCollisionModel(RobotModel model,
                                                   const collision::LinkPieceOptions& pieces) {
  const auto meshes = readCollisionMeshes(model);
  return collision::RobotCollisionModel(std::move(model), meshes, pieces);
}

collision::RobotCollisionModel robotCollisionModel(const std::string& urdfPath,
                                                   const collision::LinkPieceOptions& pieces) {
  return robotCollisionModel(loadUrdf(urdfPath), pieces);
}

}  // namespace kaboum::testing
