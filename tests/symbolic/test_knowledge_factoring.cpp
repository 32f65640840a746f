// Factored knowledge states (knowledge_factoring.hpp, docs/contingent.md "Knowledge
// representations"): the same solvability and plans that both representations accept, on every
// contingent instance of data/, and components that follow the domain's couplings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/scenarios/bartender.hpp"
#include "kaboum/scenarios/force_sensing.hpp"
#include "kaboum/scenarios/toy_geometry.hpp"
#include "kaboum/scenarios/unknown_roads.hpp"
#include "kaboum/symbolic/sexpr.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {
namespace {

using scenarios::forceSensingDomain;
using scenarios::forceSensingProblem;
using testing::contingentPath;
using testing::runCli;

struct ContingentInstance {
  std::string domain;
  std::string problem;
  std::string hidden;  // "" if none
};

// Every contingent domain/problem pair under data/pddl/contingent.
const std::vector<ContingentInstance>& dataInstances() {
  static const std::vector<ContingentInstance> instances = {
      {"blocks/domain.pddl", "blocks/p3.pddl", ""},
      {"colorballs/d.pddl", "colorballs/p.pddl", "colorballs/hidden.pddl"},
      {"doors/d.pddl", "doors/p.pddl", "doors/hidden.pddl"},
      {"doors-po-prp/domain.pddl", "doors-po-prp/n05.pddl", ""},
      {"doors-po-prp/domain-clg.pddl", "doors-po-prp/n05-clg.pddl", ""},
      {"ebtcs/d.pddl", "ebtcs/p.pddl", "ebtcs/hidden.pddl"},
      {"medpks/d.pddl", "medpks/p.pddl", ""},
      {"medpks-contff/d10.pddl", "medpks-contff/p10.pddl", ""},
      {"medpks-up-cpor/d.pddl", "medpks-up-cpor/p.pddl", ""},
      {"omelette/domain.pddl", "omelette/problem.pddl", ""},
      {"omelette/domain.pddl", "omelette/problem-one-bowl.pddl", ""},
      {"unix/d.pddl", "unix/p.pddl", "unix/hidden.pddl"},
      {"wumpus/d.pddl", "wumpus/p.pddl", "wumpus/hidden.pddl"},
      {"scenarios/bartender-domain.pddl", "scenarios/bartender-4.pddl", ""},
      {"scenarios/bimanual-assembly-domain.pddl", "scenarios/bimanual-assembly.pddl", ""}};
  return instances;
}

TEST(FactoredKnowledge, InstancesListedAreEveryContingentInstanceOfData) {
  std::size_t problems = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(contingentPath(""))) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("p") || name.starts_with("n0") || name.starts_with("bartender-4") ||
        name == "bimanual-assembly.pddl") {
      ++problems;
    }
  }
  EXPECT_EQ(problems, dataInstances().size());
}

// `plan` (found with `found`) read and checked branch by branch with `checker`.
void expectValid(const KnowledgeTask& found, const ContingentResult& result, KnowledgeTask& checker,
                 const std::string& label) {
  const std::string text = formatPlanTree(found, result.plan);
  const PlanTree parsed = parsePlanTree(text, "plan", checker);
  const TreeValidation validation = validatePlanTree(checker, parsed, "plan");
  EXPECT_TRUE(validation.valid) << label << ": " << validation.message;
}

TEST(FactoredKnowledge, AgreesWithExplicitWorldsOnEveryContingentInstance) {
  const ProcedureRegistry procedures = scenarios::toyGeometryProcedures();
  int factoredInstances = 0;
  for (const ContingentInstance& instance : dataInstances()) {
    SCOPED_TRACE(instance.problem);
    const ContingentProblem contingent =
        loadContingent(contingentPath(instance.domain), contingentPath(instance.problem));
    KnowledgeTask explicitTask(contingent, procedures, std::size_t{1} << 18,
                               KnowledgeRepresentation::Explicit);
    KnowledgeTask automatic(contingent, procedures);
    if (!automatic.factored()) {
      // Inexact (fluents, effect applicators, numeric tests) or a single component: explicit.
      EXPECT_EQ(automatic.initialBelief(), explicitTask.initialBelief());
      continue;
    }
    ++factoredInstances;
    EXPECT_EQ(automatic.possibleWorlds(automatic.initialBelief()),
              explicitTask.possibleWorlds(explicitTask.initialBelief()));
    const ContingentResult explicitResult = solveContingent(explicitTask, {});
    const ContingentResult factoredResult = solveContingent(automatic, {});
    ASSERT_EQ(explicitResult.status, factoredResult.status);
    if (factoredResult.status != PlannerStatus::Solved) continue;
    // Each representation accepts the other's plan: they agree on every branch's knowledge.
    expectValid(automatic, factoredResult, automatic, "factored plan, factored check");
    expectValid(automatic, factoredResult, explicitTask, "factored plan, explicit check");
    expectValid(explicitTask, explicitResult, automatic, "explicit plan, factored check");
    if (instance.hidden.empty()) continue;
    const std::string hiddenFile = contingentPath(instance.hidden);
    const PlanTree plan =
        parsePlanTree(formatPlanTree(automatic, factoredResult.plan), "plan", automatic);
    for (const HiddenState& state : parseHidden(readTextFile(hiddenFile), hiddenFile, contingent)) {
      const Execution run = executePlanTree(automatic, plan, automatic.hiddenWorld(state, "h"));
      EXPECT_TRUE(run.reachedGoal) << "hidden state line " << state.pos.line << ": " << run.message;
    }
  }
  // colorballs, doors (two encodings of n05 too), omelette, bartender
  EXPECT_GE(factoredInstances, 5);
}

TEST(FactoredKnowledge, IndependentUnknownsAreSeparateComponents) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(20), "fs-20");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ASSERT_TRUE(task.factored());
  EXPECT_EQ(task.componentCount(), 20);
  EXPECT_EQ(task.possibleWorlds(task.initialBelief()), std::ldexp(1.0, 20));
  EXPECT_EQ(task.initialBelief().size(), 21u);  // the core and one local world set each
  // Sensing one container splits only its component.
  Belief grasped;
  ASSERT_TRUE(task.apply(task.findOperator("(grasp o3)"), task.initialBelief(), grasped));
  Belief sensed;
  ASSERT_TRUE(task.apply(task.findOperator("(senseweight o3)"), grasped, sensed));
  const AtomId spillable = task.findAtom("(isspillable o3)");
  ASSERT_EQ(task.pendingObservation(sensed), spillable);
  Belief onTrue;
  Belief onFalse;
  task.split(spillable, sensed, onTrue, onFalse);
  EXPECT_EQ(task.possibleWorlds(onTrue), std::ldexp(1.0, 19));
  EXPECT_TRUE(task.applicable(task.findOperator("(transferupright o3)"), onTrue));
  EXPECT_FALSE(task.applicable(task.findOperator("(transferupright o3)"), onFalse));
  EXPECT_TRUE(task.applicable(task.findOperator("(transferfast o3)"), onFalse));
}

TEST(FactoredKnowledge, SettledComponentsShareSubPlansExactly) {
  // Once a container is removed nothing reads whether it was spillable: the branches join, so
  // the plan is a DAG of a few nodes per container instead of 2^n leaves of distinct nodes.
  const ContingentProblem thirty =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(30), "fs-30");
  KnowledgeTask task(thirty, ProcedureRegistry{});
  const ContingentResult result = testing::solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const TreeMetrics metrics = measure(result.plan);
  EXPECT_EQ(metrics.leaves, std::ldexp(1.0, 30));
  EXPECT_LT(metrics.dagNodes, 400u);
  Belief key;
  task.sharingKey(task.initialBelief(), key);
  EXPECT_EQ(key, task.initialBelief());  // nothing is settled before any container is handled

  // The explicit validator, which shares nothing, accepts the factored plan branch by branch.
  const ContingentProblem eight =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(8), "fs-8");
  KnowledgeTask factored(eight, ProcedureRegistry{});
  KnowledgeTask explicitTask(eight, ProcedureRegistry{}, 1000, KnowledgeRepresentation::Explicit);
  const ContingentResult shared = solveContingent(factored, {});
  ASSERT_EQ(shared.status, PlannerStatus::Solved);
  expectValid(factored, shared, explicitTask, "force sensing 8, explicit check");
}

TEST(FactoredKnowledge, TwentyUnknownRoadsGiveALinearDagThatExecutesInEveryWorld) {
  const ContingentProblem contingent =
      parseContingent(scenarios::unknownRoadsDomain(), "roads-domain",
                      scenarios::unknownRoadsProblem(20), "roads-20");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  EXPECT_EQ(task.componentCount(), 20);
  const ContingentResult result = testing::solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const TreeMetrics metrics = measure(result.plan);
  EXPECT_EQ(metrics.leaves, std::ldexp(1.0, 20));
  EXPECT_LT(metrics.dagNodes, 200u);
  // Every road blocked, every road clear, and alternating: the vehicle arrives each time.
  const PlanTree plan = parsePlanTree(formatPlanTree(task, result.plan), "plan", task);
  for (const int pattern : {0, 1, 2}) {
    std::string clear;
    for (int i = 1; i <= 20; ++i) {
      if (pattern == 1 || (pattern == 2 && i % 2 == 0))
        clear += " (clear r" + std::to_string(i) + ")";
    }
    for (int i = 1; i <= 20; ++i) {
      clear += " (clear a" + std::to_string(i) + ") (clear b" + std::to_string(i) + ")";
    }
    const auto hidden =
        parseHidden("(define (problem h) (:hidden (at l0)" + clear + "))", "h", contingent);
    const Execution run = executePlanTree(task, plan, task.hiddenWorld(hidden[0], "h"));
    EXPECT_TRUE(run.reachedGoal) << "pattern " << pattern << ": " << run.message;
  }
  EXPECT_THROW(scenarios::unknownRoadsProblem(0), InputError);
}

const std::string kCoupledDomain = R"((define (domain coupled)
  (:predicates (a) (b) (c) (done))
  (:action look-a :observe (a))
  (:action look-b :observe (b))
  (:action copy :effect (when (a) (c)))
  (:action finish :precondition (and (c)) :effect (done))))";

KnowledgeTask coupledTask(const ContingentProblem& contingent,
                          KnowledgeRepresentation representation) {
  return KnowledgeTask(contingent, ProcedureRegistry{}, 1000, representation);
}

TEST(FactoredKnowledge, ConditionalEffectsJoinTheComponentsTheyCouple) {
  const ContingentProblem contingent =
      parseContingent(kCoupledDomain, "coupled.pddl",
                      "(define (problem p) (:domain coupled) (:init (unknown (a)) (unknown (b))) "
                      "(:goal (done)))",
                      "p.pddl");
  // c is known false initially, but `copy` makes it depend on a: a and c form one component.
  KnowledgeTask factored = coupledTask(contingent, KnowledgeRepresentation::Factored);
  EXPECT_EQ(factored.componentCount(), 2);
  Belief copied;
  ASSERT_TRUE(factored.apply(factored.findOperator("(copy)"), factored.initialBelief(), copied));
  EXPECT_EQ(factored.possibleWorlds(copied), 4.0);
  EXPECT_FALSE(factored.holds({{factored.findAtom("(c)")}, {}, {}, {}, {}}, copied));
  KnowledgeTask explicitTask = coupledTask(contingent, KnowledgeRepresentation::Explicit);
  const ContingentResult a = solveContingent(factored, {});
  const ContingentResult b = solveContingent(explicitTask, {});
  EXPECT_EQ(a.status, PlannerStatus::Unsolvable);  // c stays false where a is false
  EXPECT_EQ(b.status, PlannerStatus::Unsolvable);
}

// A numeric fluent's value may differ per world: factored knowledge would not be exact.
const std::string kTankDomain = R"((define (domain tank)
  (:requirements :numeric-fluents)
  (:predicates (open) (full))
  (:functions (level))
  (:action look :observe (open))
  (:action fill :precondition (and (open) (< (level) 10))
    :effect (and (full) (increase (level) 1)))))";
const std::string kTankProblem =
    "(define (problem t) (:domain tank) (:init (= (level) 0) (unknown (open)) (unknown (full)))"
    " (:goal (full)))";

TEST(FactoredKnowledge, FactoredIsRefusedWhereItWouldNotBeExact) {
  const ContingentProblem contingent =
      parseContingent(kTankDomain, "tank.pddl", kTankProblem, "tank-1.pddl");
  KnowledgeTask automatic(contingent, ProcedureRegistry{});
  EXPECT_FALSE(automatic.factored());
  try {
    KnowledgeTask task(contingent, ProcedureRegistry{}, 1000, KnowledgeRepresentation::Factored);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tank-1.pddl: factored knowledge is not exact for this "
                                         "problem: the task has fluents"),
              std::string::npos)
        << e.what();
  }
}

// The ⊕ goal of Table 6.1 is one clause per bottle (not a normal form of 3^n disjuncts, which the
// grounder refused from 8 bottles on), each reading one bottle's component; the toy `reaches`
// checker answers alike in every world.
TEST(FactoredKnowledge, BartenderGoalIsCheckedPerBottleComponent) {
  EXPECT_EQ(scenarios::bartenderDomain(),
            readTextFile(contingentPath("scenarios/bartender-domain.pddl")));
  const ProcedureRegistry procedures = scenarios::toyGeometryProcedures();
  const ContingentProblem twenty = parseContingent(scenarios::bartenderDomain(), "bartender-domain",
                                                   scenarios::bartenderProblem(20), "b-20");
  KnowledgeTask large(twenty, procedures);
  ASSERT_TRUE(large.factored());
  EXPECT_EQ(large.componentCount(), 20);
  EXPECT_EQ(large.task().goal.clauses.size(), 20u);
  EXPECT_EQ(large.possibleWorlds(large.initialBelief()), std::ldexp(1.0, 20));

  const ContingentProblem eight = parseContingent(scenarios::bartenderDomain(), "bartender-domain",
                                                  scenarios::bartenderProblem(8), "b-8");
  KnowledgeTask factored(eight, procedures);
  KnowledgeTask explicitTask(eight, procedures, 1000, KnowledgeRepresentation::Explicit);
  ASSERT_TRUE(factored.factored());
  const ContingentResult a = solveContingent(factored, {});
  const ContingentResult b = solveContingent(explicitTask, {});
  ASSERT_EQ(a.status, PlannerStatus::Solved);
  ASSERT_EQ(b.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(a.plan).leaves, 256.0);
  expectValid(factored, a, factored, "bartender 8, factored check");
  expectValid(factored, a, explicitTask, "bartender 8, explicit check");
  expectValid(explicitTask, b, factored, "bartender 8, explicit plan, factored check");
  // Bottles 1 and 4 empty: each goes to the dishwasher, the others stay.
  const auto hidden = parseHidden(
      "(define (problem h) (:hidden (isemptybottle o1) (isemptybottle o4)))", "h", eight);
  const PlanTree plan = parsePlanTree(formatPlanTree(factored, a.plan), "plan", factored);
  const Execution run = executePlanTree(factored, plan, factored.hiddenWorld(hidden[0], "h"));
  EXPECT_TRUE(run.reachedGoal) << run.message;
  EXPECT_NE(std::find(run.steps.begin(), run.steps.end(), "(putdown robot2 o1 dishwasher)"),
            run.steps.end());
  EXPECT_EQ(std::find(run.steps.begin(), run.steps.end(), "(putdown robot2 o2 dishwasher)"),
            run.steps.end());
  EXPECT_THROW(scenarios::bartenderProblem(0), InputError);
}

TEST(FactoredKnowledge, CliChoosesTheRepresentation) {
  const std::string dir =
      std::filesystem::path(testing::writeTempFile("roads.keep", "")).parent_path().string();
  ASSERT_EQ(runCli("unknown-roads 4 --quiet --out-dir " + dir).exitCode, 0);
  const auto roads = runCli("contingent " + dir + "/unknown-roads-domain.pddl " + dir +
                            "/unknown-roads-4.pddl --json");
  EXPECT_EQ(roads.exitCode, 0) << roads.output;
  EXPECT_NE(roads.output.find("\"knowledge\": \"factored\""), std::string::npos) << roads.output;
  EXPECT_NE(roads.output.find("\"components\": 4"), std::string::npos) << roads.output;
  const std::string d = contingentPath("doors/d.pddl");
  const std::string p = contingentPath("doors/p.pddl");
  const auto automatic = runCli("contingent " + d + " " + p + " --plan-out /dev/null");
  EXPECT_EQ(automatic.exitCode, 0) << automatic.output;
  EXPECT_NE(automatic.output.find("343 initial world(s) (3 components)"), std::string::npos)
      << automatic.output;
  const auto forced =
      runCli("contingent " + d + " " + p + " --knowledge explicit --plan-out " + "/dev/null");
  EXPECT_NE(forced.output.find("343 initial world(s) (explicit)"), std::string::npos)
      << forced.output;
  const auto bad = runCli("contingent " + d + " " + p + " --knowledge lazy");
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("--knowledge"), std::string::npos) << bad.output;
  const auto inexact =
      runCli("contingent " + testing::writeTempFile("tank.pddl", kTankDomain) + " " +
             testing::writeTempFile("tank-1.pddl", kTankProblem) + " --knowledge factored");
  EXPECT_EQ(inexact.exitCode, 2) << inexact.output;
  EXPECT_NE(inexact.output.find("tank-1.pddl: factored knowledge is not exact for this "
                                "problem: the task has fluents"),
            std::string::npos)
      << inexact.output;
  ASSERT_EQ(runCli("bartender 3 --quiet --out-dir " + dir).exitCode, 0);
  const auto bartender = runCli("contingent " + dir + "/bartender-domain.pddl " + dir +
                                "/bartender-3.pddl --toy-geometry --json");
  EXPECT_EQ(bartender.exitCode, 0) << bartender.output;
  EXPECT_NE(bartender.output.find("\"components\": 3"), std::string::npos) << bartender.output;
  const auto noBottles = runCli("bartender 0 --quiet --out-dir " + dir);
  EXPECT_EQ(noBottles.exitCode, 2) << noBottles.output;
  EXPECT_NE(noBottles.output.find("n must be at least 1"), std::string::npos) << noBottles.output;
  const auto noLegs = runCli("unknown-roads 0 --quiet --out-dir " + dir);
  EXPECT_EQ(noLegs.exitCode, 2) << noLegs.output;
  EXPECT_NE(noLegs.output.find("n must be at least 1"), std::string::npos) << noLegs.output;
}

}  // namespace
}  // namespace kaboum::symbolic
