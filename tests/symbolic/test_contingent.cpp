// Knowledge-level contingent planning: PKS queries over knowledge states, the contingent dialect,
// AND–OR search with branched plans, their validator and execution against hidden states.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>

#include "kaboum/core/error.hpp"
#include "kaboum/scenarios/force_sensing.hpp"
#include "kaboum/scenarios/toy_geometry.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::scenarios;
using namespace kaboum::testing;

namespace {

using testing::contingentPath;
using testing::errorOf;
using testing::pddlPath;
using testing::solveAndValidate;

ContingentProblem parseTexts(const std::string& domain, const std::string& problem) {
  return parseContingent(domain, "d.pddl", problem, "p.pddl");
}

// --- knowledge states and primitive queries -------------------------------------------------

const std::string kSwitchDomain = R"((define (domain lamp)
  (:predicates (on) (seen) (done) (broken))
  (:action look :precondition (not (kw (on))) :effect (and (seen) (kw (on))))
  (:action fix :precondition (and (kw (on)) (not (on))) :effect (on))
  (:action finish :precondition (on) :effect (done))))";

TEST(Knowledge, UnknownAtomsAreNeitherKnownTrueNorFalse) {
  const ContingentProblem contingent =
      parseTexts(kSwitchDomain,
                 "(define (problem p) (:domain lamp) (:init (unknown (on))) "
                 "(:goal (done)))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ASSERT_EQ(task.initialBelief().size(), 2u);
  const int look = task.findOperator("(look)");
  const int fix = task.findOperator("(fix)");
  const int finish = task.findOperator("(finish)");
  ASSERT_GE(look, 0);
  ASSERT_GE(fix, 0);
  ASSERT_GE(finish, 0);
  EXPECT_TRUE(task.applicable(look, task.initialBelief()));  // ¬Kw(on)
  EXPECT_FALSE(task.applicable(fix, task.initialBelief()));  // neither Kw(on) nor K(¬on)
  EXPECT_FALSE(task.applicable(finish, task.initialBelief()));
  Belief sensed;
  ASSERT_TRUE(task.apply(look, task.initialBelief(), sensed));
  const AtomId on = task.findAtom("(on)");
  EXPECT_EQ(task.pendingObservation(sensed), on);
  EXPECT_TRUE(task.knowsWhether(on, sensed));
  EXPECT_FALSE(task.applicable(look, sensed));  // Kw(on) now holds
  Belief onTrue;
  Belief onFalse;
  task.split(on, sensed, onTrue, onFalse);
  ASSERT_EQ(onTrue.size(), 1u);
  ASSERT_EQ(onFalse.size(), 1u);
  EXPECT_TRUE(task.applicable(finish, onTrue));
  EXPECT_FALSE(task.applicable(fix, onTrue));
  EXPECT_TRUE(task.applicable(fix, onFalse));
  EXPECT_FALSE(task.applicable(look, onFalse));  // known now: Kw holds without the Kw atom
  EXPECT_EQ(task.pendingObservation(onTrue), -1);
}

TEST(Knowledge, ClassicalProblemIsTheClosedWorldSpecialCase) {
  const ContingentProblem contingent =
      loadContingent(pddlPath("blocks/domain.pddl"), pddlPath("blocks/probBLOCKS-4-0.pddl"));
  KnowledgeTask task(contingent, ProcedureRegistry{});
  EXPECT_EQ(task.initialBelief().size(), 1u);
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const TreeMetrics metrics = measure(result.plan);
  EXPECT_EQ(metrics.leaves, 1.0);
  EXPECT_EQ(metrics.branches, 0.0);
  EXPECT_GE(metrics.actions, 6.0);
}

TEST(Knowledge, OneOfAndOrConstrainTheInitialWorlds) {
  const std::string domain = R"((define (domain d) (:predicates (a) (b) (c) (g))
    (:action s :observe (a)) (:action t :observe (b)) (:action go :precondition (c) :effect (g))))";
  // The same counts whether the worlds are explicit or factored into independent components.
  for (const KnowledgeRepresentation representation :
       {KnowledgeRepresentation::Explicit, KnowledgeRepresentation::Factored}) {
    const auto worlds = [&](const std::string& init) {
      const ContingentProblem contingent =
          parseTexts(domain, "(define (problem p) (:domain d) (:init " + init + ") (:goal (g)))");
      KnowledgeTask task(contingent, ProcedureRegistry{}, 1000, representation);
      return task.possibleWorlds(task.initialBelief());
    };
    EXPECT_EQ(worlds("(c)"), 1.0);
    EXPECT_EQ(worlds("(unknown (a)) (unknown (b))"), 4.0);
    EXPECT_EQ(worlds("(oneof (a) (b))"), 2.0);
    EXPECT_EQ(worlds("(oneof (a) (b) (c))"), 3.0);
    EXPECT_EQ(worlds("(or (a) (b))"), 3.0);
    EXPECT_EQ(worlds("(or (not (a)) (b)) (unknown (a))"), 3.0);
    EXPECT_EQ(worlds("(a) (oneof (a) (b))"), 1.0);  // a known true forces b false
    EXPECT_EQ(worlds("(and (unknown (a)) (oneof (b) (c)))"), 4.0);
  }
}

TEST(Knowledge, ConstantsMayComeBeforeTheirTypes) {
  // As in the medpks benchmark files of 50 and more illnesses.
  const ContingentProblem contingent = parseTexts(
      "(define (domain d) (:constants a - thing) (:types thing) (:predicates (p ?x - thing))"
      " (:action s :parameters (?x - thing) :observe (p ?x))"
      " (:action t :parameters (?x - thing) :precondition (p ?x) :effect (not (p ?x))))",
      "(define (problem q) (:domain d) (:init (unknown (p a))) (:goal (not (p a))))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  EXPECT_EQ(task.initialBelief().size(), 2u);
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 2.0);
}

TEST(Knowledge, KvQueriesOnFunctionValues) {
  const std::string domain = R"((define (domain w) (:types o)
    (:predicates (held ?x - o) (done ?x - o))
    (:functions (weight ?x - o))
    (:action weigh :parameters (?x - o) :precondition (held ?x) :effect (kv (weight ?x)))
    (:action log :parameters (?x - o) :precondition (kv (weight ?x)) :effect (done ?x))))";
  const ContingentProblem contingent =
      parseTexts(domain,
                 "(define (problem p) (:domain w) (:objects a b - o) "
                 "(:init (held a) (= (weight b) 3)) (:goal (and (done a) (done b))))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const int logA = task.findOperator("(log a)");
  const int logB = task.findOperator("(log b)");
  ASSERT_GE(logA, 0);
  ASSERT_GE(logB, 0);
  EXPECT_FALSE(task.applicable(logA, task.initialBelief()));  // weight of a unknown
  EXPECT_TRUE(task.applicable(logB, task.initialBelief()));   // weight of b is known (3)
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const std::string text = formatPlanTree(task, result.plan);
  EXPECT_LT(text.find("(weigh a)"), text.find("(log a)")) << text;
}

// A table known clean becomes unknown after waiting (del(Kf, clean)); it may only be inspected
// while not known clean (¬K(clean)), and served only when known clean.
const std::string kStaleDomain = R"((define (domain stale)
  (:predicates (clean) (waited) (served) (noted))
  (:action wait :precondition (not (waited)) :effect (and (waited) (del kf (clean))))
  (:action inspect :precondition (not (k (clean))) :effect (kw (clean)))
  (:action wipe :precondition (not (clean)) :effect (clean))
  (:action serve :precondition (and (clean) (waited)) :effect (served))
  (:action note :precondition (not (k (not (clean)))) :effect (add kf (noted)))
  (:action unforget :effect (del kf (not (clean))))))";

ContingentProblem staleProblem(const std::string& init, const std::string& goal) {
  return parseTexts(kStaleDomain, "(define (problem p) (:domain stale) (:init " + init +
                                      ") (:goal " + goal + "))");
}

TEST(KnowledgeOperators, NotKnownTrueQuery) {
  const ContingentProblem known = staleProblem("(clean)", "(served)");
  KnowledgeTask knownTask(known, ProcedureRegistry{});
  const int inspect = knownTask.findOperator("(inspect)");
  ASSERT_GE(inspect, 0);
  EXPECT_FALSE(knownTask.applicable(inspect, knownTask.initialBelief()));  // K(clean)

  const ContingentProblem unknown = staleProblem("(unknown (clean))", "(served)");
  KnowledgeTask unknownTask(unknown, ProcedureRegistry{});
  EXPECT_TRUE(
      unknownTask.applicable(unknownTask.findOperator("(inspect)"), unknownTask.initialBelief()));

  const ContingentProblem knownFalse = staleProblem("", "(served)");  // closed world: K(¬clean)
  KnowledgeTask falseTask(knownFalse, ProcedureRegistry{});
  EXPECT_TRUE(falseTask.applicable(falseTask.findOperator("(inspect)"), falseTask.initialBelief()));
  // ¬K(¬clean): false when clean is known false, true when known true or unknown.
  const int notKnownDirty = falseTask.findOperator("(note)");
  ASSERT_GE(notKnownDirty, 0);
  EXPECT_FALSE(falseTask.applicable(notKnownDirty, falseTask.initialBelief()));
  EXPECT_TRUE(knownTask.applicable(knownTask.findOperator("(note)"), knownTask.initialBelief()));
  EXPECT_TRUE(
      unknownTask.applicable(unknownTask.findOperator("(note)"), unknownTask.initialBelief()));
}

TEST(KnowledgeOperators, DeletingFromKfForgetsTheAtom) {
  const ContingentProblem contingent = staleProblem("(clean)", "(served)");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ASSERT_EQ(task.initialBelief().size(), 1u);
  const int wait = task.findOperator("(wait)");
  const int inspect = task.findOperator("(inspect)");
  const int wipe = task.findOperator("(wipe)");
  Belief waited;
  ASSERT_TRUE(task.apply(wait, task.initialBelief(), waited));
  ASSERT_EQ(waited.size(), 2u);  // clean and not clean
  const AtomId clean = task.findAtom("(clean)");
  Belief onTrue;
  Belief onFalse;
  task.split(clean, waited, onTrue, onFalse);
  EXPECT_EQ(onTrue.size(), 1u);
  EXPECT_EQ(onFalse.size(), 1u);
  EXPECT_TRUE(task.applicable(inspect, waited));  // ¬K(clean) now
  EXPECT_FALSE(task.applicable(wipe, waited));    // nor K(¬clean)
  EXPECT_FALSE(task.knowsWhether(clean, waited));

  // del(Kf, clean) leaves known-false knowledge alone; del(Kf, ¬clean) makes it unknown.
  const ContingentProblem dirty = staleProblem("", "(served)");
  KnowledgeTask dirtyTask(dirty, ProcedureRegistry{});
  Belief after;
  ASSERT_TRUE(dirtyTask.apply(dirtyTask.findOperator("(wait)"), dirtyTask.initialBelief(), after));
  EXPECT_EQ(after.size(), 1u);
  Belief unforgotten;
  ASSERT_TRUE(dirtyTask.apply(dirtyTask.findOperator("(unforget)"), after, unforgotten));
  EXPECT_EQ(unforgotten.size(), 2u);
  // Execution: forgetting does not change the true world.
  const std::uint32_t world = task.initialBelief().front();
  const std::uint32_t next = task.applyIn(wait, world);
  EXPECT_TRUE(task.world(next).atom(clean));
}

TEST(KnowledgeOperators, ForgottenAtomIsSensedAgainInTheSolvedPlan) {
  const ContingentProblem contingent = staleProblem("(clean)", "(served)");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const std::string text = formatPlanTree(task, result.plan);
  EXPECT_NE(text.find("(inspect)"), std::string::npos) << text;
  EXPECT_NE(text.find("(wipe)"), std::string::npos) << text;
  EXPECT_EQ(measure(result.plan).leaves, 2.0) << text;

  // A goal may ask for ¬K: "the agent no longer knows the table is clean".
  const ContingentProblem forget = staleProblem("(clean)", "(not (k (clean)))");
  KnowledgeTask forgetTask(forget, ProcedureRegistry{});
  EXPECT_FALSE(forgetTask.isGoal(forgetTask.initialBelief()));
  const ContingentResult forgotten = solveAndValidate(forgetTask);
  ASSERT_EQ(forgotten.status, PlannerStatus::Solved);
  EXPECT_EQ(formatPlanTree(forgetTask, forgotten.plan).find("(wait)") != std::string::npos, true);
}

TEST(KnowledgeOperators, DeletingFromKwRemovesThePendingObservation) {
  const std::string domain = R"((define (domain lamp2)
    (:predicates (on))
    (:action look :effect (add kw (on)))
    (:action unlook :effect (del kw (on)))))";
  const ContingentProblem contingent = parseTexts(
      domain, "(define (problem p) (:domain lamp2) (:init (unknown (on))) (:goal (on)))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const AtomId on = task.findAtom("(on)");
  Belief sensed;
  ASSERT_TRUE(task.apply(task.findOperator("(look)"), task.initialBelief(), sensed));
  EXPECT_EQ(task.pendingObservation(sensed), on);
  Belief unsensed;
  ASSERT_TRUE(task.apply(task.findOperator("(unlook)"), sensed, unsensed));
  EXPECT_EQ(task.pendingObservation(unsensed), -1);
  EXPECT_EQ(unsensed, task.initialBelief());
}

// Filling a box with an unknown content (small, medium or big) makes its weight unknown
// (del(Kv, weight)); weighing senses it (add(Kv, weight)); the shelf depends on the weight.
const std::string kScaleDomain = R"((define (domain scale) (:types box)
  (:predicates (small ?b - box) (medium ?b - box) (big ?b - box) (filled ?b - box)
               (shelved ?b - box))
  (:functions (weight ?b - box))
  (:action fill :parameters (?b - box) :precondition (not (filled ?b))
    :effect (and (filled ?b) (del kv (weight ?b)) (when (small ?b) (assign (weight ?b) 1))
                 (when (medium ?b) (assign (weight ?b) 4)) (when (big ?b) (assign (weight ?b) 9))))
  (:action weigh :parameters (?b - box) :precondition (and (filled ?b) (not (kv (weight ?b))))
    :effect (kv (weight ?b)))
  (:action shelve-low :parameters (?b - box)
    :precondition (and (filled ?b) (kv (weight ?b)) (>= (weight ?b) 5)) :effect (shelved ?b))
  (:action shelve-high :parameters (?b - box)
    :precondition (and (filled ?b) (kv (weight ?b)) (< (weight ?b) 5)) :effect (shelved ?b))))";

const std::string kScaleProblem = R"((define (problem one-box) (:domain scale) (:objects b1 - box)
  (:init (= (weight b1) 0) (oneof (small b1) (medium b1) (big b1)))
  (:goal (shelved b1))))";

TEST(KvSensing, BranchesOncePerPossibleValue) {
  const ContingentProblem contingent = parseTexts(kScaleDomain, kScaleProblem);
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ASSERT_EQ(task.initialBelief().size(), 3u);
  const FluentId weight = task.findFluent("(weight b1)");
  ASSERT_GE(weight, 0);
  EXPECT_TRUE(task.knowsValue(weight, task.initialBelief()));  // 0 in every world
  Belief filled;
  ASSERT_TRUE(task.apply(task.findOperator("(fill b1)"), task.initialBelief(), filled));
  FluentId pending = -1;
  double value = 0.0;
  EXPECT_FALSE(task.knowsValue(weight, filled));
  EXPECT_FALSE(task.pendingValue(filled, pending, value));  // not sensed yet
  Belief weighed;
  ASSERT_TRUE(task.apply(task.findOperator("(weigh b1)"), filled, weighed));
  EXPECT_TRUE(task.knowsValue(weight, weighed));
  ASSERT_TRUE(task.pendingValue(weighed, pending, value));
  EXPECT_EQ(pending, weight);
  Belief equal;
  Belief other;
  task.splitValue(weight, value, weighed, equal, other);
  EXPECT_EQ(equal.size(), 1u);
  EXPECT_EQ(other.size(), 2u);
  EXPECT_FALSE(task.pendingValue(equal, pending, value));  // one value left: known

  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const std::string text = formatPlanTree(task, result.plan);
  const TreeMetrics metrics = measure(result.plan);
  EXPECT_EQ(metrics.leaves, 3.0) << text;  // weights 1, 4 and 9
  EXPECT_EQ(metrics.branches, 2.0) << text;
  EXPECT_NE(text.find("(branch (= (weight b1) "), std::string::npos) << text;
  EXPECT_NE(text.find("(shelve-low b1)"), std::string::npos) << text;
  EXPECT_NE(text.find("(shelve-high b1)"), std::string::npos) << text;
}

TEST(KvSensing, ExecutionFollowsTheSensedValueAndTheValidatorNeedsKv) {
  const ContingentProblem contingent = parseTexts(kScaleDomain, kScaleProblem);
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveContingent(task, {});
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  for (const char* content : {"small", "medium", "big"}) {
    const std::vector<HiddenState> hidden =
        parseHidden(std::string("(:hidden (") + content + " b1))", "h", contingent);
    const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(hidden[0], "h"));
    EXPECT_TRUE(run.reachedGoal) << content << ": " << run.message;
    const bool heavy = std::string(content) == "big";
    EXPECT_EQ(std::count(run.steps.begin(), run.steps.end(), "(shelve-low b1)"), heavy ? 1 : 0)
        << content;
  }
  // Branching on the weight without weighing it first is rejected.
  const std::string unsensed =
      "(plan (fill b1) (branch (= (weight b1) 9) (true (shelve-low b1)) (false (shelve-high "
      "b1))))";
  const TreeValidation validation =
      validatePlanTree(task, parsePlanTree(unsensed, "u.plan", task), "u.plan");
  EXPECT_FALSE(validation.valid);
  EXPECT_NE(validation.message.find("u.plan:1:17: branch on (weight b1), whose value no sensing"),
            std::string::npos)
      << validation.message;
  EXPECT_THROW(parsePlanTree("(plan (branch (= (weight b1) heavy) (true) (false)))", "x", task),
               InputError);
  EXPECT_THROW(parsePlanTree("(plan (branch (= (height b1) 1) (true) (false)))", "x", task),
               InputError);
}

// --- Force Sensing (thesis Table 3.1, Figure 3.2) --------------------------------------------

TEST(ForceSensing, TwoContainersGiveTheBranchedPlanOfFigure32) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(2), "fs-2");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  EXPECT_EQ(task.possibleWorlds(task.initialBelief()), 4.0);
  EXPECT_TRUE(task.factored());  // two independent unknowns
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const TreeMetrics metrics = measure(result.plan);
  EXPECT_EQ(metrics.leaves, 4.0);  // one leaf per spillable/empty combination
  EXPECT_EQ(metrics.branches, 3.0);
  EXPECT_EQ(metrics.depth, 8u);  // grasp, sense, transfer, ungrasp per container
  const std::string text = formatPlanTree(task, result.plan);
  // Every path grasps, weighs, then branches on isSpillable before transferring.
  const auto grasp = text.find("(grasp o");
  const auto sense = text.find("(senseweight o");
  const auto branch = text.find("(branch (isspillable o");
  ASSERT_NE(grasp, std::string::npos) << text;
  EXPECT_LT(grasp, sense);
  EXPECT_LT(sense, branch);
  EXPECT_NE(text.find("(transferupright o"), std::string::npos);
  EXPECT_NE(text.find("(transferfast o"), std::string::npos);
}

TEST(ForceSensing, ExecutionFollowsTheSensedBranch) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(2), "fs-2");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveContingent(task, {});
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  // Figure 3.2: o1 is spillable, o2 is empty.
  const auto hidden =
      parseHidden("(define (problem h) (:hidden (isspillable o1)))", "hidden", contingent);
  const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(hidden[0], "hidden"));
  EXPECT_TRUE(run.reachedGoal) << run.message;
  const auto has = [&](const std::string& step) {
    return std::find(run.steps.begin(), run.steps.end(), step) != run.steps.end();
  };
  EXPECT_TRUE(has("(transferupright o1)"));
  EXPECT_TRUE(has("(transferfast o2)"));
  EXPECT_FALSE(has("(transferfast o1)"));
  EXPECT_TRUE(has("branch (isspillable o1) -> true"));
  EXPECT_TRUE(has("branch (isspillable o2) -> false"));
}

TEST(ForceSensing, ScalesToTenContainers) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(10), "fs-10");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveContingent(task, {});
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  const TreeMetrics metrics = measure(result.plan);
  EXPECT_EQ(metrics.leaves, 1024.0);
  EXPECT_EQ(metrics.depth, 40u);
  EXPECT_TRUE(validatePlanTree(task, result.plan, "plan").valid);
}

TEST(ForceSensing, SearchEndsWithTheStatusOfTheLimitReached) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(8), "fs-8");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ContingentOptions nodes;
  nodes.limits.expansions = 5;
  const ContingentResult limited = solveContingent(task, nodes);
  EXPECT_EQ(limited.status, PlannerStatus::NodeLimit);
  EXPECT_EQ(limited.statistics.expanded, 5u);
  EXPECT_EQ(limited.plan.root, -1);
  ContingentOptions time;
  time.limits.seconds = 1e-9;
  EXPECT_EQ(solveContingent(task, time).status, PlannerStatus::TimeLimit);
  ContingentOptions memory;
  memory.limits.memoryBytes = 1;
  EXPECT_EQ(solveContingent(task, memory).status, PlannerStatus::MemoryLimit);
  const std::atomic<bool> cancel{true};
  ContingentOptions cancelled;
  cancelled.limits.cancel = &cancel;
  EXPECT_EQ(solveContingent(task, cancelled).status, PlannerStatus::Cancelled);
}

// --- Bartender (Table 6.1) and Bimanual Assembly (Tables 6.5/6.6) with toy geometry ---------

TEST(Scenarios, BartenderBranchesOnEveryBottleAndHandsOverThroughTheSharedArea) {
  const ContingentProblem contingent =
      loadContingent(contingentPath("scenarios/bartender-domain.pddl"),
                     contingentPath("scenarios/bartender-4.pddl"));
  KnowledgeTask task(contingent, toyGeometryProcedures());
  EXPECT_EQ(task.possibleWorlds(task.initialBelief()), 16.0);  // factored: a component per bottle
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 16.0);
  // Figure 6.2: o1 and o2 are empty. robot1 cannot reach the dishwasher, so it puts o1 down in
  // the shared area where robot2 picks it up; full bottles o3 and o4 stay out of the dishwasher.
  const auto hidden = parseHidden(
      "(define (problem h) (:hidden (isemptybottle o1) (isemptybottle o2)))", "h", contingent);
  const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(hidden[0], "h"));
  ASSERT_TRUE(run.reachedGoal) << run.message;
  const auto has = [&](const std::string& step) {
    return std::find(run.steps.begin(), run.steps.end(), step) != run.steps.end();
  };
  EXPECT_TRUE(has("(putdown robot1 o1 any)"));
  EXPECT_TRUE(has("(pickup robot2 o1 any)"));
  EXPECT_TRUE(has("(putdown robot2 o1 dishwasher)"));
  EXPECT_TRUE(has("(putdown robot2 o2 dishwasher)"));
  // As in the thesis, the planner senses every bottle first (sensing has no preconditions).
  ASSERT_GE(run.steps.size(), 8u);
  for (std::size_t i = 0; i < 8; i += 2) {
    EXPECT_EQ(run.steps[i].rfind("(senseifempty o", 0), 0u) << run.steps[i];
    EXPECT_EQ(run.steps[i + 1].rfind("branch (isemptybottle o", 0), 0u) << run.steps[i + 1];
  }
}

TEST(Scenarios, BimanualAssemblyBuildsTheGearbox) {
  const ContingentProblem contingent =
      loadContingent(contingentPath("scenarios/bimanual-assembly-domain.pddl"),
                     contingentPath("scenarios/bimanual-assembly.pddl"));
  EXPECT_THROW(KnowledgeTask(contingent, ProcedureRegistry{}), InputError);  // needs `reaches`
  KnowledgeTask task(contingent, toyGeometryProcedures());
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(measure(result.plan).leaves, 1.0);
  const std::string text = formatPlanTree(task, result.plan);
  EXPECT_NE(text.find("(assemblepipebearing robot1 o3 robot2"), std::string::npos) << text;
  EXPECT_NE(text.find("(assemblebearingtree"), std::string::npos) << text;
  EXPECT_NE(text.find("(assemblepipetree robot1 o3 o4)"), std::string::npos) << text;
}

// --- search modes ----------------------------------------------------------------------------

class SearchMode : public ::testing::TestWithParam<const char*> {};

TEST_P(SearchMode, ForceSensingTwoContainersHasFourValidatedLeaves) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(2), "fs-2");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ContingentOptions options;
  options.mode = GetParam();
  const ContingentResult result = solveAndValidate(task, options);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << GetParam();
  EXPECT_EQ(measure(result.plan).leaves, 4.0) << GetParam();
  // Each container needs grasp, senseWeight, a transfer and ungrasp: no path is shorter.
  EXPECT_GE(measure(result.plan).depth, 8u) << GetParam();
}

TEST_P(SearchMode, EbtcsSolvesAndExecutesEveryHiddenState) {
  const ContingentProblem contingent =
      loadContingent(contingentPath("ebtcs/d.pddl"), contingentPath("ebtcs/p.pddl"));
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ContingentOptions options;
  options.mode = GetParam();
  const ContingentResult result = solveAndValidate(task, options);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << GetParam();
  EXPECT_GE(measure(result.plan).leaves, 2.0);
  const std::vector<HiddenState> hidden =
      parseHidden(readTextFile(contingentPath("ebtcs/hidden.pddl")), "hidden", contingent);
  for (const HiddenState& state : hidden) {
    const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(state, "hidden"));
    EXPECT_TRUE(run.reachedGoal) << GetParam() << ": " << run.message;
  }
}

INSTANTIATE_TEST_SUITE_P(Contingent, SearchMode,
                         ::testing::Values("gbfs", "astar", "bfs", "dfs", "ids"));

TEST(SearchModeBadInput, UnknownModeIsAnInputError) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(1), "fs-1");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  ContingentOptions options;
  options.mode = "beam";
  EXPECT_THROW(solveContingent(task, options), InputError);
}

// --- public benchmarks (copies in data/pddl/contingent) --------------------------------------

struct Benchmark {
  const char* name;
  const char* domain;
  const char* problem;
};

class PublicBenchmark : public ::testing::TestWithParam<Benchmark> {};

TEST_P(PublicBenchmark, SolvesAndEveryBranchValidates) {
  const Benchmark& b = GetParam();
  const ContingentProblem contingent =
      loadContingent(contingentPath(std::string(b.name) + "/" + b.domain),
                     contingentPath(std::string(b.name) + "/" + b.problem));
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const ContingentResult result = solveAndValidate(task);
  ASSERT_EQ(result.status, PlannerStatus::Solved) << b.name;
  EXPECT_GE(measure(result.plan).leaves, 2.0) << b.name << ": a contingent plan branches";
}

INSTANTIATE_TEST_SUITE_P(Contingent, PublicBenchmark,
                         ::testing::Values(Benchmark{"medpks", "d.pddl", "p.pddl"},
                                           Benchmark{"ebtcs", "d.pddl", "p.pddl"},
                                           Benchmark{"unix", "d.pddl", "p.pddl"},
                                           Benchmark{"doors", "d.pddl", "p.pddl"},
                                           Benchmark{"blocks", "domain.pddl", "p3.pddl"},
                                           Benchmark{"wumpus", "d.pddl", "p.pddl"},
                                           Benchmark{"colorballs", "d.pddl", "p.pddl"}),
                         [](const auto& param) { return std::string(param.param.name); });

TEST(HiddenExecution, EveryHiddenStateOfTheBenchmarksReachesTheGoal) {
  for (const std::string name : {"ebtcs", "unix", "doors"}) {
    const ContingentProblem contingent =
        loadContingent(contingentPath(name + "/d.pddl"), contingentPath(name + "/p.pddl"));
    KnowledgeTask task(contingent, ProcedureRegistry{});
    const ContingentResult result = solveContingent(task, {});
    ASSERT_EQ(result.status, PlannerStatus::Solved) << name;
    const std::string file = contingentPath(name + "/hidden.pddl");
    const auto hidden = parseHidden(readTextFile(file), file, contingent);
    EXPECT_GE(hidden.size(), 1u);
    for (const HiddenState& state : hidden) {
      const Execution run = executePlanTree(task, result.plan, task.hiddenWorld(state, file));
      EXPECT_TRUE(run.reachedGoal) << name << " line " << state.pos.line << ": " << run.message;
    }
  }
}

// --- validator rejects broken plans ----------------------------------------------------------

TEST(PlanTreeValidator, RejectsPlansThatDoNotBranchOrDoNotReachTheGoal) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(1), "fs-1");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const auto verdict = [&](const std::string& text) {
    return validatePlanTree(task, parsePlanTree(text, "t.plan", task), "t.plan");
  };
  EXPECT_TRUE(verdict("(plan (grasp o1) (senseweight o1) (branch (isspillable o1) "
                      "(true (transferupright o1) (ungrasp o1)) "
                      "(false (transferfast o1) (ungrasp o1))))")
                  .valid);
  // Transferring fast without knowing the container is empty.
  auto bad = verdict("(plan (grasp o1) (senseweight o1) (transferfast o1) (ungrasp o1))");
  EXPECT_FALSE(bad.valid);
  EXPECT_NE(bad.message.find("t.plan:1:"), std::string::npos) << bad.message;
  EXPECT_NE(bad.message.find("precondition of (transferfast o1)"), std::string::npos);
  // Branching without sensing.
  bad = verdict("(plan (grasp o1) (branch (isspillable o1) (true) (false)))");
  EXPECT_FALSE(bad.valid);
  EXPECT_NE(bad.message.find("no sensing action observed"), std::string::npos) << bad.message;
  // One branch stops short of the goal.
  bad = verdict(
      "(plan (grasp o1) (senseweight o1) (branch (isspillable o1) "
      "(true (transferupright o1) (ungrasp o1)) (false (transferfast o1))))");
  EXPECT_FALSE(bad.valid);
  EXPECT_NE(bad.message.find("without knowing the goal"), std::string::npos) << bad.message;
}

const std::string kSenseThenGo = R"((define (domain d) (:predicates (a) (x) (g))
    (:action s :precondition (not (x)) :effect (x) :observe (a))
    (:action go :precondition (x) :effect (g))))";

TEST(PlanTreeValidator, RejectsPlansThatLoop) {
  const ContingentProblem contingent = parseTexts(
      kSenseThenGo, "(define (problem p) (:domain d) (:init (unknown (a))) (:goal (g)))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const PlanTree plan = parsePlanTree(
      "(plan (s) (branch (a)\n (true (label n1) (go) (goto n1)) (false (go))))", "loop.plan", task);
  const TreeValidation validation = validatePlanTree(task, plan, "loop.plan");
  EXPECT_FALSE(validation.valid);
  EXPECT_NE(validation.message.find("loop.plan:2:"), std::string::npos) << validation.message;
  EXPECT_NE(validation.message.find("loops back"), std::string::npos) << validation.message;
}

TEST(PlanTreeValidator, SharedNodesRoundTripThroughLabels) {
  const ContingentProblem contingent = parseTexts(
      kSenseThenGo, "(define (problem p) (:domain d) (:init (unknown (a))) (:goal (g)))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const std::string text = "(plan (s) (branch (a) (true (label n1) (go)) (false (goto n1))))";
  const PlanTree plan = parsePlanTree(text, "t.plan", task);
  // (go) after the branch is one node reached from both sides, validated for each.
  const TreeValidation validation = validatePlanTree(task, plan, "t.plan");
  EXPECT_TRUE(validation.valid) << validation.message;
  EXPECT_EQ(validation.metrics.actions, 3.0);
  EXPECT_EQ(validation.metrics.leaves, 2.0);
}

// --- bad input ------------------------------------------------------------------------------

TEST(ContingentBadInput, SensingActionThatChangesItsObservedAtom) {
  const std::string message =
      errorOf("(define (domain d) (:predicates (a))\n (:action s :effect (not (a)) :observe (a)))",
              "(define (problem p) (:domain d) (:init) (:goal (a)))");
  EXPECT_NE(message.find("d.pddl:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("changes the atom it observes"), std::string::npos) << message;
}

TEST(ContingentBadInput, ContradictoryInitialKnowledge) {
  const std::string domain = "(define (domain d) (:predicates (a) (b)) (:action s :observe (a)))";
  std::string message =
      errorOf(domain, "(define (problem p) (:domain d)\n (:init (a) (not (a))) (:goal (a)))");
  EXPECT_NE(message.find("p.pddl:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("contradictory"), std::string::npos) << message;
  message = errorOf(
      domain, "(define (problem p) (:domain d)\n (:init (a) (b) (oneof (a) (b))) (:goal (a)))");
  EXPECT_NE(message.find("p.pddl:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("no world satisfies"), std::string::npos) << message;
}

TEST(ContingentBadInput, GoalThatCanNeverBecomeKnown) {
  const std::string message =
      errorOf("(define (domain d) (:predicates (a) (b)) (:action s :observe (b)))",
              "(define (problem p) (:domain d) (:init (unknown (a)))\n (:goal (a)))");
  EXPECT_NE(message.find("p.pddl:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("can never become known"), std::string::npos) << message;
}

TEST(ContingentBadInput, MalformedOneOfOrAndUnknown) {
  const std::string domain = "(define (domain d) (:predicates (a) (b)) (:action s :observe (a)))";
  const auto problem = [](const std::string& init) {
    return "(define (problem p) (:domain d)\n (:init " + init + ") (:goal (a)))";
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"(oneof)", "needs at least one atom"},
      {"(oneof (a) (oneof (b)))", "malformed 'oneof'"},
      {"(oneof (a) (and (b)))", "malformed 'oneof'"},
      {"(oneof (a) x)", "expected an atom"},
      {"(oneof (a) (c))", "undefined predicate 'c'"},
      {"(or (a) (a b))", "takes 0 argument(s)"},
      {"(unknown (a) (b))", "'unknown' takes one atom"},
  };
  for (const auto& [init, expected] : cases) {
    const std::string message = errorOf(domain, problem(init));
    EXPECT_NE(message.find("p.pddl:2:"), std::string::npos) << init << " -> " << message;
    EXPECT_NE(message.find(expected), std::string::npos) << init << " -> " << message;
  }
}

TEST(ContingentBadInput, MalformedKnowledgeQueries) {
  const auto domain = [](const std::string& precondition) {
    return "(define (domain d) (:predicates (a)) (:functions (f))\n (:action s :precondition " +
           precondition + " :effect (a)))";
  };
  const std::string problem = "(define (problem p) (:domain d) (:init) (:goal (a)))";
  EXPECT_NE(errorOf(domain("(kw ())"), problem).find("d.pddl:2:"), std::string::npos);
  EXPECT_NE(errorOf(domain("(kw (zz))"), problem).find("undefined predicate 'zz'"),
            std::string::npos);
  EXPECT_NE(errorOf(domain("(kv (g))"), problem).find("undefined function 'g'"), std::string::npos);
  EXPECT_NE(errorOf(domain("(not (k (zz)))"), problem).find("undefined predicate 'zz'"),
            std::string::npos);
  const auto effect = [](const std::string& text) {
    return "(define (domain d) (:predicates (a))\n (:action s :effect " + text + "))";
  };
  EXPECT_NE(errorOf(effect("(del kx (a))"), problem).find("d.pddl:2:26: unknown database 'kx'"),
            std::string::npos);
  EXPECT_NE(errorOf(effect("(del kf (not))"), problem).find("expected an atom"), std::string::npos);
  EXPECT_NE(errorOf(effect("(del kf (zz))"), problem).find("undefined predicate 'zz'"),
            std::string::npos);
  EXPECT_NE(
      errorOf("(define (domain d) (:predicates (a))\n (:action s :observe (not (a))))", problem)
          .find("':observe' takes atoms"),
      std::string::npos);
}

TEST(ContingentBadInput, HiddenStateOutsideTheInitialKnowledge) {
  const ContingentProblem contingent =
      loadContingent(contingentPath("ebtcs/d.pddl"), contingentPath("ebtcs/p.pddl"));
  KnowledgeTask task(contingent, ProcedureRegistry{});
  // oneof: a package in the bomb, but not two.
  const auto hidden =
      parseHidden("(define (problem h)\n (:hidden (in p0 b0) (in p1 b0)))", "h", contingent);
  try {
    task.hiddenWorld(hidden[0], "h");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("h:2:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseHidden("(define (problem h))", "h", contingent), InputError);
}

TEST(ContingentBadInput, TooManyInitialWorldsIsAnError) {
  const ContingentProblem contingent =
      parseContingent(forceSensingDomain(), "fs-domain", forceSensingProblem(12), "fs-12");
  EXPECT_THROW(
      KnowledgeTask(contingent, ProcedureRegistry{}, 1000, KnowledgeRepresentation::Explicit),
      InputError);
  // Factored, the limit is per component: 12 components of 2 worlds each.
  EXPECT_NO_THROW(KnowledgeTask(contingent, ProcedureRegistry{}, 1000));
}

}  // namespace
}  // namespace kaboum::symbolic
