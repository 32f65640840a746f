// Planning inputs as published: Contingent-FF's non-deterministic effects `(nondet l)` at the
// knowledge level, in the validator and in executions against hidden states, and the published
// files other planners read despite their inconsistencies (copies in data/pddl/contingent).
#include <gtest/gtest.h>

#include <set>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

using testing::contingentPath;
using testing::errorOf;
using testing::runCli;
using testing::solveAndValidate;
using testing::writeTempFile;

// --- (nondet l): l may or may not take place ------------------------------------------------

const std::string kVaseDomain = R"((define (domain vase)
  (:predicates (intact) (armed) (lit))
  (:action knock :effect (when (armed) (nondet (not (intact)))))
  (:action strike :effect (nondet (lit)))
  (:action admire :precondition (intact) :effect (lit))))";

TEST(NondeterministicEffects, KnowledgeOfTheAtomIsLostWhereTheEffectApplies) {
  const ContingentProblem contingent =
      parseContingent(kVaseDomain, "vase.pddl",
                      "(define (problem p) (:domain vase) (:init (intact) (unknown (armed))) "
                      "(:goal (lit)))",
                      "p.pddl");
  // Explicit worlds, to look at them one by one.
  KnowledgeTask task(contingent, ProcedureRegistry{}, 1000, KnowledgeRepresentation::Explicit);
  ASSERT_EQ(task.initialBelief().size(), 2u);
  const AtomId intact = task.findAtom("(intact)");
  const AtomId armed = task.findAtom("(armed)");
  const int admire = task.findOperator("(admire)");
  EXPECT_TRUE(task.applicable(admire, task.initialBelief()));

  // Armed: the vase may break (two worlds); unarmed: it stays intact. K(intact) is lost.
  Belief knocked;
  ASSERT_TRUE(task.apply(task.findOperator("(knock)"), task.initialBelief(), knocked));
  EXPECT_EQ(knocked.size(), 3u);
  EXPECT_FALSE(task.applicable(admire, knocked));
  for (const std::uint32_t w : knocked) {
    EXPECT_TRUE(task.world(w).atom(armed) || task.world(w).atom(intact));
  }

  // (nondet (lit)) from ¬lit: lit or not; applied again it adds no world.
  Belief struck;
  ASSERT_TRUE(task.apply(task.findOperator("(strike)"), task.initialBelief(), struck));
  EXPECT_EQ(struck.size(), 4u);
  Belief again;
  ASSERT_TRUE(task.apply(task.findOperator("(strike)"), struck, again));
  EXPECT_EQ(again, struck);
  // A world where lit already holds keeps it: the effect only adds lit.
  Belief admired;
  ASSERT_TRUE(task.apply(admire, task.initialBelief(), admired));
  Belief admiredStruck;
  ASSERT_TRUE(task.apply(task.findOperator("(strike)"), admired, admiredStruck));
  EXPECT_EQ(admiredStruck, admired);
}

const std::string kCoinDomain = R"((define (domain coin)
  (:predicates (heads) (tossed) (done))
  (:action toss :precondition (not (tossed)) :effect (and (tossed) (nondet (heads))))
  (:action look :precondition (tossed) :observe (heads))
  (:action cash-in :precondition (and (tossed) (heads)) :effect (done))
  (:action turn :precondition (and (tossed) (not (heads))) :effect (heads))))";

TEST(NondeterministicEffects, PlansSenseTheOutcomeAndNatureChoosesItInExecutions) {
  const ContingentProblem contingent = parseContingent(
      kCoinDomain, "coin.pddl", "(define (problem p) (:domain coin) (:goal (done)))", "p.pddl");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ASSERT_EQ(task.initialBelief().size(), 1u);
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 2.0) << formatPlanTree(task, result.plan);

  const auto hidden = parseHidden("(:hidden)", "h.pddl", contingent);
  const std::uint32_t world = task.hiddenWorld(hidden[0], "h.pddl");
  std::set<std::string> outcomes;
  for (std::uint64_t seed = 0; seed < 16; ++seed) {
    task.seedOutcomes(seed);
    const Execution run = executePlanTree(task, result.plan, world);
    EXPECT_TRUE(run.reachedGoal) << "seed " << seed << ": " << run.message;
    ASSERT_GE(run.steps.size(), 3u);
    outcomes.insert(run.steps[2]);  // toss, look, then the branch taken
    task.seedOutcomes(seed);
    EXPECT_EQ(executePlanTree(task, result.plan, world).steps, run.steps) << "seed " << seed;
  }
  EXPECT_EQ(outcomes, (std::set<std::string>{"branch (heads) -> true", "branch (heads) -> false"}));
}

TEST(NondeterministicEffects, TheValidatorRejectsAPlanThatAssumesAnOutcome) {
  const ContingentProblem contingent = parseContingent(
      kCoinDomain, "coin.pddl", "(define (problem p) (:domain coin) (:goal (done)))", "p.pddl");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const TreeValidation verdict =
      validatePlanTree(task, parsePlanTree("(plan (toss)\n (cash-in))", "t.plan", task), "t.plan");
  EXPECT_FALSE(verdict.valid);
  EXPECT_EQ(verdict.message, "t.plan:2:2: precondition of (cash-in) is not known to hold");
}

TEST(NondeterministicEffects, MalformedOrObservedNondetIsAnError) {
  const std::string problem = "(define (problem p) (:domain d) (:goal (a)))";
  EXPECT_EQ(
      errorOf("(define (domain d) (:predicates (a) (b))\n (:action s :effect (nondet (a) (b))))",
              problem),
      "d.pddl:2:21: 'nondet' takes one literal, e.g. (nondet (not (p ?x)))");
  EXPECT_EQ(
      errorOf("(define (domain d) (:predicates (a) (b))\n (:action s :effect (nondet (and (a)))))",
              problem),
      "d.pddl:2:21: 'nondet' takes one literal, e.g. (nondet (not (p ?x)))");
  const std::string observed = errorOf(
      "(define (domain d) (:predicates (a))\n (:action s :effect (nondet (not (a))) "
      ":observe (a)))",
      problem);
  EXPECT_NE(observed.find("d.pddl:2:"), std::string::npos) << observed;
  EXPECT_NE(observed.find("changes the atom it observes"), std::string::npos) << observed;
}

// The published Omelette domain in the nondet dialect (data/README-pddl.md): breaking an egg in
// may spoil the bowl, and its actions name the problem's object n0.
TEST(NondeterministicEffects, TheOmeletteDomainLoadsSolvesAndValidates) {
  const std::string domain = contingentPath("omelette/domain.pddl");
  const ContingentProblem contingent =
      loadContingent(domain, contingentPath("omelette/problem.pddl"));
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const std::string text = formatPlanTree(task, result.plan);
  EXPECT_EQ(measure(result.plan).actions, 9.0) << text;
  // Every egg is broken into bowl1 and poured over: bowl2 is never at risk.
  EXPECT_EQ(text.find("(break-in bowl2"), std::string::npos) << text;

  // One bowl: once an egg is in, nothing tells whether it is unspoiled.
  const ContingentProblem oneBowl =
      loadContingent(domain, contingentPath("omelette/problem-one-bowl.pddl"));
  KnowledgeTask oneBowlTask(oneBowl, ProcedureRegistry{});
  EXPECT_EQ(solveContingent(oneBowlTask, {}).status, PlannerStatus::Unsolvable);

  // The classical parser names the construct it does not plan with.
  try {
    loadDomain(domain);
    ADD_FAILURE() << "nondet read by the classical parser";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("domain.pddl:25:17: 'nondet'"), std::string::npos)
        << e.what();
  }
}

// --- published files with inconsistencies other planners read ----------------------------

TEST(PublishedInputs, ContingentFfMedpksNamesProblemObjectsInItsActions) {
  const ContingentProblem contingent = loadContingent(contingentPath("medpks-contff/d10.pddl"),
                                                      contingentPath("medpks-contff/p10.pddl"));
  EXPECT_EQ(contingent.domain.undeclaredConstants.size(), 21u);  // i0 … i10, s1 … s10
  EXPECT_TRUE(contingent.problem.warnings.empty());
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 10.0);
}

TEST(PublishedInputs, UpCporMedpksTypesItsConstantsWithUndeclaredTypes) {
  const std::string domain = contingentPath("medpks-up-cpor/d.pddl");
  const ContingentProblem contingent =
      loadContingent(domain, contingentPath("medpks-up-cpor/p.pddl"));
  EXPECT_EQ(contingent.domain.warnings,
            (std::vector<std::string>{
                domain + ":3:50: type 'illness' is not declared in :types; read as a subtype of "
                         "object",
                domain + ":4:37: type 'stain' is not declared in :types; read as a subtype of "
                         "object"}));
  KnowledgeTask task(contingent, ProcedureRegistry{});
  EXPECT_EQ(solveAndValidate(task).status, PlannerStatus::Solved);
}

TEST(PublishedInputs, PoPrpDoorsProblemNamesAnotherDomain) {
  const std::string domain = contingentPath("doors-po-prp/domain-clg.pddl");
  const std::string problem = contingentPath("doors-po-prp/n05-clg.pddl");
  const ContingentProblem contingent = loadContingent(domain, problem);
  EXPECT_EQ(
      contingent.problem.warnings,
      std::vector<std::string>{problem + ":2:14: problem names domain 'colored-balls' but " +
                               domain + " defines domain 'doors'; reading it with that domain"});
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 25.0);  // 5 × 5 door positions

  // The CLI reads it too, with the warning as one line on stderr.
  const testing::CommandResult cli = runCli("contingent " + domain + " " + problem + " --quiet");
  EXPECT_EQ(cli.exitCode, 0) << cli.output;
  EXPECT_NE(cli.output.find("kaboum: warning: " + problem +
                            ":2:14: problem names domain 'colored-balls'"),
            std::string::npos)
      << cli.output;
}

// PO-PRP's own doors files: a `(:sensor …)` is a sensing action, `(invariant …)` in :init a
// `oneof` (the CLG version beside it, n05-clg.pddl, writes the same instance so).
TEST(PublishedInputs, PoPrpSensorsAreSensingActionsAndInvariantsOneOfs) {
  const std::string domain = contingentPath("doors-po-prp/domain.pddl");
  const std::string problem = contingentPath("doors-po-prp/n05.pddl");
  const ContingentProblem contingent = loadContingent(domain, problem);
  EXPECT_EQ(contingent.problem.warnings.size(), 1u);  // it names domain colored-balls too
  ASSERT_EQ(contingent.constraints.size(), 2u);
  for (const KnowledgeConstraint& constraint : contingent.constraints) {
    EXPECT_EQ(constraint.kind, KnowledgeConstraint::Kind::OneOf);
    EXPECT_EQ(constraint.literals.size(), 5u);
  }
  KnowledgeTask task(contingent, ProcedureRegistry{});
  EXPECT_EQ(task.possibleWorlds(task.initialBelief()), 25.0);
  EXPECT_GE(task.findOperator("(door-obs p1 p2 p3)"), 0);
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 25.0);
  const auto hidden = parseHidden(readTextFile(problem), problem, contingent);
  ASSERT_EQ(hidden.size(), 5u);
  for (const HiddenState& state : hidden) {
    const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(state, problem));
    EXPECT_TRUE(run.reachedGoal) << "line " << state.pos.line << ": " << run.message;
  }
}

TEST(PublishedInputs, ContingentValidateSeedsNaturesChoices) {
  const std::string domain = writeTempFile("coin-domain.pddl", kCoinDomain);
  const std::string problem =
      writeTempFile("coin-problem.pddl", "(define (problem p) (:domain coin) (:goal (done)))");
  const std::string plan = writeTempFile(
      "coin.plan",
      "(plan (toss) (look) (branch (heads) (true (cash-in)) (false (turn) (cash-in))))");
  const std::string hidden = writeTempFile("coin-hidden.pddl", "(:hidden)");
  std::set<std::string> steps;
  for (const char* seed : {"0", "1", "2", "3", "4", "5", "6", "7"}) {
    const testing::CommandResult cli =
        runCli("contingent-validate " + domain + " " + problem + " " + plan + " --hidden " +
               hidden + " --seed " + seed);
    EXPECT_EQ(cli.exitCode, 0) << cli.output;
    const std::size_t at = cli.output.find("goal reached after ");
    ASSERT_NE(at, std::string::npos) << cli.output;
    steps.insert(cli.output.substr(at, 28));
  }
  // Heads: toss, look, cash-in; tails: also turn.
  EXPECT_EQ(steps, (std::set<std::string>{"goal reached after 4 step(s)",
                                          "goal reached after 5 step(s)"}));
}

}  // namespace
}  // namespace kaboum::symbolic
