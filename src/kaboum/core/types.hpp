// The vocabulary every module shares: points and rigid transforms (thesis §2.1 notation: a pose
// is an element of SE(3), applied to points in metres).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace kaboum {

using Vec3 = Eigen::Vector3d;
using Pose = Eigen::Isometry3d;

}  // namespace kaboum
