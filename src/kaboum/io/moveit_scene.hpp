// MoveIt's formats, so that users bring their MoveIt set-ups and MotionBenchMaker's problems: the
// allowed collision pairs of an SRDF, and motion problems written as a planning scene and a
// motion-plan request (YAML), read into a scene description. Reference: docs/moveit-import.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "kaboum/io/scene_file.hpp"
#include "kaboum/kinematics/robot_model.hpp"

namespace kaboum::io {

// The <disable_collisions link1="..." link2="..."/> pairs of the SRDF at `path`, each unordered
// pair once, in file order; every link must be one of `model`'s. Bad input throws InputError with
// one line, e.g. "panda.srdf:57: disable_collisions: unknown link 'panda_lnk3' (did you mean
// 'panda_link3'?)".
std::vector<AllowedPair> readSrdfAllowedPairs(const std::string& path, const RobotModel& model);

// A robot as MoveIt knows it: its URDF, its SRDF (whose <disable_collisions> pairs the
// self-collision checks skip; empty: none) and the planning group of the requests.
struct MoveItRobot {
  std::filesystem::path urdf;
  std::filesystem::path srdf;
  std::string group;                     // a request's group_name must be this (e.g. "panda_arm")
  std::vector<std::string> groupJoints;  // joints every goal sets (e.g. panda_joint1..7)
};

// One motion problem of MoveIt's planning-scene format (MotionBenchMaker): a world and a
// start/goal for one robot group. Configurations are full RobotModel variable vectors; the goal
// copies the joints outside the group from the start.
struct MotionProblem {
  SceneDescription scene;  // the robot (home: the start) and one static object per primitive
  std::string robot;       // the robot's name in `scene`: the URDF's robot name
  std::vector<double> start;
  std::vector<double> goal;
  std::string name;  // "<scene's folder>/<scene's file stem>", e.g. "box_panda/scene0001"
};

// Reads a planning scene (world.collision_objects, allowed_collision_matrix, robot_state) and a
// motion-plan request (start_state, goal_constraints) of `robot`. Bad input throws InputError
// with one line naming the file, line, column and key, e.g. "scene0001.yaml:40:15:
// world.collision_objects[2].primitives[0].type: unsupported shape 'cone' (box, cylinder,
// sphere)".
MotionProblem readMoveItProblem(const std::filesystem::path& sceneYaml,
                                const std::filesystem::path& requestYaml, const MoveItRobot& robot);

// The files of one problem in a MotionBenchMaker folder.
struct MoveItProblemFiles {
  std::filesystem::path scene;    // sceneNNNN.yaml
  std::filesystem::path request;  // requestNNNN.yaml, the same NNNN
};

// Every problem in `folder` and its sub-folders (MotionBenchMaker keeps one folder per scenario),
// sorted by path. InputError when the folder cannot be read, holds no problem, or a scene has no
// request of the same number (or a request no scene).
std::vector<MoveItProblemFiles> listMoveItProblems(const std::filesystem::path& folder);

}  // namespace kaboum::io
