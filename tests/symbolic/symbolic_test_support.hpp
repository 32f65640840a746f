// Helpers shared by the symbolic tests: data paths, planning a file pair and validating the plan
// with our validator, and running the CLI.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/symbolic/planner.hpp"
#include "kaboum/symbolic/validator.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::symbolic::testing {

using namespace kaboum::testing;

inline std::string pddlPath(const std::string& relative) {
  return kaboum::testing::dataFile("pddl/" + relative);
}

// A domain/problem pair under data/pddl.
struct IpcInstance {
  std::string domain;
  std::string problem;
};

// One small instance of every copied IPC domain (and the ADL feature test), for search tests.
inline const std::vector<IpcInstance>& smallIpcInstances() {
  static const std::vector<IpcInstance> instances = {
      {"blocks/domain.pddl", "blocks/probBLOCKS-4-0.pddl"},
      {"gripper/domain.pddl", "gripper/prob01.pddl"},
      {"logistics00/domain.pddl", "logistics00/probLOGISTICS-4-0.pddl"},
      {"depot/domain.pddl", "depot/p01.pddl"},
      {"miconic/domain.pddl", "miconic/s3-0.pddl"},
      {"adl/domain.pddl", "adl/problem.pddl"}};
  return instances;
}

// Plans and checks the plan with validatePlan; returns the report.
inline PlanReport planAndValidate(const Domain& domain, const Problem& problem,
                                  const SearchOptions& options,
                                  const ProcedureRegistry& procedures = {}) {
  PlanReport report = plan(domain, problem, procedures, options);
  if (report.search.status == PlannerStatus::Solved) {
    std::string text;
    for (const std::string& step : report.plan) text += step + "\n";
    const std::vector<PlanStep> steps = parsePlan(text, "plan", domain, problem);
    AttachmentRuntime attachments(domain, problem, procedures);
    const ValidationResult verdict = validatePlan(domain, problem, steps, attachments);
    EXPECT_TRUE(verdict.valid) << options.mode << "/" << options.heuristic << ": "
                               << verdict.message;
  }
  return report;
}

inline std::string contingentPath(const std::string& relative) {
  return pddlPath("contingent/" + relative);
}

// The InputError message of reading a contingent domain ("d.pddl") and problem ("p.pddl") and
// building their knowledge task; "" if there is none.
std::string errorOf(const std::string& domain, const std::string& problem);

// Solves, checks that the printed tree reads back with the same size and that every branch
// validates, and returns the result.
ContingentResult solveAndValidate(KnowledgeTask& task, const ContingentOptions& options = {});

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr
};

// Runs the kaboum CLI with `arguments` (a shell-quoted string).
CommandResult runCli(const std::string& arguments);

// Writes `text` to a fresh file under the test temp directory and returns its path.
std::string writeTempFile(const std::string& name, const std::string& text);

}  // namespace kaboum::symbolic::testing
