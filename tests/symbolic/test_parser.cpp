// Parser tests: real IPC domains parse, the accepted subset is resolved correctly, and every class
// of bad input gives a one-line file:line:col error.
#include <gtest/gtest.h>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/pddl.hpp"
#include "symbolic_test_support.hpp"

namespace kaboum::symbolic {

using namespace kaboum::testing;

namespace {

using testing::pddlPath;

TEST(PddlParser, ParsesIpcDomainsAndProblems) {
  for (const auto& [domainFile, problemFile, actions] :
       std::vector<std::tuple<std::string, std::string, std::size_t>>{
           {"blocks/domain.pddl", "blocks/probBLOCKS-6-0.pddl", 4},
           {"gripper/domain.pddl", "gripper/prob01.pddl", 3},
           {"logistics00/domain.pddl", "logistics00/probLOGISTICS-4-0.pddl", 6},
           {"depot/domain.pddl", "depot/p01.pddl", 5},
           {"miconic/domain.pddl", "miconic/s3-0.pddl", 4}}) {
    const Domain domain = loadDomain(pddlPath(domainFile));
    EXPECT_EQ(domain.actions.size(), actions) << domainFile;
    const Problem problem = loadProblem(pddlPath(problemFile), domain);
    EXPECT_FALSE(problem.init.empty());
    EXPECT_NE(problem.goal.kind, Formula::Kind::True);
  }
}

TEST(PddlParser, ResolvesTypesConstantsAndQuantifiers) {
  const Domain domain = loadDomain(pddlPath("adl/domain.pddl"));
  const int tool = domain.findType("tool");
  const int item = domain.findType("item");
  ASSERT_GE(tool, 0);
  EXPECT_TRUE(domain.isSubtype(tool, item));
  EXPECT_FALSE(domain.isSubtype(item, tool));
  EXPECT_EQ(domain.constantNames, std::vector<std::string>{"home"});
  const Action& paint = domain.actions[domain.findAction("paint")];
  EXPECT_EQ(paint.parameterCount, 1);
  EXPECT_EQ(paint.slotTypes.size(), 3u);  // ?l, then ?t (exists) and ?i (forall)
  EXPECT_EQ(paint.precondition.children[1].kind, Formula::Kind::Exists);
  EXPECT_EQ(paint.precondition.children[2].kind, Formula::Kind::Forall);
  const Problem problem = loadProblem(pddlPath("adl/problem.pddl"), domain);
  EXPECT_EQ(problem.findObject("home"), 0);                   // constants come first
  EXPECT_EQ(problem.objectsOfType(domain, item).size(), 2u);  // box and the brush (a tool)
}

TEST(PddlParser, ReadsModulesAndObjectFluents) {
  const Domain domain = parseDomain(R"((define (domain m)
    (:requirements :typing :object-fluents :numeric-fluents)
    (:types cell)
    (:functions (below ?c - cell) - cell (x) (y))
    (:modules (free ?c - cell conditionchecker isFree)
              (go ?c - cell (x) (y) effect Go@libGeo.so :reads ((x))))
    (:action a :parameters (?c - cell)
      :precondition (and [free ?c] (= (below ?c) ?c) (< (x) 3))
      :effect (and [go ?c] (assign (below ?c) ?c) (increase (y) (* 2 (x))))))
  )",
                                    "m.pddl");
  ASSERT_EQ(domain.modules.size(), 2u);
  EXPECT_EQ(domain.modules[0].kind, Module::Kind::ConditionChecker);
  EXPECT_EQ(domain.modules[0].procedure, "isFree");
  EXPECT_EQ(domain.modules[1].library, "libGeo.so");  // case preserved
  EXPECT_EQ(domain.modules[1].writes.size(), 2u);
  EXPECT_EQ(domain.modules[1].reads.size(), 1u);
  EXPECT_FALSE(domain.functions[0].isNumeric());
  const Formula& pre = domain.actions[0].precondition;
  EXPECT_EQ(pre.children[0].kind, Formula::Kind::Module);
  EXPECT_EQ(pre.children[1].kind, Formula::Kind::Equal);
  EXPECT_EQ(pre.children[2].kind, Formula::Kind::Compare);
}

// Expects `text` (as a domain, or as a problem for `domainText`) to fail with exactly `message`.
void expectError(const std::string& text, const std::string& message,
                 const std::string& domainText = "") {
  try {
    if (domainText.empty()) {
      parseDomain(text, "d.pddl");
    } else {
      parseProblem(text, "p.pddl", parseDomain(domainText, "d.pddl"));
    }
    ADD_FAILURE() << "no error, expected: " << message;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

const char* kSmallDomain = R"((define (domain s)
  (:types block)
  (:predicates (on ?a ?b - block) (clear ?a - block))
  (:action noop :parameters (?a - block) :precondition (clear ?a) :effect (not (clear ?a)))))";

TEST(PddlParserErrors, Syntax) {
  expectError("(define (domain s)", "d.pddl:1:1: expected ')' to close the list opened here");
  expectError("(define (domain s)))", "d.pddl:1:20: unexpected ')'");
  expectError("(define (domain s) (:predicates (p]))", "d.pddl:1:35: expected ')' but found ']'");
  expectError("(define (problem s))", "d.pddl:1:1: expected '(define (domain NAME) ...)'");
  expectError("(define (domain s) (:action a :parameters (x)))",
              "d.pddl:1:44: expected a variable starting with '?', found 'x'");
  expectError("(define (domain s) (:bogus))", "d.pddl:1:21: unknown domain section ':bogus'");
}

TEST(PddlParserErrors, UndefinedNames) {
  expectError("(define (domain s) (:predicates (p ?x - thing)))",
              "d.pddl:1:41: undefined type 'thing'");
  expectError("(define (domain s) (:action a :parameters () :precondition (q)))",
              "d.pddl:1:61: undefined predicate 'q'");
  expectError("(define (domain s) (:predicates (p ?x)) (:action a :parameters () :effect (p c1)))",
              "d.pddl:1:78: undefined constant or object 'c1'");
  expectError("(define (domain s) (:predicates (p ?x)) (:action a :parameters () :effect (p ?y)))",
              "d.pddl:1:78: undefined variable '?y'");
  expectError("(define (domain s) (:action a :parameters () :precondition [m]))",
              "d.pddl:1:61: undefined module 'm'");
  expectError("(define (domain s) (:action a :parameters () :effect (assign (f) 1)))",
              "d.pddl:1:63: undefined function 'f'");
  expectError("(define (problem p) (:domain s) (:objects b - ball) (:goal (and)))",
              "p.pddl:1:47: undefined type 'ball'", kSmallDomain);
  expectError("(define (problem p) (:domain s) (:objects a - block) (:goal (clear z)))",
              "p.pddl:1:68: undefined constant or object 'z'", kSmallDomain);
  expectError("(define (problem p) (:domain s) (:init (glued a)) (:goal (and)))",
              "p.pddl:1:41: undefined predicate 'glued'", kSmallDomain);
}

TEST(PddlParserErrors, ArityMismatches) {
  expectError(
      "(define (domain s) (:predicates (p ?x)) (:action a :parameters (?x) :precondition (p)))",
      "d.pddl:1:83: predicate 'p' takes 1 argument(s), 0 given");
  expectError("(define (problem p) (:domain s) (:objects a - block) (:init (on a)) (:goal (and)))",
              "p.pddl:1:61: predicate 'on' takes 2 argument(s), 1 given", kSmallDomain);
  expectError(
      "(define (domain s) (:modules (m ?x conditionchecker f)) (:action a :parameters () "
      ":precondition [m]))",
      "d.pddl:1:97: module 'm' takes 1 argument(s), 0 given");
}

TEST(PddlParserErrors, UnsupportedAndInconsistent) {
  expectError("(define (domain s) (:requirements :strips :durative-actions))",
              "d.pddl:1:43: unsupported requirement ':durative-actions'");
  expectError("(define (domain s) (:derived (p) (q)))",
              "d.pddl:1:21: unsupported section ':derived'");
  expectError("(define (problem p) (:domain other) (:goal (and)))",
              "p.pddl:1:30: problem is for domain 'other', not 's'", kSmallDomain);
  expectError("(define (problem p) (:domain s))", "p.pddl:1:1: missing ':goal'", kSmallDomain);
  expectError(
      "(define (domain s) (:modules (m effect f)) (:action a :parameters () "
      ":precondition [m]))",
      "d.pddl:1:84: module 'm' is an effect applicator, used as a condition");
  expectError("(define (domain s) (:predicates (p) (p)))", "d.pddl:1:37: duplicate predicate 'p'");
}

TEST(PddlParserErrors, DeepNestingIsRejectedNotACrash) {
  const std::string deep(100000, '(');
  EXPECT_THROW(parseDomain(deep, "deep.pddl"), InputError);
}

}  // namespace
}  // namespace kaboum::symbolic
