// A plan file as one self-contained web page (thesis §6.1.3, the run-time components; peers show
// plans in RViz or PyBullet): the scene — robots' link meshes, objects, locations — with the
// bounding convex pieces the planner used (§4.4), every action's motions timed as `kaboum execute`
// times them (exec::Schedule) and its gripper events, and the plan tree with its sensing branches;
// the viewer script bundled in, the meshes compressed. Reference: docs/viewer.md.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "kaboum/exec/schedule.hpp"

namespace kaboum::web {

struct PageOptions {
  std::string title;  // the page's title, e.g. the plan file's name
  exec::TrajectoryOptions trajectory;
};

struct PageSummary {
  std::size_t bytes = 0;
  std::size_t meshes = 0;  // distinct original meshes
  std::size_t pieces = 0;  // convex pieces
  std::size_t actions = 0;
  std::size_t branches = 0;  // sensing branch nodes
  double duration = 0;       // seconds of the longest way through the plan
};

struct PlanPage {
  std::string html;
  PageSummary summary;
};

// The page of `plan` (read with tamp::readPlanFile against `task` and `world`). Motions are timed
// rest-to-rest (the certified path; `options.trajectory.profile` is not used). Throws InputError
// for a mesh file that cannot be read.
PlanPage planPage(const world::World& world, const symbolic::KnowledgeTask& task,
                  const tamp::PlanFileContents& plan, const PageOptions& options);

// The world pose of every robot link at each of `times` along the run the page opens with (the
// true outcome at every sensing branch), as the page's window.kaboum.linkPoses() gives them:
// [{"time": t, "robots": {robot: {link: pose}}}] (io::toJson poses). The browser test's
// reference.
nlohmann::json linkPosesAt(const world::World& world, const symbolic::KnowledgeTask& task,
                           const tamp::PlanFileContents& plan, const PageOptions& options,
                           std::span<const double> times);

}  // namespace kaboum::web
