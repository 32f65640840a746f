// The AND–OR search with effect applicators (the integrated planner's geometry, thesis §6.1.2):
// effects are computed only for the actions the search reaches, actions whose effects have only
// failed leave the heuristic's relaxation, and a symbolic transition already tried waits for the
// untried ones, so that geometric variants of one symbolic state are not enumerated first;
// symbolic plans are refined first where no condition reads what the effects compute.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/contingent.hpp"
#include "kaboum/symbolic/heuristic.hpp"

namespace kaboum::symbolic {
namespace {

ContingentProblem parseTexts(const std::string& domain, const std::string& problem) {
  return parseContingent(domain, "d.pddl", problem, "p.pddl");
}

// The search with effect applicators from the start (no symbolic plans refined first), in `mode`.
ContingentOptions integrated(const std::string& mode = "gbfs") {
  ContingentOptions options;
  options.mode = mode;
  options.symbolicFirst = false;
  return options;
}

std::string firstArgument(const AttachmentArgs& args) {
  return args.objects.empty() ? std::string() : std::string(args.name(0));
}

// Effect applicators that count their calls per first argument ("" without one); `fail` always
// fails, the others write the read value plus one (a new opaque state each time, as a geometric
// effect does).
ProcedureRegistry countingProcedures(std::map<std::string, int>& calls) {
  ProcedureRegistry registry;
  registry.addApplicator("step", [&calls](const AttachmentArgs& args, std::span<double> writes) {
    ++calls[firstArgument(args)];
    writes[0] = args.reads[0] + 1;
    return true;
  });
  registry.addApplicator("fail", [&calls](const AttachmentArgs& args, std::span<double>) {
    ++calls[firstArgument(args)];
    return false;
  });
  return registry;
}

TEST(ContingentEffects, EffectsRunOnlyForTheActionsTheSearchReaches) {
  const std::string domain = R"((define (domain chores)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:types chore)
    (:predicates (done ?c - chore))
    (:functions (state))
    (:modules (work ?c - chore (state) effect step :reads ((state))))
    (:action do :parameters (?c - chore) :effect (and (done ?c) [work ?c]))))";
  const std::string problem = R"((define (problem p) (:domain chores)
    (:objects c1 c2 c3 c4 c5 c6 c7 c8 - chore)
    (:init (= (state) 0))
    (:goal (done c5))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  std::map<std::string, int> calls;
  KnowledgeTask task(contingent, countingProcedures(calls));
  const ContingentResult result = solveContingent(task, integrated());
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  // Eight actions are applicable at the start; the heuristic reaches the goal with one of them.
  EXPECT_EQ(calls["c5"], 1);
  EXPECT_EQ(calls.size(), 1u);
}

TEST(ContingentEffects, ActionsWhoseEffectsFailedLeaveTheHeuristic) {
  // `shortcut` reaches the goal at once but its effect always fails; the long way is
  // start, climb, finish. Once the shortcut has failed, the heuristic no longer counts on it, so
  // the detours (`wander`), which look as good as `climb` while the shortcut is believed
  // possible, are never tried.
  const std::string domain = R"((define (domain detour)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:types place)
    (:predicates (started) (high) (goal) (seen ?p - place))
    (:functions (state))
    (:modules (go ?p - place (state) effect step :reads ((state)))
              (roam ?p - place (state) effect roam :reads ((state)))
              (jump ?p - place (state) effect fail :reads ((state))))
    (:action wander :parameters (?p - place) :precondition (started)
      :effect (and (seen ?p) [roam ?p]))
    (:action shortcut :parameters (?p - place) :effect (and (goal) [jump ?p]))
    (:action start :parameters (?p - place) :effect (and (started) [go ?p]))
    (:action climb :parameters (?p - place) :precondition (started)
      :effect (and (high) [go ?p]))
    (:action finish :parameters (?p - place) :precondition (high)
      :effect (and (goal) [go ?p]))))";
  const std::string problem = R"((define (problem p) (:domain detour)
    (:objects home - place)
    (:init (= (state) 0))
    (:goal (goal))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  std::map<std::string, int> calls;
  ProcedureRegistry procedures = countingProcedures(calls);
  int roamed = 0;
  procedures.addApplicator("roam", [&roamed](const AttachmentArgs& args, std::span<double> out) {
    ++roamed;
    out[0] = args.reads[0] + 1;
    return true;
  });
  KnowledgeTask task(contingent, procedures);
  const ContingentResult result = solveContingent(task, integrated());
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_EQ(formatPlanTree(task, result.plan),
            "(plan\n  (start home)\n  (climb home)\n  (finish home))\n");
  EXPECT_EQ(roamed, 0);
}

TEST(ContingentEffects, ATransitionAlreadyTriedWaitsForUntriedOnes) {
  // `fidget` changes only the opaque state, so it leads to a new knowledge state every time;
  // depth-first search, which takes the newest successor first, would fidget for ever.
  const std::string domain = R"((define (domain fidget)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:types hand)
    (:predicates (ready) (goal))
    (:functions (state))
    (:modules (shake ?h - hand (state) effect step :reads ((state))))
    (:action prepare :parameters (?h - hand) :effect (ready))
    (:action finish :parameters (?h - hand) :precondition (ready) :effect (goal))
    (:action fidget :parameters (?h - hand) :effect [shake ?h])))";
  const std::string problem = R"((define (problem p) (:domain fidget)
    (:objects left - hand)
    (:init (= (state) 0))
    (:goal (goal))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  std::map<std::string, int> calls;
  KnowledgeTask task(contingent, countingProcedures(calls));
  ContingentOptions options = integrated("dfs");
  options.limits.expansions = 1000;
  const ContingentResult result = solveContingent(task, options);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_LE(calls["left"], 2);
}

TEST(ContingentEffects, ProgressIsReportedWhileTheSearchRuns) {
  const ContingentProblem contingent =
      parseTexts(R"((define (domain count)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:predicates (goal))
    (:functions (state))
    (:modules (tick (state) effect step :reads ((state)))
              (stop (state) effect fail :reads ((state))))
    (:action tick :effect [tick])
    (:action finish :effect (and (goal) [stop]))))",
                 "(define (problem p) (:domain count) (:init (= (state) 0)) (:goal (goal)))");
  std::map<std::string, int> calls;
  KnowledgeTask task(contingent, countingProcedures(calls));
  ContingentOptions options = integrated();
  options.limits.expansions = 50;
  std::vector<std::size_t> expanded;
  options.progress = [&expanded](const ContingentStatistics& statistics) {
    expanded.push_back(statistics.expanded);
  };
  options.progressPeriod = 0;
  const ContingentResult result = solveContingent(task, options);
  EXPECT_EQ(result.status, PlannerStatus::NodeLimit);
  ASSERT_GE(expanded.size(), 50u);
  EXPECT_TRUE(std::is_sorted(expanded.begin(), expanded.end()));
  EXPECT_EQ(expanded.back(), 50u);  // the last report comes with the node limit
}

TEST(ContingentEffects, TheRelaxationKnowsANegatedAtomNoActionDeletes) {
  // (broken) is unknown and no action changes it: where it holds, the goal's second disjunct
  // (not (broken)) can never hold, so the goal needs `repair`.
  const std::string domain = R"((define (domain lamp)
    (:predicates (broken) (fixed))
    (:action repair :effect (fixed))))";
  const std::string problem = R"((define (problem p) (:domain lamp)
    (:init (unknown (broken)))
    (:goal (or (fixed) (not (broken))))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  KnowledgeTask task(contingent, ProcedureRegistry{});
  const AtomId broken = task.findAtom("(broken)");
  ASSERT_GE(broken, 0);
  ASSERT_EQ(task.initialBelief().size(), 2u);
  const std::unique_ptr<Heuristic> ff = makeHeuristic("ff", task.task());
  for (const std::uint32_t w : task.initialBelief()) {
    EXPECT_EQ(ff->evaluate(task.world(w), nullptr), task.world(w).atom(broken) ? 1 : 0);
  }
}

TEST(ContingentEffects, SeveralGeometricSamplesPerCallFindWhatTheFirstMisses) {
  // `put` may run once; only its third sample (sample 2) leaves a state that `finish` accepts.
  // With one sample per call the search is exhausted; with three it finds the plan, which names
  // the sample, reads back, validates and executes.
  const std::string domain = R"((define (domain samples)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:types item)
    (:predicates (placed) (goal))
    (:functions (state))
    (:modules (drop ?i - item (state) effect drop :reads ((state)))
              (good ?i - item conditionchecker good :reads ((state))))
    (:action put :parameters (?i - item) :precondition (not (placed))
      :effect (and (placed) [drop ?i]))
    (:action finish :parameters (?i - item) :precondition (and (placed) [good ?i])
      :effect (goal))))";
  const std::string problem = R"((define (problem p) (:domain samples)
    (:objects cup - item)
    (:init (= (state) 0))
    (:goal (goal))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  std::vector<std::uint32_t> drawn;
  ProcedureRegistry procedures;
  procedures.addApplicator("drop", [&drawn](const AttachmentArgs& args, std::span<double> out) {
    drawn.push_back(args.sample);
    out[0] = 10 + args.sample;
    return true;
  });
  procedures.addChecker("good", [](const AttachmentArgs& args) { return args.reads[0] == 12; });
  for (const std::string mode : {"bfs", "dfs", "gbfs"}) {
    SCOPED_TRACE(mode);
    {
      KnowledgeTask task(contingent, procedures);
      const ContingentOptions one = integrated(mode);
      EXPECT_EQ(solveContingent(task, one).status, PlannerStatus::Unsolvable);
    }
    drawn.clear();
    KnowledgeTask task(contingent, procedures);
    ContingentOptions three = integrated(mode);
    three.samples = 3;
    const ContingentResult result = solveContingent(task, three);
    ASSERT_EQ(result.status, PlannerStatus::Solved);
    EXPECT_EQ(drawn, (std::vector<std::uint32_t>{0, 1, 2}));  // each sample computed once
    const std::string text = formatPlanTree(task, result.plan);
    EXPECT_EQ(text, "(plan\n  (sample 2 (put cup))\n  (finish cup))\n");
    const PlanTree read = parsePlanTree(text, "plan.txt", task);
    EXPECT_EQ(formatPlanTree(task, read), text);
    EXPECT_TRUE(validatePlanTree(task, read, "plan.txt").valid);
    EXPECT_TRUE(executePlanTree(task, read, task.initialBelief()[0]).reachedGoal);
    const PlanTree first =
        parsePlanTree("(plan (sample 0 (put cup)) (finish cup))", "first.txt", task);
    EXPECT_EQ(validatePlanTree(task, first, "first.txt").message,
              "first.txt:1:28: precondition of (finish cup) is not known to hold");
  }
}

TEST(ContingentEffects, ASymbolicPlanIsRefinedWhereNoConditionReadsTheEffects) {
  // Eight chores, each done by an action with an effect applicator; nothing reads the state it
  // writes. The symbolic plan is found first, and its effects are computed once each.
  const std::string domain = R"((define (domain chores)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:types chore)
    (:predicates (done ?c - chore))
    (:functions (state))
    (:modules (work ?c - chore (state) effect step :reads ((state))))
    (:action do :parameters (?c - chore) :effect (and (done ?c) [work ?c]))))";
  const std::string problem = R"((define (problem p) (:domain chores)
    (:objects c1 c2 c3 c4 - chore)
    (:init (= (state) 0))
    (:goal (and (done c1) (done c2) (done c3) (done c4)))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  for (const std::string mode : {"bfs", "dfs", "gbfs", "astar", "ids"}) {
    SCOPED_TRACE(mode);
    std::map<std::string, int> calls;
    KnowledgeTask task(contingent, countingProcedures(calls));
    ContingentOptions options;
    options.mode = mode;
    const ContingentResult result = solveContingent(task, options);
    ASSERT_EQ(result.status, PlannerStatus::Solved);
    EXPECT_TRUE(result.statistics.refinedSymbolicPlan);
    EXPECT_EQ(result.statistics.refinements, 0u);
    EXPECT_EQ(calls, (std::map<std::string, int>{{"c1", 1}, {"c2", 1}, {"c3", 1}, {"c4", 1}}));
    EXPECT_TRUE(validatePlanTree(task, result.plan, "plan").valid);
  }
}

TEST(ContingentEffects, AFailedRefinementLeavesItsTransitionOutOfTheNextSymbolicPlan) {
  // `direct` reaches the goal in one action but its effect always fails; `start` and `arrive`
  // take two. The first symbolic plan is (direct); its refinement fails, and the next leaves that
  // transition out: (start) (direct), which fails from the new state too; the third goes round.
  const std::string domain = R"((define (domain detour)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:types place)
    (:predicates (halfway) (goal))
    (:functions (state))
    (:modules (go ?p - place (state) effect step :reads ((state)))
              (jump ?p - place (state) effect fail :reads ((state))))
    (:action direct :parameters (?p - place) :effect (and (goal) [jump ?p]))
    (:action start :parameters (?p - place) :effect (and (halfway) [go ?p]))
    (:action arrive :parameters (?p - place) :precondition (halfway)
      :effect (and (goal) [go ?p]))))";
  const std::string problem = R"((define (problem p) (:domain detour)
    (:objects home - place) (:init (= (state) 0)) (:goal (goal))))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  std::map<std::string, int> calls;
  KnowledgeTask task(contingent, countingProcedures(calls));
  ContingentOptions options;
  options.mode = "bfs";
  const ContingentResult result = solveContingent(task, options);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_TRUE(result.statistics.refinedSymbolicPlan);
  EXPECT_EQ(result.statistics.refinements, 2u);
  EXPECT_EQ(result.statistics.refinementFailure,
            "symbolic plan: an attachment reports (direct home) infeasible");
  EXPECT_EQ(formatPlanTree(task, result.plan), "(plan\n  (start home)\n  (arrive home))\n");
}

TEST(ContingentEffects, WhereNoSymbolicPlanRefinesTheSearchWithEffectsTakesOver) {
  // `put` may run once and only its third sample satisfies `finish`: no symbolic plan refines
  // (sample 0 only), the search with effect applicators and three samples per call finds one.
  // A condition checker reads the state here, so symbolic plans are not tried at all.
  const std::string domain = R"((define (domain once)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:predicates (placed) (goal))
    (:functions (state))
    (:modules (drop (state) effect drop :reads ((state)))
              (good conditionchecker good :reads ((state))))
    (:action put :precondition (not (placed)) :effect (and (placed) [drop]))
    (:action finish :precondition (and (placed) [good]) :effect (goal))))";
  const std::string problem =
      "(define (problem p) (:domain once) (:init (= (state) 0)) (:goal (goal)))";
  const ContingentProblem contingent = parseTexts(domain, problem);
  ProcedureRegistry procedures;
  procedures.addApplicator("drop", [](const AttachmentArgs& args, std::span<double> out) {
    out[0] = 10 + args.sample;
    return true;
  });
  procedures.addChecker("good", [](const AttachmentArgs& args) { return args.reads[0] == 12; });
  KnowledgeTask task(contingent, procedures);
  ContingentOptions options;
  options.samples = 3;
  const ContingentResult result = solveContingent(task, options);
  ASSERT_EQ(result.status, PlannerStatus::Solved);
  EXPECT_FALSE(result.statistics.refinedSymbolicPlan);
  EXPECT_FALSE(result.statistics.refinementFailed);
  EXPECT_EQ(result.statistics.refinements, 0u);

  // Without the checker, and with an effect that always fails, the one symbolic plan (put)
  // (finish) does not refine, no other exists, and the search with effects finds none either.
  const std::string unchecked = R"((define (domain once)
    (:requirements :strips :typing :numeric-fluents :semantic-attachments)
    (:predicates (placed) (goal))
    (:functions (state))
    (:modules (drop (state) effect fail :reads ((state))))
    (:action put :precondition (not (placed)) :effect (and (placed) [drop]))
    (:action finish :precondition (placed) :effect (goal))))";
  std::map<std::string, int> calls;
  KnowledgeTask failing(parseTexts(unchecked, problem), countingProcedures(calls));
  const ContingentResult none = solveContingent(failing, ContingentOptions{});
  EXPECT_EQ(none.status, PlannerStatus::Unsolvable);
  EXPECT_TRUE(none.statistics.refinementFailed);
  EXPECT_EQ(none.statistics.refinements, 1u);
}

TEST(PlanTreeDepth, PlansLongerThanTheCallStackIsDeepAreValidatedAndMeasured) {
  // Depth-first search may return plans of tens of thousands of actions; validating and measuring
  // them must not recurse once per action.
  const ContingentProblem contingent = parseTexts(
      "(define (domain d) (:predicates (waited) (goal)) (:action wait :effect (waited)) "
      "(:action finish :effect (goal)))",
      "(define (problem p) (:domain d) (:goal (goal)))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  constexpr int kActions = 300000;
  ASSERT_GE(task.findOperator("(wait)"), 0);
  PlanTree plan;
  plan.nodes.resize(kActions + 2);
  for (int i = 0; i <= kActions; ++i) {
    plan.nodes[i].kind = PlanTree::Node::Kind::Action;
    plan.nodes[i].op = task.findOperator(i == kActions ? "(finish)" : "(wait)");
    plan.nodes[i].next = i + 1;
  }
  plan.root = 0;
  const TreeValidation validation = validatePlanTree(task, plan, "plan");
  EXPECT_TRUE(validation.valid) << validation.message;
  EXPECT_EQ(validation.metrics.actions, kActions + 1);
  EXPECT_EQ(validation.metrics.depth, static_cast<std::size_t>(kActions) + 1);
  EXPECT_EQ(validation.metrics.dagNodes, static_cast<std::size_t>(kActions) + 2);

  // A deadline stops the validation before an action once its time is up.
  PlannerLimits none;
  none.seconds = 0;
  const Deadline deadline(none);
  while (deadline.elapsedSeconds() <= 0) {
  }
  const TreeValidation stopped = validatePlanTree(task, plan, "plan", &deadline);
  EXPECT_FALSE(stopped.valid);
  EXPECT_EQ(stopped.stoppedBy, PlannerStatus::TimeLimit);
  EXPECT_EQ(stopped.message, "plan: stopped before (wait): time-limit");
}

TEST(ContingentEffects, APlanNamesItsSamplesAsNumbers) {
  const ContingentProblem contingent =
      parseTexts("(define (domain d) (:predicates (goal)) (:action finish :effect (goal)))",
                 "(define (problem p) (:domain d) (:goal (goal)))");
  KnowledgeTask task(contingent, ProcedureRegistry{});
  for (const std::string sample : {"-1", "two", "1.5", "4294967296"}) {
    try {
      parsePlanTree("(plan (sample " + sample + " (finish)))", "plan.txt", task);
      ADD_FAILURE() << sample;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "plan.txt:1:15: expected a sample number: " + sample);
    }
  }
}

}  // namespace
}  // namespace kaboum::symbolic
