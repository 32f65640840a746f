// Grounder tests: reachability pruning, static simplification, ADL compilation.
#include <gtest/gtest.h>

#include <algorithm>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/planner.hpp"
#include "kaboum/symbolic/task.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

using testing::pddlPath;

bool hasOperator(const GroundTask& task, const std::string& name) {
  return std::any_of(task.operators.begin(), task.operators.end(),
                     [&](const Operator& op) { return op.name == name; });
}

TEST(Grounder, GripperOperatorsMatchTheTypedCount) {
  const Domain domain = loadDomain(pddlPath("gripper/domain.pddl"));
  const Problem problem = loadProblem(pddlPath("gripper/prob01.pddl"), domain);
  const GroundTask task = ground(domain, problem);
  // 2 rooms, 4 balls, 2 grippers: move for each (from, to) pair including from = to (it has
  // effects), pick and drop for each ball x room x gripper.
  EXPECT_EQ(task.operators.size(), 4u + 16u + 16u);
  // Static predicates (room, ball, gripper) are compiled away.
  for (const Operator& op : task.operators) {
    for (const AtomId atom : op.precondition.positive) {
      EXPECT_EQ(task.atomNames[atom].find("(room"), std::string::npos);
    }
  }
}

TEST(Grounder, PrunesUnreachableOperators) {
  const Domain domain = parseDomain(R"((define (domain r)
    (:predicates (at ?x) (road ?x ?y) (gold ?x) (rich))
    (:action go :parameters (?x ?y) :precondition (and (at ?x) (road ?x ?y))
      :effect (and (at ?y) (not (at ?x))))
    (:action take :parameters (?x) :precondition (and (at ?x) (gold ?x)) :effect (rich))))",
                                    "r.pddl");
  const Problem problem = parseProblem(R"((define (problem p) (:domain r)
    (:objects a b c island)
    (:init (at a) (road a b) (road b c) (gold island))
    (:goal (rich))))",
                                       "p.pddl", domain);
  const GroundTask task = ground(domain, problem);
  EXPECT_TRUE(hasOperator(task, "go a b"));
  EXPECT_TRUE(hasOperator(task, "go b c"));
  EXPECT_FALSE(hasOperator(task, "take island"));  // never reachable
  EXPECT_FALSE(task.goal.reachable);               // (rich) is unreachable: unsolvable
}

TEST(Grounder, CompilesAdlFeatures) {
  const Domain domain = loadDomain(pddlPath("adl/domain.pddl"));
  const Problem problem = loadProblem(pddlPath("adl/problem.pddl"), domain);
  const GroundTask task = ground(domain, problem);
  // (or (road a b) (road b a)) is static: exactly one drive a->b operator, no split.
  EXPECT_EQ(std::count_if(task.operators.begin(), task.operators.end(),
                          [](const Operator& op) { return op.name == "drive a b"; }),
            1);
  EXPECT_FALSE(hasOperator(task, "drive home c"));  // no road
  EXPECT_FALSE(hasOperator(task, "drive a a"));     // (not (= ?from ?to))
  // Drive moves carried items with one conditional effect per item.
  for (const Operator& op : task.operators) {
    if (op.name.rfind("drive", 0) == 0) {
      EXPECT_EQ(op.conditional.size(), 2u) << op.name;
    }
  }
  // paint c: the existential over tools becomes a precondition on the brush; the universal
  // requires carrying the box (the only item that can be at c).
  const auto paint = std::find_if(task.operators.begin(), task.operators.end(),
                                  [](const Operator& op) { return op.name == "paint c"; });
  ASSERT_NE(paint, task.operators.end());
  EXPECT_TRUE(task.goal.conjunctive());
}

// A goal ∧_i (φ_i ∨ ψ_i) over 13 objects is 13 clauses of two conditions; its normal form would
// have 2^13 = 8192 disjuncts, beyond the grounder's limit. The heuristic searches reach it.
TEST(Grounder, GoalConjunctsKeepTheirOwnDisjunctions) {
  const Domain domain = parseDomain(R"((define (domain lamps)
    (:predicates (red ?x) (green ?x) (done))
    (:action paint-red :parameters (?x) :effect (red ?x))
    (:action paint-green :parameters (?x) :effect (green ?x))
    (:action finish :parameters () :effect (done))))",
                                    "lamps.pddl");
  std::string objects;
  for (int i = 1; i <= 13; ++i) objects += " l" + std::to_string(i);
  const Problem problem = parseProblem("(define (problem p) (:domain lamps) (:objects" + objects +
                                           ") (:init (red l1)) (:goal (and (done) (forall (?x) "
                                           "(or (red ?x) (green ?x))))))",
                                       "p.pddl", domain);
  const GroundTask task = ground(domain, problem);
  EXPECT_TRUE(task.goal.reachable);
  EXPECT_EQ(task.goal.conjunction.positive.size(), 1u);  // (done)
  EXPECT_EQ(task.goal.clauses.size(), 13u);
  for (const std::string mode : {"gbfs", "astar"}) {
    SearchOptions options;
    options.mode = mode;
    const PlanReport report = plan(domain, problem, {}, options);
    ASSERT_EQ(report.search.status, PlannerStatus::Solved) << mode;
    EXPECT_EQ(report.plan.size(), 13u) << mode;  // finish and one paint per lamp but l1
  }
}

TEST(Grounder, SplitsDisjunctivePreconditions) {
  const Domain domain = parseDomain(R"((define (domain d)
    (:predicates (p) (q) (done))
    (:action a :parameters () :precondition (or (p) (q)) :effect (done))
    (:action spoil :parameters () :precondition (done) :effect (and (not (p)) (not (q))))))",
                                    "d.pddl");
  const Problem problem = parseProblem(
      "(define (problem x) (:domain d) (:init (p) (q)) (:goal (done)))", "x.pddl", domain);
  const GroundTask task = ground(domain, problem);
  EXPECT_EQ(std::count_if(task.operators.begin(), task.operators.end(),
                          [](const Operator& op) { return op.name == "a"; }),
            2);
}

TEST(Grounder, RejectsFormulasWithTooManyDisjuncts) {
  const Domain domain = parseDomain(R"((define (domain d)
    (:predicates (p ?x) (q ?x) (done))
    (:action a :parameters () :precondition (forall (?x) (or (p ?x) (q ?x))) :effect (done))
    (:action spoil :parameters (?x) :precondition (done) :effect (and (not (p ?x)) (not (q ?x))))))",
                                    "d.pddl");
  std::string init;
  std::string objects;
  for (int i = 0; i < 16; ++i) {
    objects += " o" + std::to_string(i);
    init += " (p o" + std::to_string(i) + ") (q o" + std::to_string(i) + ")";
  }
  const Problem problem = parseProblem("(define (problem x) (:domain d) (:objects" + objects +
                                           ") (:init" + init + ") (:goal (done)))",
                                       "x.pddl", domain);
  EXPECT_THROW(ground(domain, problem, 1024), InputError);
}

}  // namespace
}  // namespace kaboum::symbolic
