// The examples the exec tests run (tests/exec/data/README.md): a scenario's World, its task, and a
// committed plan file read against them, each built once per test program.
#pragma once

#include <memory>
#include <string>

#include "../support/test_support.hpp"
#include "kaboum/exec/executor.hpp"
#include "kaboum/io/path_file.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"

namespace kaboum::exec {

inline std::string execData(const std::string& file) {
  return testing::sourceFile("tests/exec/data/" + file);
}

// A scenario of examples/ with one of its problems and a plan file of it.
class ExampleRun {
 public:
  ExampleRun(const std::string& folder, const std::string& domain, const std::string& problem,
             const std::string& plan)
      : world_(io::readSceneFile(testing::exampleFile(folder + "/scene.yaml")),
               {world::MeshPieces::Hulls, std::nullopt}),
        problem_(symbolic::loadContingent(testing::exampleFile(folder + "/" + domain),
                                          testing::exampleFile(folder + "/" + problem))),
        attachments_(world_) {
    attachments_.registerProcedures(registry_);
    task_ = std::make_unique<symbolic::KnowledgeTask>(problem_, registry_);
    plan_ = tamp::readPlanFile(io::readJsonFile(execData(plan)), plan, *task_, world_);
  }

  [[nodiscard]] const world::World& world() const { return world_; }
  [[nodiscard]] const symbolic::ContingentProblem& problem() const { return problem_; }
  [[nodiscard]] symbolic::KnowledgeTask& task() { return *task_; }
  [[nodiscard]] const tamp::PlanFileContents& plan() const { return plan_; }

 private:
  world::World world_;
  symbolic::ContingentProblem problem_;
  tamp::GeometricAttachments attachments_;
  symbolic::ProcedureRegistry registry_;
  std::unique_ptr<symbolic::KnowledgeTask> task_;
  tamp::PlanFileContents plan_;
};

inline ExampleRun& pickAndPlace() {
  static ExampleRun run("pick-and-place", "domain.pddl", "problem.pddl",
                        "pick-and-place.plan.json");
  return run;
}

inline ExampleRun& bartender() {
  static ExampleRun run("bartender", "domain.pddl", "problem-1.pddl", "bartender-1.plan.json");
  return run;
}

}  // namespace kaboum::exec
