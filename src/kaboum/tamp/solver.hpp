// The integrated planner (thesis §6.1, Figure 6.1; Definition 5): the knowledge-level planner
// searches a domain whose geometric preconditions and effects are the geometric attachments, in
// the integrated space of symbolic and geometric states; the plan — a tree that branches on
// sensing — comes back with the geometry of every action, checked by the symbolic validator and
// with every path replayed by the independent verifier on the original meshes. Reference:
// docs/tamp.md.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "kaboum/core/planner_status.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/tamp/geometric_attachments.hpp"
#include "kaboum/verify/path_verifier.hpp"

namespace kaboum::tamp {

struct SolveOptions {
  symbolic::ContingentOptions search;  // mode, heuristic, time and node limits
  std::size_t maxWorlds = std::size_t{1} << 18;
  TampOptions geometry;
  bool verify = true;  // replay every path with the independent verifier
  verify::VerifyOptions verification;
  // Registers further procedures (the Python API's attachments, docs/python.md) after the
  // geometric attachments, whose map gives them the geometric state behind an identifier.
  std::function<void(GeometricAttachments&, symbolic::ProcedureRegistry&)> registerProcedures;
  // Procedures registered there that are geometric effects too: each writes the identifier that
  // GeometricAttachments::record gave the state it reached, its geometry recorded there.
  std::vector<std::string> geometricEffects;
};

// One motion of a plan replayed on the original meshes.
struct PathCheck {
  std::size_t node = 0;  // the plan node of its action
  std::string action;    // the geometric effect: "pickUp(kr5, block)"
  std::size_t step = 0;  // index into the effect's steps
  GeometricStep::Kind kind = GeometricStep::Kind::Transit;
  std::string robot;
  verify::PathVerification result;
};

// The independent checks of a plan: the symbolic validator over every branch, and every motion
// replayed on the original meshes.
struct PlanVerification {
  symbolic::TreeValidation symbolic;
  bool pathsChecked = false;
  std::size_t paths = 0;
  std::size_t samples = 0;
  std::size_t collidingPaths = 0;
  double smallestClearance = 0;   // metres, over every path (infinity when nothing is checked)
  std::string firstCollision;     // "pickUp(kr5, block) step 2 (approach): …", or ""
  std::vector<PathCheck> checks;  // every path, in the order checked
  double seconds = 0;

  [[nodiscard]] bool passed() const {
    return symbolic.valid && (!pathsChecked || collidingPaths == 0);
  }
};

struct SolveResult {
  PlannerStatus status = PlannerStatus::Unsolvable;
  std::string message;  // why there is no plan, or why a plan failed its checks
  symbolic::PlanTree plan;
  // Per plan node: the geometry of its action's geometric effects (empty for other nodes).
  std::vector<std::vector<ActionGeometry>> geometry;
  symbolic::ContingentStatistics search;
  GeometricStatistics geometric;
  std::vector<symbolic::ModuleStatistics> modules;
  std::size_t geometricStates = 0;
  double seconds = 0;           // the whole solve, verification excluded
  double symbolicSeconds = 0;   // search time outside the attachments
  double geometricSeconds = 0;  // inside the geometric attachments
  PlanVerification verification;
};

class Solver {
 public:
  // Binds the domain's modules to the geometric attachments (and to libraries it names), checks
  // that every argument of a geometric attachment names a scene entity of the right kind and that
  // the geometric fluents start at the initial state (0). Throws InputError naming the problem
  // file, the scene file and the name otherwise. `world` must outlive the solver.
  Solver(const World& world, symbolic::ContingentProblem problem, SolveOptions options = {});
  ~Solver();
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  SolveResult solve();

  [[nodiscard]] symbolic::KnowledgeTask& task() { return *task_; }
  [[nodiscard]] const symbolic::ContingentProblem& problem() const { return problem_; }
  [[nodiscard]] const GeometricAttachments& attachments() const { return *attachments_; }
  [[nodiscard]] const World& world() const { return *world_; }
  // The fluents that hold a geometric state identifier (written by geometric effects).
  [[nodiscard]] const std::vector<symbolic::FluentId>& geometricFluents() const {
    return geometricFluents_;
  }

 private:
  // Whether module `module` is bound to one of options_.geometricEffects.
  [[nodiscard]] bool isRecordedEffect(const symbolic::Module& module) const;
  void checkCalls();
  // The geometry of every action node, replaying the plan from the initial knowledge; false with
  // `message` when an action's geometric state is not the same in every world it runs in.
  bool collectGeometry(SolveResult& result);
  void verifyPlan(SolveResult& result);

  const World* world_;
  symbolic::ContingentProblem problem_;
  SolveOptions options_;
  std::unique_ptr<GeometricAttachments> attachments_;
  std::unique_ptr<symbolic::KnowledgeTask> task_;
  std::vector<symbolic::FluentId> geometricFluents_;
};

// The states along an action's steps: before each step, and after the last (a Grasp holds the
// object, taking it from the robot holding it in a handover; a Release places it, or right after
// a handover's Grasp leaves it with the receiver). Throws std::invalid_argument for a gripper
// event that does not apply (a Release of an object the robot neither holds nor just handed over).
std::vector<GeometricState> statesAlong(const World& world, const GeometricState& from,
                                        const ActionGeometry& action);

// Replays every motion of `action` (of plan node `node`) with the independent verifier in its
// state — `states` as statesAlong() gives them, the robot holding what it holds there — and adds
// each to `verification`.
void verifyActionPaths(const verify::ReferenceGeometry& reference, std::size_t node,
                       const ActionGeometry& action, const std::vector<GeometricState>& states,
                       const verify::VerifyOptions& options, PlanVerification& verification);

}  // namespace kaboum::tamp
