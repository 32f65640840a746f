// Reading back and independently checking the plan file that `kaboum solve --plan-out` writes
// (docs/plan-format.md; thesis §6.1.3, what execution relies on): the plan tree against the
// problem's knowledge-level task and every action's geometry against the World; the symbolic
// validator over every branch, and the geometry replayed from the World's initial state along the
// plan with every motion checked by the independent verifier. Reference: docs/verify.md.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "kaboum/tamp/solver.hpp"

namespace kaboum::tamp {

// A plan file resolved against a task and a World: the plan tree (nodes numbered as the file
// numbers them) and per node the geometry of its action (empty for other nodes).
struct PlanFileContents {
  symbolic::PlanTree plan;
  std::vector<std::vector<ActionGeometry>> geometry;
};

// Reads plan file `fileName` (its JSON `json`): actions and branch tests by name against `task`;
// robots, tools and objects by name against `world`; poses; waypoints checked against the robot's
// joint count and limits. Throws InputError with one line naming the file and the key, e.g.
// "plan.json: nodes[3].geometry[0].steps[1].waypoints[2]: 5 values, but robots 'kr5' have 6
// joints".
PlanFileContents readPlanFile(const nlohmann::json& json, const std::string& fileName,
                              const symbolic::KnowledgeTask& task, const World& world);

struct PlanCheckOptions {
  verify::VerifyOptions verification;
  // Called before each action's geometry is replayed, with "nodes[3] (pickup kr5 block left)".
  std::function<void(const std::string&)> progress;
};

// Metres and radians: how far a grasp or release may be from the pose the robot's configuration
// gives, and (joint units) a motion from where the robot is.
inline constexpr double kPlanPositionTolerance = 1e-3;
inline constexpr double kPlanAngleTolerance = 0.1 * std::numbers::pi / 180;
inline constexpr double kPlanJointTolerance = 1e-6;

struct PlanCheck {
  PlanFileContents contents;
  // The symbolic validation of every branch and every motion on the original meshes.
  PlanVerification verification;
  // Geometry that does not follow on: a motion not starting where the robot is, a grasp or
  // release away from the object, branches that rejoin in different states, e.g. "nodes[3]
  // (pickup kr5 block left): pickUp(kr5, block) step 2 (approach): starts 0.2 (joint 'a1') from
  // where robot 'kr5' is".
  std::vector<std::string> failures;

  [[nodiscard]] bool passed() const { return verification.passed() && failures.empty(); }
};

// Reads plan file `fileName` (its JSON `json`) of `problem` and checks it in `world`: the symbolic
// validator over every branch, the geometric effects answered by the plan's own transitions and
// the condition checkers evaluated on the replayed states; every action's steps applied in order
// from the World's initial state along every branch, each motion replayed by verify::verifyPath.
// Throws InputError for bad input (readPlanFile's, or modules naming no attachment).
PlanCheck verifyPlanFile(const World& world, const symbolic::ContingentProblem& problem,
                         const nlohmann::json& json, const std::string& fileName,
                         const PlanCheckOptions& options = {});

}  // namespace kaboum::tamp
