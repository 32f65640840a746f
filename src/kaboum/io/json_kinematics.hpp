// JSON of kinematics results: tool poses and inverse kinematics solutions (lengths in metres,
// angles in radians).
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "kaboum/core/types.hpp"

namespace kaboum::io {

// position [x, y, z], quaternion_wxyz [w, x, y, z] (the rotation as a unit quaternion).
nlohmann::json toJson(const Pose& pose);
// The pose toJson(Pose) writes, read from `value` (at key `key` of file `file`). Throws InputError
// with one line naming the file and the key, e.g. "plan.json: nodes[3].pose.position: expected 3
// numbers".
Pose poseFromJson(const nlohmann::json& value, const std::string& file, const std::string& key);

// reachable (at least one solution), solutions: one array of joint values per solution, root to
// tip.
nlohmann::json ikSolutionsJson(std::span<const std::vector<double>> solutions);

}  // namespace kaboum::io
