// JSON of kinematics results: tool poses and inverse kinematics solutions (lengths in metres,
// angles in radians).
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "kaboum/core/types.hpp"

namespace kaboum::io {

// position [x, y, z], quaternion_wxyz [w, x, y, z] (the rotation as a unit quaternion).
nlohmann::json toJson(const Pose& pose);

// reachable (at least one solution), solutions: one array of joint values per solution, root to
// tip.
nlohmann::json ikSolutionsJson(std::span<const std::vector<double>> solutions);

}  // namespace kaboum::io
