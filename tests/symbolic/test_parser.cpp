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
  expectError("(define (domain s) (:action a :parameters () :precondition (q)))",
              "d.pddl:1:61: undefined predicate 'q'");
  expectError("(define (domain s) (:predicates (p ?x)) (:action a :parameters () :effect (p ?y)))",
              "d.pddl:1:78: undefined variable '?y'");
  expectError("(define (domain s) (:action a :parameters () :precondition [m]))",
              "d.pddl:1:61: undefined module 'm'");
  expectError("(define (domain s) (:action a :parameters () :effect (assign (f) 1)))",
              "d.pddl:1:63: undefined function 'f'");
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
  expectError("(define (problem p) (:domain s))", "p.pddl:1:1: missing ':goal'", kSmallDomain);
  expectError(
      "(define (domain s) (:modules (m effect f)) (:action a :parameters () "
      ":precondition [m]))",
      "d.pddl:1:84: module 'm' is an effect applicator, used as a condition");
  expectError("(define (domain s) (:predicates (p) (p)))", "d.pddl:1:37: duplicate predicate 'p'");
  expectError("(define (problem p) (:domain s) (:objects a b a - block) (:goal (and)))",
              "p.pddl:1:47: duplicate object 'a'", kSmallDomain);
}

TEST(PddlParserErrors, UnsupportedEffectsAndInitialStatementsAreNamed) {
  expectError("(define (domain s) (:predicates (p)) (:action a :effect (nondet (p))))",
              "d.pddl:1:58: 'nondet' (a non-deterministic effect of Contingent-FF's dialect) "
              "needs the knowledge-level planner: kaboum contingent");
  expectError("(define (domain s) (:predicates (p)) (:action a :effect (oneof (p) (not (p)))))",
              "d.pddl:1:58: unsupported: non-deterministic 'oneof' effects");
  expectError("(define (domain s) (:predicates (p)) (:action a :effect (probabilistic 0.5 (p))))",
              "d.pddl:1:58: unsupported: probabilistic effects ('probabilistic')");
  expectError(
      "(define (problem p) (:domain s) (:objects a - block)\n"
      "  (:init (invariant (clear a) (on a a))) (:goal (and)))",
      "p.pddl:2:11: PO-PRP's '(invariant …)' (uncertain initial knowledge) needs the "
      "knowledge-level planner: kaboum contingent",
      kSmallDomain);
}

// --- inconsistencies other planners read (Contingent-FF, CLG, Fast Downward) ----------------

TEST(PddlParser, AProblemNamingAnotherDomainIsReadWithAWarning) {
  const Domain domain = parseDomain(kSmallDomain, "d.pddl");
  const Problem problem =
      parseProblem("(define (problem p) (:domain other) (:objects a - block) (:goal (clear a)))",
                   "p.pddl", domain);
  EXPECT_EQ(problem.warnings,
            std::vector<std::string>{"p.pddl:1:30: problem names domain 'other' but d.pddl "
                                     "defines domain 's'; reading it with that domain"});
  EXPECT_EQ(problem.objectNames, std::vector<std::string>{"a"});
  EXPECT_TRUE(domain.warnings.empty());
}

TEST(PddlParser, UndeclaredTypesAreReadAsSubtypesOfObjectWithAWarning) {
  const Domain domain = parseDomain(
      "(define (domain s) (:constants c - thing) (:predicates (p ?x - thing))\n"
      "  (:functions (f ?x - thing) - number)\n"
      "  (:action a :parameters (?x - thing) :effect (increase (f ?x) (- 3 1))))",
      "d.pddl");
  EXPECT_EQ(domain.warnings, std::vector<std::string>{"d.pddl:1:36: type 'thing' is not declared "
                                                      "in :types; read as a subtype of object"});
  const int thing = domain.findType("thing");
  ASSERT_GE(thing, 0);
  EXPECT_EQ(domain.types[thing].parent, 0);
  EXPECT_EQ(domain.constantTypes, std::vector<int>{thing});
  EXPECT_TRUE(domain.functions[0].isNumeric());  // '- number' is no type
  const Problem problem = parseProblem(
      "(define (problem p) (:domain s) (:objects b e - ball) (:goal (p c)))", "p.pddl", domain);
  EXPECT_EQ(
      problem.warnings,
      std::vector<std::string>{
          "p.pddl:1:49: type 'ball' is not declared by d.pddl; its objects are of type object"});
  EXPECT_EQ(problem.objectTypes, (std::vector<int>{thing, 0, 0}));
}

TEST(PddlParser, DomainSectionsMayComeInAnyOrder) {
  const Domain domain = parseDomain(
      "(define (domain s) (:constants c - block) (:predicates (p ?x - block)) (:types block))",
      "d.pddl");
  EXPECT_TRUE(domain.warnings.empty());
  EXPECT_EQ(domain.constantTypes, std::vector<int>{domain.findType("block")});
}

TEST(PddlParser, ActionsMayNameObjectsTheProblemDeclares) {
  const std::string text =
      "(define (domain s) (:types block) (:predicates (p ?x - block))\n"
      "  (:action a :parameters () :effect (p c1)))";
  const Domain domain = parseDomain(text, "d.pddl");
  ASSERT_EQ(domain.undeclaredConstants.size(), 1u);
  const Problem problem = parseProblem(
      "(define (problem p) (:domain s) (:objects b c1 - block) (:goal (p c1)))", "p.pddl", domain);
  EXPECT_EQ(problem.objectNames, (std::vector<std::string>{"c1", "b"}));
  EXPECT_EQ(problem.objectTypes, (std::vector<int>{1, 1}));  // c1 takes the problem's type
  EXPECT_TRUE(problem.warnings.empty());
  expectError("(define (problem p) (:domain s) (:objects b - block) (:goal (p b)))",
              "d.pddl:2:40: undefined constant or object 'c1': neither a domain constant nor an "
              "object of p.pddl",
              text);
}

TEST(PddlParser, ProblemsMayDeclareDomainConstantsAgain) {
  const std::string text =
      "(define (domain s) (:types place thing - object room - place) (:constants home - place)\n"
      "  (:predicates (at ?x - place)))";
  const Domain domain = parseDomain(text, "d.pddl");
  const auto typesOf = [&](const std::string& objects) {
    return parseProblem("(define (problem p) (:domain s) (:objects " + objects + ") (:goal (and)))",
                        "p.pddl", domain)
        .objectTypes;
  };
  const int place = domain.findType("place");
  const int room = domain.findType("room");
  EXPECT_EQ(typesOf("home - place a - room"), (std::vector<int>{place, room}));
  EXPECT_EQ(typesOf("home"), std::vector<int>{place});        // object: it stays a place
  EXPECT_EQ(typesOf("home - room"), std::vector<int>{room});  // the narrower type
  expectError("(define (problem p) (:domain s) (:objects home - thing) (:goal (and)))",
              "p.pddl:1:43: object 'home' of type 'thing' is a domain constant of the unrelated "
              "type 'place'",
              text);
}

// --- lexical rules: Fast Downward's translator (lisp_parser.tokenize) --------------------------

// The top-level expressions of `text` rendered back to PDDL, one space apart.
std::string reread(const std::string& text) {
  std::string out;
  for (const SExpr& expr : readSExprs(text, "t.pddl"))
    out += (out.empty() ? "" : " ") + toString(expr);
  return out;
}

std::string lexError(const std::string& text) {
  try {
    readSExprs(text, "t.pddl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PddlLexer, AQuestionMarkStartsAVariableEvenGluedToAName) {
  EXPECT_EQ(reread("(and (aircraft?a) (city ?c))"), "(and (aircraft ?a) (city ?c))");
  EXPECT_EQ(reread("(p ?a?b)"), "(p ?a ?b)");
  const SExpr atom = readSExprs("(aircraft?a)", "t.pddl")[0];
  EXPECT_EQ(atom.items[1].pos.column, 10);  // the variable keeps its own position
}

TEST(PddlLexer, ParenthesesEndNames) {
  EXPECT_EQ(reread("(and(at ?x)(clear ?y))"), "(and (at ?x) (clear ?y))");
  EXPECT_EQ(reread("(p a)(q b)"), "(p a) (q b)");
}

TEST(PddlLexer, CommentsRunToTheEndOfTheLineAndMayHoldAnything) {
  EXPECT_EQ(reread("(p ; caf\xC3\xA9 (unbalanced\n a)"), "(p a)");
  EXPECT_EQ(reread("(p a;glued comment\n)"), "(p a)");
  EXPECT_EQ(reread("(p ; old Mac line end\r a)"), "(p a)");
  EXPECT_EQ(reread("(p a) ; no final line end"), "(p a)");
}

TEST(PddlLexer, LinesEndAtNewlineCarriageReturnOrBoth) {
  const SExpr list = readSExprs("(p\ra\r\nb\nc)", "t.pddl")[0];
  EXPECT_EQ(list.items[1].pos.line, 2);
  EXPECT_EQ(list.items[2].pos.line, 3);
  EXPECT_EQ(list.items[3].pos.line, 4);
  EXPECT_EQ(list.items[3].pos.column, 1);
}

TEST(PddlLexer, NamesAreCaseInsensitiveButKeepTheirSpelling) {
  EXPECT_EQ(reread("(DEFINE (Domain BW))"), "(define (domain bw))");
  EXPECT_EQ(readSExprs("(Pick-Up)", "t.pddl")[0].items[0].original, "Pick-Up");
}

TEST(PddlLexer, NamesHoldHyphensDigitsAndPunctuation) {
  EXPECT_EQ(reread("(on-table ?x-1 - block_2 :effect x.y 2.5 -3 1e3)"),
            "(on-table ?x-1 - block_2 :effect x.y 2.5 -3 1e3)");
  EXPECT_EQ(readSExprs("(?x - t)", "t.pddl")[0].items.size(), 3u);  // a lone '-' is a token
}

TEST(PddlLexer, WhitespaceIsAnyAsciiSpaceIncludingSeparators) {
  EXPECT_EQ(reread("(p\ta\fb\vc\x1c"
                   "d\x1f"
                   "e)"),
            "(p a b c d e)");
  EXPECT_EQ(reread("\xEF\xBB\xBF(p a)"), "(p a)");  // a UTF-8 byte order mark is skipped
}

TEST(PddlLexer, NonAsciiOrControlCharactersOutsideCommentsAreErrors) {
  EXPECT_EQ(lexError("(p caf\xC3\xA9)"), "t.pddl:1:7: non-ASCII character outside a comment");
  EXPECT_EQ(lexError("(p\n a\x01)"), "t.pddl:2:3: unexpected control character in name");
}

TEST(PddlParser, ReadsZenotravelWhoseDomainGluesAVariableToAName) {
  const Domain domain = loadDomain(pddlPath("zenotravel/domain.pddl"));
  const Action& refuel = domain.actions[domain.findAction("refuel")];
  const Formula& aircraft = refuel.precondition.children[0];
  EXPECT_EQ(domain.predicates[aircraft.symbol].name, "aircraft");
  ASSERT_EQ(aircraft.args.size(), 1u);
  EXPECT_EQ(aircraft.args[0].kind, Term::Kind::Variable);
  const Problem problem = loadProblem(pddlPath("zenotravel/p01.pddl"), domain);
  const PlanReport report = testing::planAndValidate(domain, problem, SearchOptions{});
  EXPECT_EQ(report.search.status, PlannerStatus::Solved);
}

TEST(PddlParserErrors, DeepNestingIsRejectedNotACrash) {
  const std::string deep(100000, '(');
  EXPECT_THROW(parseDomain(deep, "deep.pddl"), InputError);
}

}  // namespace
}  // namespace kaboum::symbolic
