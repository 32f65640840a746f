// kaboum.solve and kaboum.Solution: the integrated planner (thesis Chapter 6; `kaboum solve`, with
// the same options) from Python, the plan tree with every action's certified geometry as Python
// objects and numpy arrays, the statistics and the plan file (docs/plan-format.md).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <optional>

#include "bindings.hpp"
#include "cancellable.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/exec/executor.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/symbolic/heuristic.hpp"
#include "kaboum/tamp/plan_file.hpp"
#include "page_cli.hpp"
#include "python_attachments.hpp"
#include "scene_world.hpp"
#include "transition.hpp"

namespace kaboum::python {

namespace {

struct ActionGeometryView {
  std::string procedure;
  std::vector<std::string> arguments;
  std::size_t from = 0;
  std::size_t to = 0;
  std::vector<StepView> steps;
};

struct PlanNodeView {
  std::string kind;  // "action", "branch", "goal"
  std::string text;  // the action "(pickup kr5 block left)", the branch's test, or ""
  int next = -1;
  int onFalse = -1;
  std::uint32_t sample = 0;
  std::vector<ActionGeometryView> geometry;
};

// A finished solve: the solver (its task names the plan's actions), the result, and the Python
// attachments its task calls.
struct Solution {
  std::shared_ptr<SceneWorld> scene;
  std::shared_ptr<PythonAttachments> attachments;
  std::unique_ptr<tamp::Solver> solver;
  tamp::SolveResult result;
  tamp::PlanSources sources;
  std::vector<PlanNodeView> nodes;
};

// The figures `kaboum solve` prints on stderr every few seconds of a long solve.
struct SolveProgress {
  double seconds = 0;
  std::size_t expanded = 0;
  std::size_t geometricStates = 0;
  std::size_t motionQueries = 0;
  std::size_t failures = 0;
};

// The seed of a call's transition: the solve's, with the procedure, its arguments, read values
// and sample, so that each call draws its own motions and the same call the same ones.
std::uint64_t transitionSeed(const AttachmentCall& call) {
  std::vector<std::uint32_t> parts;
  const auto add = [&](std::uint64_t value) {
    parts.push_back(static_cast<std::uint32_t>(value));
    parts.push_back(static_cast<std::uint32_t>(value >> 32));
  };
  add(call.owner->attachments().options().seed);
  add(std::hash<std::string>{}(*call.procedure));
  for (const py::handle name : call.args) add(std::hash<std::string>{}(name.cast<std::string>()));
  for (const py::handle value : call.reads) add(std::hash<double>{}(value.cast<double>()));
  add(call.sample);
  std::seed_seq sequence(parts.begin(), parts.end());
  std::uint64_t seed = 0;
  sequence.generate(reinterpret_cast<std::uint32_t*>(&seed),
                    reinterpret_cast<std::uint32_t*>(&seed) + 2);
  return seed;
}

// Records `transition` as the geometry of geometric effect `call`; the identifier of the state it
// reaches.
double record(const AttachmentCall& call, const Transition& transition) {
  PythonAttachments& owner = *call.owner;
  const std::vector<std::string>& geometric = owner.geometricEffects();
  if (std::find(geometric.begin(), geometric.end(), *call.procedure) == geometric.end()) {
    throw std::invalid_argument(
        fmt::format("attachment '{}' records geometry: name it in kaboum.solve's geometric_effects",
                    *call.procedure));
  }
  tamp::GeometricAttachments& attachments = owner.attachments();
  const std::size_t from = owner.stateId(call);
  if (transition.scene() != owner.scene() ||
      !(transition.from() == attachments.map().state(from))) {
    throw std::invalid_argument(fmt::format(
        "attachment '{}': the transition does not start in the call's state", *call.procedure));
  }
  tamp::ActionGeometry geometry{*call.procedure, {}, from, 0, transition.steps()};
  for (const py::handle name : call.args) geometry.arguments.push_back(name.cast<std::string>());
  return static_cast<double>(attachments.record(std::move(geometry), transition.state()));
}

py::object pythonValue(const nlohmann::json& json) {
  return py::module_::import("json").attr("loads")(json.dump());
}

std::vector<PlanNodeView> nodeViews(tamp::Solver& solver, const tamp::SolveResult& result) {
  std::vector<PlanNodeView> nodes;
  symbolic::KnowledgeTask& task = solver.task();
  for (std::size_t id = 0; id < result.plan.nodes.size(); ++id) {
    const symbolic::PlanTree::Node& node = result.plan.nodes[id];
    PlanNodeView view{"goal", "", node.next, node.onFalse, node.sample, {}};
    if (node.kind == symbolic::PlanTree::Node::Kind::Action) {
      view.kind = "action";
      view.text = "(" + task.task().operators[static_cast<std::size_t>(node.op)].name + ")";
    } else if (node.kind == symbolic::PlanTree::Node::Kind::Branch) {
      view.kind = "branch";
      view.text = symbolic::branchTest(task, node);
    }
    if (id < result.geometry.size()) {
      for (const tamp::ActionGeometry& action : result.geometry[id]) {
        ActionGeometryView geometry{action.procedure, action.arguments, action.from, action.to, {}};
        for (const tamp::GeometricStep& step : action.steps) {
          geometry.steps.push_back(stepView(solver.world(), step));
        }
        view.geometry.push_back(std::move(geometry));
      }
    }
    nodes.push_back(std::move(view));
  }
  return nodes;
}

// One of `names`, or InputError naming the option.
const std::string& member(const std::string& option, const std::string& value,
                          const std::vector<std::string>& names) {
  if (std::find(names.begin(), names.end(), value) == names.end()) {
    throw InputError(
        fmt::format("{}: expected one of {}, got '{}'", option, fmt::join(names, ", "), value));
  }
  return value;
}

world::SearchStrategy placementStrategy(const std::string& name) {
  member("placement", name, {"random", "quadtree", "linear"});
  if (name == "quadtree") return world::SearchStrategy::Quadtree;
  if (name == "linear") return world::SearchStrategy::Linear;
  return world::SearchStrategy::Random;
}

void requirePositive(const char* option, double value) {
  if (!(value > 0))
    throw InputError(fmt::format("{}: expected a positive number, got {}", option, value));
}

std::unique_ptr<Solution> solve(const std::shared_ptr<SceneWorld>& scene, const std::string& domain,
                                const std::string& problem, const std::string& search,
                                const std::string& heuristic, double timeLimit,
                                std::optional<std::size_t> nodeLimit, double memoryLimit,
                                std::size_t maxWorlds, std::uint64_t seed, double motionTimeLimit,
                                const std::string& planner, const std::string& placement,
                                int graspSamples, std::uint32_t samples, bool integrated,
                                bool verify, const std::optional<py::dict>& attachments,
                                const std::vector<std::string>& geometricEffects,
                                const std::optional<py::function>& progress,
                                double progressPeriod) {
  tamp::SolveOptions options;
  options.search.mode = member("search", search, symbolic::contingentSearchModes());
  options.search.heuristic = member("heuristic", heuristic, symbolic::heuristicNames());
  requirePositive("time_limit", timeLimit);
  requirePositive("memory_limit", memoryLimit);
  requirePositive("motion_time_limit", motionTimeLimit);
  requirePositive("grasp_samples", graspSamples);
  requirePositive("progress_period", progressPeriod);
  if (samples < 1 || samples > 1000) {
    throw InputError(fmt::format("samples: expected 1 to 1000, got {}", samples));
  }
  options.search.limits.seconds = timeLimit;
  if (nodeLimit) options.search.limits.expansions = *nodeLimit;
  options.search.limits.memoryBytes = static_cast<std::size_t>(memoryLimit * 1e6);
  options.search.samples = samples;
  options.search.symbolicFirst = !integrated;
  options.maxWorlds = maxWorlds;
  options.geometry.seed = seed;
  options.geometry.motion.timeLimit = motionTimeLimit;
  options.geometry.motion.planner = member("planner", planner, motion::motionPlannerNames());
  options.geometry.placementStrategy = placementStrategy(placement);
  options.geometry.graspSamples = graspSamples;
  options.verify = verify;
  auto solution = std::make_unique<Solution>();
  solution->scene = scene;
  solution->sources = {domain, problem, scene->file()};
  const auto cancel = std::make_shared<std::atomic<bool>>(false);
  if (attachments || !geometricEffects.empty()) {
    solution->attachments = std::make_shared<PythonAttachments>(
        scene, attachments.value_or(py::dict()), geometricEffects, cancel);
    options.registerProcedures = [python = solution->attachments.get()](
                                     tamp::GeometricAttachments& geometric,
                                     symbolic::ProcedureRegistry& registry) {
      python->registerProcedures(geometric, registry);
    };
    options.geometricEffects = geometricEffects;
  }
  if (progress) {
    // Called on the solve's thread while the solver exists; the GIL only for the call. False
    // cancels the solve.
    options.search.progress = [&solution, &progress,
                               cancel](const symbolic::ContingentStatistics& searched) {
      const tamp::GeometricAttachments& geometric = solution->solver->attachments();
      const SolveProgress figures{searched.seconds, searched.expanded, geometric.map().size(),
                                  geometric.statistics().motionQueries,
                                  geometric.statistics().failures};
      py::gil_scoped_acquire locked;
      const py::object answer = (*progress)(figures);
      if (py::isinstance<py::bool_>(answer) && !answer.cast<bool>()) *cancel = true;
    };
    options.search.progressPeriod = progressPeriod;
  }
  options.search.limits.cancel = cancel.get();
  options.geometry.motion.cancel = cancel.get();
  runCancellable(
      [&] {
        solution->solver = std::make_unique<tamp::Solver>(
            scene->world(), symbolic::loadContingent(domain, problem), options);
        solution->result = solution->solver->solve();
      },
      *cancel);
  solution->nodes = nodeViews(*solution->solver, solution->result);
  return solution;
}

nlohmann::json planFile(Solution& self) {
  return tamp::planFileJson(*self.solver, self.result, self.sources);
}

// A run through the plan (thesis §6.1.3): the actions timed as quintic trajectories on one clock.
struct Execution {
  std::shared_ptr<SceneWorld> scene;
  exec::ExecutionResult result;
};

// Walks the plan from its root as `kaboum execute` does, each sensing outcome from `sensing`
// (called with the branch's test, "(isemptybottle o1)", returning its truth).
Execution execute(Solution& self, const std::optional<py::function>& sensing,
                  const std::string& profile) {
  if (self.result.status != PlannerStatus::Solved) {
    throw std::invalid_argument("execute: the solve found no plan (" +
                                toString(self.result.status) + ")");
  }
  exec::ExecutionOptions options;
  options.trajectory.profile = exec::profileNamed(profile);
  if (sensing) {
    options.sensing = [&sensing](const exec::SensingQuery& query) {
      return static_cast<bool>(py::bool_((*sensing)(query.test)));
    };
  }
  const tamp::PlanFileContents plan{self.result.plan, self.result.geometry};
  return {self.scene, exec::execute(self.scene->world(), self.solver->task(), plan, options)};
}

// Robot `robot`'s trajectory sampled at `rate` Hz: times, and positions, velocities and
// accelerations (samples × joints).
py::tuple trajectory(const Execution& self, const std::string& robot, double rate) {
  requirePositive("rate", rate);
  const exec::RobotSamples samples =
      exec::sampleRobot(self.result.schedule, self.scene->robot(robot), rate);
  const auto table = [&](const std::vector<double>& values) {
    py::array_t<double> array({samples.times.size(), samples.dof});
    std::copy(values.begin(), values.end(), array.mutable_data());
    return array;
  };
  return py::make_tuple(vectorArray(samples.times), table(samples.positions),
                        table(samples.velocities), table(samples.accelerations));
}

}  // namespace

void bindSolve(py::module_& module) {
  py::class_<AttachmentCall>(module, "AttachmentCall",
                             "What an attachment written in Python receives (docs/python.md).")
      .def_readonly("args", &AttachmentCall::args,
                    "The names of the module's arguments, as the problem names its objects.")
      .def_readonly("reads", &AttachmentCall::reads,
                    "The values of the fluents the module reads, in declaration order.")
      .def_readonly("sample", &AttachmentCall::sample,
                    "Which geometric sample of this call an effect computes (solve's samples).")
      .def_property_readonly(
          "world", [](const AttachmentCall& self) { return self.owner->scene(); }, "The scene.")
      .def_property_readonly(
          "state",
          [](const AttachmentCall& self) {
            return SceneState{self.owner->scene(),
                              self.owner->attachments().map().state(self.owner->stateId(self))};
          },
          "The geometric state whose identifier is the first read value.")
      .def(
          "transition",
          [](const AttachmentCall& self) {
            const tamp::GeometricAttachments& attachments = self.owner->attachments();
            return Transition(
                self.owner->scene(), attachments.map().state(self.owner->stateId(self)),
                attachments.options().motion, transitionSeed(self), self.owner->cancel());
          },
          "A Transition from the call's state whose motions use the solve's planner and "
          "motion_time_limit, stop on Ctrl-C, and are seeded by the solve's seed and the call.")
      .def("record", &record, py::arg("transition"),
           "Records `transition` (from the call's state) as this geometric effect's geometry, "
           "which the plan then carries and verifies, and returns the identifier of the state "
           "it reaches: the value of the geometric state fluent the effect writes. ValueError "
           "unless the procedure is in solve's geometric_effects.");
  py::class_<SolveProgress>(module, "Progress",
                            "The figures of a long solve, as `kaboum solve` prints them.")
      .def_readonly("seconds", &SolveProgress::seconds, "Seconds of search so far.")
      .def_readonly("expanded", &SolveProgress::expanded, "Knowledge states expanded.")
      .def_readonly("geometric_states", &SolveProgress::geometricStates)
      .def_readonly("motion_queries", &SolveProgress::motionQueries)
      .def_readonly("failures", &SolveProgress::failures, "Failed geometric calls.");
  py::class_<ActionGeometryView>(module, "ActionGeometry",
                                 "The geometry of one geometric effect of a plan action.")
      .def_readonly("procedure", &ActionGeometryView::procedure, "'pickUp', 'putDown', …")
      .def_readonly("arguments", &ActionGeometryView::arguments)
      .def_readonly("from_state", &ActionGeometryView::from,
                    "Geometric state identifier before (Solution.state).")
      .def_readonly("to_state", &ActionGeometryView::to, "Geometric state identifier after.")
      .def_readonly("steps", &ActionGeometryView::steps);
  py::class_<PlanNodeView>(module, "PlanNode",
                           "A node of the plan tree: an action, a branch on a sensed fact, or a "
                           "goal leaf.")
      .def_readonly("kind", &PlanNodeView::kind, "'action', 'branch' or 'goal'.")
      .def_readonly("text", &PlanNodeView::text,
                    "The action '(pickup kr5 block left)', the branch's test '(p a)', or ''.")
      .def_readonly("next", &PlanNodeView::next,
                    "The next node (a branch: where the test holds); -1 for none.")
      .def_readonly("on_false", &PlanNodeView::onFalse,
                    "A branch: the node where the test does not hold; else -1.")
      .def_readonly("sample", &PlanNodeView::sample,
                    "An action: the geometric sample its effects computed.")
      .def_readonly("geometry", &PlanNodeView::geometry,
                    "An action: the geometry of its geometric effects.");

  py::class_<Solution>(module, "Solution", "What kaboum.solve found, verified.")
      .def_property_readonly(
          "status", [](const Solution& self) { return toString(self.result.status); },
          "'solved', 'unsolvable', 'time-limit', 'memory-limit', 'node-limit' or 'cancelled'.")
      .def_property_readonly(
          "solved",
          [](const Solution& self) {
            return self.result.status == PlannerStatus::Solved && self.result.verification.passed();
          },
          "Solved and the plan passed its checks (the exit code 0 of `kaboum solve`).")
      .def_property_readonly(
          "message", [](const Solution& self) { return self.result.message; },
          "Why there is no plan or why it failed its checks; '' otherwise.")
      .def_property_readonly(
          "failures", [](const Solution& self) { return self.result.geometric.recentFailures; },
          "The latest failed geometric calls and why.")
      .def_property_readonly(
          "root", [](const Solution& self) { return self.result.plan.root; },
          "The index of the plan's first node, -1 without a plan.")
      .def_property_readonly(
          "nodes", [](const Solution& self) { return self.nodes; },
          "The plan's nodes (a tree that may share nodes); follow next and on_false from root.")
      .def(
          "plan_text",
          [](Solution& self) {
            return symbolic::formatPlanTree(self.solver->task(), self.result.plan);
          },
          "The plan as `kaboum solve` prints it (docs/contingent.md).")
      .def(
          "state",
          [](Solution& self, std::size_t id) {
            return SceneState{self.scene, self.solver->attachments().map().state(id)};
          },
          py::arg("id"),
          "The geometric state of an identifier (ActionGeometry.from_state, to_state; 0 is the "
          "initial state). IndexError for an unknown one.")
      .def_property_readonly(
          "geometric_states",
          [](Solution& self) { return self.solver->attachments().map().size(); },
          "How many geometric states the search computed.")
      .def_property_readonly(
          "statistics",
          [](Solution& self) {
            return pythonValue(tamp::statisticsJson(self.scene->world(), self.result));
          },
          "Times, search, attachment calls and geometry (thesis Table 6.7; the plan file's "
          "'statistics').")
      .def(
          "plan_file", [](Solution& self) { return pythonValue(planFile(self)); },
          "The plan file as a dict (docs/plan-format.md).")
      .def(
          "write_plan",
          [](Solution& self, const std::string& path) {
            std::ofstream out(path);
            if (!out || !(out << planFile(self).dump(1) << "\n")) {
              throw InputError(locate(path, "cannot write the plan file"));
            }
          },
          py::arg("path"),
          "Writes the plan file that `kaboum verify-plan` and `kaboum execute` read.")
      .def(
          "write_page",
          [](Solution& self, const std::string& path) {
            if (self.result.status != PlannerStatus::Solved) {
              throw std::invalid_argument("write_page: the solve found no plan");
            }
            const tamp::PlanFileContents plan{self.result.plan, self.result.geometry};
            const web::PageSummary summary = cli::writePlanPage(
                path, self.sources.problem, self.scene->world(), self.solver->task(), plan);
            return pythonValue(cli::pageJson(path, summary));
          },
          py::arg("path"),
          "Writes the plan as one self-contained 3-D web page, as `kaboum solve --html` "
          "(docs/viewer.md); returns its summary (bytes, meshes, pieces, actions, branches, "
          "duration).")
      .def("execute", &execute, py::arg("sensing") = py::none(), py::kw_only(),
           py::arg("profile") = "rest-to-rest",
           "Runs the plan from its root as `kaboum execute` does: `sensing(test)` gives each "
           "branch's outcome ('(isemptybottle o1)' -> bool); `profile` 'rest-to-rest' or "
           "'blended'. Raises InputError when a branch is met without `sensing`.");

  py::class_<Execution>(module, "Execution",
                        "A run through the plan: every action's paths timed as quintic "
                        "trajectories within the joint limits on one clock (docs/execution.md).")
      .def_property_readonly("reached_goal",
                             [](const Execution& self) { return self.result.reachedGoal; })
      .def_property_readonly(
          "duration", [](const Execution& self) { return self.result.schedule.duration(); },
          "Seconds from the first action's start to the last one's end.")
      .def_property_readonly(
          "actions",
          [](const Execution& self) {
            std::vector<py::tuple> actions;
            for (const exec::TimedAction& action : self.result.schedule.actions()) {
              actions.push_back(py::make_tuple(action.name, action.start, action.end));
            }
            return actions;
          },
          "(name, start, end) of every action run, in order.")
      .def_property_readonly(
          "sensed",
          [](const Execution& self) {
            std::vector<py::tuple> outcomes;
            for (const exec::SensingOutcome& outcome : self.result.sensed) {
              outcomes.push_back(py::make_tuple(outcome.test, outcome.value, outcome.time));
            }
            return outcomes;
          },
          "(test, outcome, time) of every sensing branch met.")
      .def("trajectory", &trajectory, py::arg("robot"), py::arg("rate") = 1000.0,
           "The robot's trajectory sampled at `rate` Hz: (times, positions, velocities, "
           "accelerations), the last three samples x joints.");

  module.def("solve", &solve, py::arg("world"), py::arg("domain"), py::arg("problem"),
             py::kw_only(), py::arg("search") = "gbfs", py::arg("heuristic") = "ff",
             py::arg("time_limit") = 60.0, py::arg("node_limit") = py::none(),
             py::arg("memory_limit") = 8000.0, py::arg("max_worlds") = std::size_t{1} << 18,
             py::arg("seed") = 1, py::arg("motion_time_limit") = 2.0,
             py::arg("planner") = "rrtconnect", py::arg("placement") = "random",
             py::arg("grasp_samples") = 16, py::arg("samples") = 1, py::arg("integrated") = false,
             py::arg("verify") = true, py::arg("attachments") = py::none(),
             py::arg("geometric_effects") = std::vector<std::string>{},
             py::arg("progress") = py::none(), py::arg("progress_period") = 5.0,
             "Solves the PDDL `domain` and `problem` in `world` as `kaboum solve` does, with the "
             "same options (time_limit and motion_time_limit in seconds, memory_limit in MB). "
             "`attachments` maps procedure names of the domain's :modules to Python callables "
             "(docs/python.md); `geometric_effects` names those that record geometry "
             "(AttachmentCall.record) and write the geometric state fluent. `progress(figures)` "
             "is called every `progress_period` seconds of search with a Progress (False "
             "cancels). Releases the GIL; Ctrl-C cancels the search and raises "
             "KeyboardInterrupt. Raises InputError for bad files or options.");
}

}  // namespace kaboum::python
