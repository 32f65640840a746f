// The path file: a joint-space path of the robots of a scene, as the motion planner writes it and
// `kaboum verify-path` replays it (thesis §4.5, certified motion). Format: docs/path-format.md.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "kaboum/core/types.hpp"

namespace kaboum::io {

// An object a robot holds during a whole path: its frame at `objectInLink` in the frame of `link`.
struct HeldObject {
  std::string robot;
  std::string object;
  std::string link;
  Pose objectInLink = Pose::Identity();
};

// A joint-space path of one or several robots of a scene (docs/path-format.md): the robots that
// move, each waypoint the concatenation of their configurations (RobotModel variable order) in
// `robots` order; the other robots stay at home and the objects at their initial poses.
struct PathFile {
  std::string scene;  // the scene file, as written (informative)
  std::vector<std::string> robots;
  std::vector<std::vector<double>> waypoints;
  std::vector<HeldObject> held;
};

// Reads a path file. Everything the file alone decides is checked (format and version, keys and
// their types, finite numbers, waypoints of one length); names and lengths against a scene are
// the reader's caller's. Bad input throws InputError with one line naming the file and key, e.g.
// "path.json: waypoints[2]: 5 values, waypoints[0] has 6".
PathFile readPathFile(const std::filesystem::path& file);

// The JSON of a file (path files, plan files). Throws InputError naming the file (and line and
// column) when it cannot be read or is no JSON.
nlohmann::json readJsonFile(const std::filesystem::path& file);

// Writes `path` as toJson(path), one waypoint per line. Throws InputError when the file cannot be
// written.
void writePathFile(const std::filesystem::path& file, const PathFile& path);

// The file's JSON: format, version, scene, robots, waypoints, held (also used for --json output).
nlohmann::json toJson(const PathFile& path);

}  // namespace kaboum::io
