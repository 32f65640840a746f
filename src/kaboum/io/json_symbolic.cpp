#include "kaboum/io/json_symbolic.hpp"

#include <cstddef>
#include <vector>

namespace kaboum::io {

using namespace kaboum::symbolic;

nlohmann::json toJson(PlannerStatus status) {
  return toString(status);
}

nlohmann::json toJson(const SearchStatistics& statistics) {
  const SearchStatistics& s = statistics;
  return {{"expanded", s.expanded},        {"generated", s.generated},
          {"evaluated", s.evaluated},      {"reopened", s.reopened},
          {"dead_ends", s.deadEnds},       {"stored_states", s.storedStates},
          {"memory_bytes", s.memoryBytes}, {"iterations", s.iterations}};
}

nlohmann::json toJson(const GroundingStatistics& statistics) {
  return {{"atoms", statistics.reachableAtoms},
          {"operators", statistics.operators},
          {"fixpoint_passes", statistics.fixpointPasses}};
}

nlohmann::json toJson(const ModuleStatistics& statistics) {
  return {{"module", statistics.name},
          {"calls", statistics.calls},
          {"cache_hits", statistics.cacheHits},
          {"seconds", statistics.seconds}};
}

nlohmann::json toJson(const PlanReport& report) {
  const SearchStatistics& stats = report.search.statistics;
  nlohmann::json attachments = nlohmann::json::array();
  for (const ModuleStatistics& module : report.modules) attachments.push_back(toJson(module));
  const bool solved = report.search.status == PlannerStatus::Solved;
  nlohmann::json out = toJson(stats);
  out.update({{"status", toJson(report.search.status)},
              {"plan_length", solved ? nlohmann::json(report.plan.size()) : nlohmann::json()},
              {"plan", report.plan},
              {"grounding", toJson(report.grounding)},
              {"time",
               {{"parse", report.parseSeconds},
                {"ground", report.groundSeconds},
                {"search", stats.seconds},
                {"total", report.parseSeconds + report.groundSeconds + stats.seconds}}},
              {"attachments", attachments}});
  return out;
}

nlohmann::json toJson(const ValidationResult& result) {
  return {{"valid", result.valid}, {"failed_step", result.failedStep}, {"message", result.message}};
}

nlohmann::json toJson(const KnowledgeTask& task, const PlanTree& plan) {
  nlohmann::json nodes = nlohmann::json::array();
  if (plan.root < 0) return {{"root", nullptr}, {"nodes", nodes}};
  const std::vector<int> degree = inDegrees(plan);
  for (std::size_t i = 0; i < plan.nodes.size(); ++i) {
    if (degree[i] == 0 && static_cast<int>(i) != plan.root) continue;
    const PlanTree::Node& node = plan.nodes[i];
    nlohmann::json entry = {{"id", i}};
    if (node.kind == PlanTree::Node::Kind::Goal) {
      entry["kind"] = "goal";
    } else if (node.kind == PlanTree::Node::Kind::Action) {
      entry["kind"] = "action";
      entry["action"] = "(" + task.task().operators[node.op].name + ")";
      entry["next"] = node.next;
    } else {
      entry["kind"] = "branch";
      entry["atom"] = branchTest(task, node);
      entry["on_true"] = node.next;
      entry["on_false"] = node.onFalse;
    }
    nodes.push_back(std::move(entry));
  }
  return {{"root", plan.root}, {"nodes", nodes}};
}

nlohmann::json toJson(const TreeMetrics& metrics) {
  return {{"actions", metrics.actions},
          {"branches", metrics.branches},
          {"leaves", metrics.leaves},
          {"depth", metrics.depth},
          {"dag_nodes", metrics.dagNodes}};
}

nlohmann::json toJson(const ContingentStatistics& statistics) {
  const ContingentStatistics& s = statistics;
  return {{"expanded", s.expanded},  {"generated", s.generated}, {"evaluated", s.evaluated},
          {"dead_ends", s.deadEnds}, {"reused", s.reused},       {"knowledge_states", s.beliefs},
          {"worlds", s.worlds},      {"seconds", s.seconds}};
}

nlohmann::json toJson(const KnowledgeTask& task, const ContingentResult& result) {
  nlohmann::json out = toJson(result.statistics);
  out.update({{"status", toJson(result.status)},
              {"plan", toJson(task, result.plan)},
              {"tree", toJson(measure(result.plan))},
              {"initial_worlds", task.possibleWorlds(task.initialBelief())},
              {"knowledge", task.factored() ? "factored" : "explicit"},
              {"components", task.componentCount()},
              {"operators", task.task().operators.size()}});
  return out;
}

nlohmann::json toJson(const TreeValidation& validation) {
  return {{"valid", validation.valid},
          {"message", validation.message},
          {"actions", validation.metrics.actions},
          {"leaves", validation.metrics.leaves},
          {"depth", validation.metrics.depth}};
}

nlohmann::json toJson(const Execution& execution) {
  return {{"reached_goal", execution.reachedGoal},
          {"steps", execution.steps},
          {"message", execution.message}};
}

}  // namespace kaboum::io
