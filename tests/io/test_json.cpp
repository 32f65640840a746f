// io's JSON of every module's results on small real inputs: each object has exactly the documented
// keys with the values of the result it describes, and plans survive the trip through their
// readers (parsePlan, parsePlanTree).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io_test_support.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/json_geometry.hpp"
#include "kaboum/io/json_kinematics.hpp"
#include "kaboum/io/json_symbolic.hpp"
#include "kaboum/io/urdf_loader.hpp"
#include "kaboum/kinematics/arm_ik.hpp"
#include "kaboum/kinematics/kinematic_chain.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/symbolic/pddl.hpp"
#include "kaboum/symbolic/sexpr.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;
using namespace kaboum::kinematics;
using namespace kaboum::symbolic;
using namespace kaboum::testing;

namespace {

using test::meshData;
using test::ScratchDir;

std::vector<std::string> keysOf(const nlohmann::json& object) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : object.items()) keys.push_back(key);
  return keys;
}

// The keys sorted, as nlohmann::json stores an object's members.
std::vector<std::string> sorted(std::vector<std::string> keys) {
  std::sort(keys.begin(), keys.end());
  return keys;
}

void expectStats(const nlohmann::json& json, const DistanceStats& stats, double diagonal) {
  EXPECT_EQ(keysOf(json), sorted({"min", "mean", "max", "max_percent_of_diagonal"}));
  EXPECT_EQ(json.at("min").get<double>(), stats.min);
  EXPECT_EQ(json.at("mean").get<double>(), stats.mean);
  EXPECT_EQ(json.at("max").get<double>(), stats.max);
  EXPECT_EQ(json.at("max_percent_of_diagonal").get<double>(), 100.0 * stats.max / diagonal);
}

TriangleMesh orientedMesh(const std::string& name) {
  TriangleMesh mesh = readMesh(meshData(name));
  bool changed = false;
  EXPECT_TRUE(orientOutward(mesh, changed)) << name;
  return mesh;
}

TEST(GeometryJson, MeshAnalysisSurvivesAWriteAndRead) {
  ScratchDir dir;
  const TriangleMesh cube = readMesh(meshData("cube.off"));
  const nlohmann::json json = toJson(analyzeMesh(cube));
  EXPECT_EQ(keysOf(json),
            sorted({"vertices", "triangles", "components", "border_edges", "border_loops",
                    "non_manifold_edges", "non_manifold_vertices", "degenerate_triangles", "closed",
                    "edge_manifold", "consistently_oriented", "outward_oriented", "volume",
                    "diagonal", "box_min", "box_max"}));
  EXPECT_EQ(json.at("vertices"), 8);
  EXPECT_EQ(json.at("triangles"), 12);
  EXPECT_EQ(json.at("components"), 1);
  EXPECT_EQ(json.at("border_edges"), 0);
  EXPECT_EQ(json.at("closed"), true);
  EXPECT_EQ(json.at("outward_oriented"), true);
  EXPECT_NEAR(json.at("volume").get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(json.at("diagonal").get<double>(), std::sqrt(3.0), 1e-12);
  EXPECT_EQ(json.at("box_min"), nlohmann::json({0.0, 0.0, 0.0}));
  EXPECT_EQ(json.at("box_max"), nlohmann::json({1.0, 1.0, 1.0}));

  const std::string copy = dir.file("cube.obj");
  writeMesh(cube, copy);
  EXPECT_EQ(toJson(analyzeMesh(readMesh(copy))), json);
}

TEST(GeometryJson, VerifierReportsOnTheKr5WristBound) {
  const TriangleMesh wrist = orientedMesh("kr5-wrist.stl");
  BoundingMeshOptions options;
  options.targetVertices = 40;
  const BoundingMeshResult bound = simplifyBounding(wrist, options);

  const HausdorffReport hausdorff = measureHausdorff(wrist, bound.mesh, 2000, 1);
  const nlohmann::json distances = toJson(hausdorff);
  EXPECT_EQ(keysOf(distances),
            sorted({"original_to_result", "result_to_original", "diagonal", "samples"}));
  expectStats(distances.at("original_to_result"), hausdorff.originalToResult, hausdorff.diagonal);
  expectStats(distances.at("result_to_original"), hausdorff.resultToOriginal, hausdorff.diagonal);
  EXPECT_EQ(distances.at("diagonal").get<double>(), hausdorff.diagonal);
  EXPECT_EQ(distances.at("samples"), hausdorff.samples);

  const ContainmentReport containment =
      verifyContainment(wrist, bound.mesh, BoundSide::Outer, 2000, 1);
  const nlohmann::json verdict = toJson(containment);
  EXPECT_EQ(keysOf(verdict), sorted({"containment_defined", "note", "samples_checked", "violations",
                                     "worst_violation", "self_intersecting_pairs", "inside_out"}));
  EXPECT_EQ(verdict.at("containment_defined"), true);
  EXPECT_EQ(verdict.at("violations"), 0);
  EXPECT_EQ(verdict.at("self_intersecting_pairs"), 0);
  EXPECT_EQ(verdict.at("inside_out"), false);
  EXPECT_EQ(verdict.at("samples_checked"), containment.checked);
}

TEST(GeometryJson, StatisticsOfTheKr5WristBound) {
  const TriangleMesh wrist = orientedMesh("kr5-wrist.stl");
  BoundingMeshOptions options;
  options.targetVertices = 40;
  const BoundingMeshResult bound = simplifyBounding(wrist, options);
  const BoundingMeshStats& s = bound.stats;
  const nlohmann::json json = toJson(bound);
  EXPECT_EQ(keysOf(json),
            sorted({"input_vertices", "output_vertices", "output_triangles", "contractions",
                    "seconds", "runs", "contractions_per_second", "stop_reason", "locked_vertices",
                    "rejected", "polish", "quadric_error"}));
  EXPECT_EQ(json.at("input_vertices"), wrist.vertices.size());
  EXPECT_EQ(json.at("output_vertices"), 40);
  EXPECT_EQ(json.at("output_triangles"), bound.mesh.triangles.size());
  EXPECT_EQ(json.at("contractions"), s.contractions);
  EXPECT_EQ(json.at("runs"), 1);
  EXPECT_EQ(json.at("stop_reason"), s.stopReason);
  EXPECT_EQ(json.at("quadric_error").get<double>(), s.quadricError);
  EXPECT_EQ(json.at("contractions_per_second").get<double>(), contractionsPerSecond(s));
  EXPECT_EQ(keysOf(json.at("rejected")),
            sorted({"infeasible", "topology", "geometry", "crossing"}));
  EXPECT_EQ(json.at("rejected").at("crossing"), s.rejectedCrossing);
  EXPECT_EQ(keysOf(json.at("polish")), sorted({"moves", "flips", "relocations", "seconds"}));
  EXPECT_EQ(json.at("polish").at("moves"), 0);
}

TEST(GeometryJson, DecompositionOfACube) {
  const TriangleMesh cube = readMesh(meshData("cube.off"));
  const Decomposition decomposition = decomposeBounding(cube, {});
  const DecompositionQuality quality =
      measureDecomposition(decomposition.closedInput, decomposition.pieces, 2000, 1);
  const nlohmann::json json = toJson(decomposition, quality);
  EXPECT_EQ(keysOf(json),
            sorted({"input_vertices", "input_triangles", "holes_filled", "epsilon",
                    "epsilon_percent_of_diagonal", "pieces", "total_vertices", "vertices_per_piece",
                    "bounded_vertices", "hull_vertices", "splits", "refinements", "stop_reason",
                    "estimated_error", "seconds", "distances"}));
  EXPECT_EQ(json.at("input_vertices"), 8);
  EXPECT_EQ(json.at("input_triangles"), 12);
  EXPECT_EQ(json.at("holes_filled"), 0);
  EXPECT_EQ(json.at("pieces"), decomposition.pieces.size());
  EXPECT_EQ(json.at("total_vertices"), decomposition.stats.totalVertices);
  EXPECT_EQ(json.at("epsilon_percent_of_diagonal").get<double>(),
            100.0 * decomposition.stats.epsilon / quality.diagonal);
  const PieceVertexCounts counts = pieceVertexCounts(decomposition.pieces);
  EXPECT_EQ(json.at("vertices_per_piece"),
            nlohmann::json({{"min", counts.min}, {"mean", counts.mean}, {"max", counts.max}}));
  EXPECT_LE(counts.min, counts.max);

  const nlohmann::json& distances = json.at("distances");
  EXPECT_EQ(distances, toJson(quality));
  EXPECT_EQ(keysOf(distances),
            sorted({"original_to_approximation", "approximation_to_original", "diagonal", "samples",
                    "uncovered_samples", "worst_uncovered"}));
  expectStats(distances.at("original_to_approximation"), quality.originalToApproximation,
              quality.diagonal);
  expectStats(distances.at("approximation_to_original"), quality.approximationToOriginal,
              quality.diagonal);
  EXPECT_EQ(distances.at("uncovered_samples"), 0);
}

// The pose a JSON object describes.
Pose poseOf(const nlohmann::json& json) {
  const auto& p = json.at("position");
  const auto& r = json.at("quaternion_wxyz");
  Pose pose = Pose::Identity();
  pose.linear() = Eigen::Quaterniond(r[0].get<double>(), r[1].get<double>(), r[2].get<double>(),
                                     r[3].get<double>())
                      .toRotationMatrix();
  pose.translation() = Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  return pose;
}

TEST(KinematicsJson, Kr5PoseAndItsIkSolutions) {
  const RobotModel robot = loadUrdf(kr5Urdf());
  const KinematicChain chain(robot);
  const std::vector<double> q{0.1, -0.2, 0.3, 0.4, 0.5, 0.6};
  const Pose pose = chain.toolPose(q);
  const nlohmann::json json = toJson(pose);
  EXPECT_EQ(keysOf(json), sorted({"position", "quaternion_wxyz"}));
  EXPECT_EQ(json.at("position").size(), 3u);
  EXPECT_EQ(json.at("quaternion_wxyz").size(), 4u);
  EXPECT_TRUE(poseOf(json).isApprox(pose, 1e-12));

  const auto ik = ArmIk::fit(chain);
  ASSERT_TRUE(ik);
  ArmIk::Solutions found;
  ik->solve(pose, found);
  std::vector<std::vector<double>> solutions;
  for (int s = 0; s < found.count; ++s) {
    const auto& values = found.q[static_cast<std::size_t>(s)];
    solutions.emplace_back(values.begin(), values.begin() + chain.dof());
  }
  const nlohmann::json answer = ikSolutionsJson(solutions);
  EXPECT_EQ(keysOf(answer), sorted({"reachable", "solutions"}));
  EXPECT_EQ(answer.at("reachable"), true);
  ASSERT_EQ(answer.at("solutions").size(), solutions.size());
  for (const auto& solution : answer.at("solutions")) {
    EXPECT_TRUE(chain.toolPose(solution.get<std::vector<double>>()).isApprox(pose, 1e-9));
  }

  const nlohmann::json none = ikSolutionsJson({});
  EXPECT_EQ(none.at("reachable"), false);
  EXPECT_EQ(none.at("solutions"), nlohmann::json::array());
}

std::string pddl(const std::string& relative) {
  return dataFile("pddl/" + relative);
}

TEST(SymbolicJson, PlannerStatusNames) {
  EXPECT_EQ(toJson(PlannerStatus::Solved), "solved");
  EXPECT_EQ(toJson(PlannerStatus::Unsolvable), "unsolvable");
  EXPECT_EQ(toJson(PlannerStatus::TimeLimit), "time-limit");
  EXPECT_EQ(toJson(PlannerStatus::MemoryLimit), "memory-limit");
  EXPECT_EQ(toJson(PlannerStatus::NodeLimit), "node-limit");
  EXPECT_EQ(toJson(PlannerStatus::Cancelled), "cancelled");
}

TEST(SymbolicJson, BlocksPlanReportReadsBackAsAValidPlan) {
  const Domain domain = loadDomain(pddl("blocks/domain.pddl"));
  const Problem problem = loadProblem(pddl("blocks/probBLOCKS-4-0.pddl"), domain);
  const PlanReport report = plan(domain, problem, ProcedureRegistry{}, SearchOptions{});
  const nlohmann::json json = toJson(report);
  EXPECT_EQ(keysOf(json),
            sorted({"status", "plan_length", "plan", "expanded", "generated", "evaluated",
                    "reopened", "dead_ends", "stored_states", "memory_bytes", "iterations",
                    "grounding", "time", "attachments"}));
  EXPECT_EQ(json.at("status"), "solved");
  EXPECT_EQ(json.at("plan_length"), report.plan.size());
  EXPECT_EQ(json.at("expanded"), report.search.statistics.expanded);
  EXPECT_EQ(json.at("grounding"), toJson(report.grounding));
  EXPECT_EQ(keysOf(json.at("grounding")), sorted({"atoms", "operators", "fixpoint_passes"}));
  EXPECT_EQ(json.at("grounding").at("operators"), report.grounding.operators);
  EXPECT_EQ(keysOf(json.at("time")), sorted({"parse", "ground", "search", "total"}));
  EXPECT_EQ(json.at("attachments"), nlohmann::json::array());

  std::string text;
  for (const auto& step : json.at("plan")) text += step.get<std::string>() + "\n";
  const std::vector<PlanStep> steps = parsePlan(text, "plan", domain, problem);
  EXPECT_EQ(steps.size(), report.plan.size());
  AttachmentRuntime attachments(domain, problem, ProcedureRegistry{});
  const ValidationResult validation = validatePlan(domain, problem, steps, attachments);
  const nlohmann::json verdict = toJson(validation);
  EXPECT_EQ(keysOf(verdict), sorted({"valid", "failed_step", "message"}));
  EXPECT_EQ(verdict.at("valid"), true) << verdict.dump();
  EXPECT_EQ(verdict.at("failed_step"), 0);
}

TEST(SymbolicJson, UnsolvedPlanHasNoLength) {
  SearchOptions options;
  options.limits.expansions = 1;
  const PlanReport report =
      planFiles(pddl("blocks/domain.pddl"), pddl("blocks/probBLOCKS-6-0.pddl"), {}, options);
  const nlohmann::json json = toJson(report);
  EXPECT_EQ(json.at("status"), "node-limit");
  EXPECT_TRUE(json.at("plan_length").is_null());
  EXPECT_EQ(json.at("plan"), nlohmann::json::array());
}

// The tree a plan DAG's JSON describes, unfolded from the root as S-expression text.
std::string unfold(const nlohmann::json& dag) {
  std::map<int, nlohmann::json> nodes;
  for (const auto& node : dag.at("nodes")) nodes[node.at("id").get<int>()] = node;
  const std::function<std::string(int)> from = [&](int id) -> std::string {
    const nlohmann::json& node = nodes.at(id);
    const std::string kind = node.at("kind").get<std::string>();
    if (kind == "goal") return "";
    if (kind == "action") {
      return " " + node.at("action").get<std::string>() + from(node.at("next").get<int>());
    }
    return " (branch " + node.at("atom").get<std::string>() + " (true" +
           from(node.at("on_true").get<int>()) + ") (false" + from(node.at("on_false").get<int>()) +
           "))";
  };
  return "(plan" + from(dag.at("root").get<int>()) + ")";
}

TEST(SymbolicJson, ContingentPlanTreeReadsBackAsTheSameTree) {
  const std::string dir = pddl("contingent/unix/");
  const ContingentProblem contingent = loadContingent(dir + "d.pddl", dir + "p.pddl");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveContingent(task, {});
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const TreeMetrics metrics = measure(result.plan);

  const nlohmann::json json = toJson(task, result);
  EXPECT_EQ(keysOf(json), sorted({"status", "plan", "tree", "initial_worlds", "knowledge",
                                  "components", "operators", "expanded", "generated", "evaluated",
                                  "dead_ends", "reused", "knowledge_states", "worlds", "seconds"}));
  EXPECT_EQ(json.at("status"), "solved");
  EXPECT_EQ(json.at("initial_worlds"), task.possibleWorlds(task.initialBelief()));
  EXPECT_EQ(json.at("knowledge"), task.factored() ? "factored" : "explicit");
  EXPECT_EQ(json.at("components"), task.componentCount());
  EXPECT_EQ(json.at("operators"), task.task().operators.size());
  EXPECT_EQ(json.at("knowledge_states"), result.statistics.beliefs);
  EXPECT_EQ(json.at("tree"), toJson(metrics));
  EXPECT_EQ(keysOf(json.at("tree")),
            sorted({"actions", "branches", "leaves", "depth", "dag_nodes"}));
  EXPECT_EQ(json.at("tree").at("leaves").get<double>(), metrics.leaves);

  const nlohmann::json& dag = json.at("plan");
  EXPECT_EQ(dag, toJson(task, result.plan));
  EXPECT_EQ(dag.at("root"), result.plan.root);
  EXPECT_EQ(dag.at("nodes").size(), metrics.dagNodes);
  for (const auto& node : dag.at("nodes")) {
    const std::string kind = node.at("kind").get<std::string>();
    const std::vector<std::string> expected =
        kind == "goal"     ? std::vector<std::string>{"id", "kind"}
        : kind == "action" ? std::vector<std::string>{"id", "kind", "action", "next"}
                           : std::vector<std::string>{"id", "kind", "atom", "on_true", "on_false"};
    EXPECT_EQ(keysOf(node), sorted(expected)) << node.dump();
  }

  const PlanTree parsed = parsePlanTree(formatPlanTree(task, result.plan), "plan", task);
  EXPECT_EQ(unfold(toJson(task, parsed)), unfold(dag));
  EXPECT_NE(unfold(dag).find("(branch "), std::string::npos) << unfold(dag);

  const nlohmann::json empty = toJson(task, PlanTree{});
  EXPECT_TRUE(empty.at("root").is_null());
  EXPECT_EQ(empty.at("nodes"), nlohmann::json::array());
}

TEST(SymbolicJson, ContingentValidationAndExecutions) {
  const std::string dir = pddl("contingent/unix/");
  const ContingentProblem contingent = loadContingent(dir + "d.pddl", dir + "p.pddl");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveContingent(task, {});
  ASSERT_EQ(result.status, PlannerStatus::Solved);

  const TreeValidation validation = validatePlanTree(task, result.plan, "plan");
  const nlohmann::json verdict = toJson(validation);
  EXPECT_EQ(keysOf(verdict), sorted({"valid", "message", "actions", "leaves", "depth"}));
  EXPECT_EQ(verdict.at("valid"), true) << verdict.dump();
  EXPECT_EQ(verdict.at("message"), "");
  EXPECT_EQ(verdict.at("depth"), validation.metrics.depth);

  const std::string hiddenFile = dir + "hidden.pddl";
  const std::vector<HiddenState> hidden =
      parseHidden(readTextFile(hiddenFile), hiddenFile, contingent);
  ASSERT_FALSE(hidden.empty());
  for (const HiddenState& state : hidden) {
    const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(state, hiddenFile));
    const nlohmann::json json = toJson(run);
    EXPECT_EQ(keysOf(json), sorted({"reached_goal", "steps", "message"}));
    EXPECT_EQ(json.at("reached_goal"), true) << json.dump();
    EXPECT_EQ(json.at("steps").get<std::vector<std::string>>(), run.steps);
  }
}

}  // namespace
}  // namespace kaboum::io
