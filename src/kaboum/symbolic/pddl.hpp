// Lifted PDDL domain and problem (thesis §3.1 and §6.1.2; seed 004 §II for PDDL/M modules), as
// produced by the parser and consumed by the grounder and the validator. Names are resolved to
// indices; quantified and action variables live in numbered slots of the action's binding.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "kaboum/symbolic/sexpr.hpp"

namespace kaboum::symbolic {

using ObjectId = std::int32_t;
inline constexpr int kNumberType = -1;  // result type of numeric functions

struct Type {
  std::string name;
  int parent = -1;  // -1 only for the root type "object"
};

// A term: a variable slot, an object (constant or problem object), or an object-valued or numeric
// function applied to terms.
struct Term {
  enum class Kind { Variable, Object, Function };
  Kind kind = Kind::Object;
  int index = 0;  // slot, object id or function id
  std::vector<Term> args;
};

// Numeric expression over numbers and fluents: + - * / and unary minus.
struct NumExpr {
  enum class Kind { Number, Fluent, Add, Sub, Mul, Div, Neg };
  Kind kind = Kind::Number;
  double value = 0.0;
  Term fluent;  // Kind::Fluent: a Term of kind Function
  std::vector<NumExpr> args;
};

enum class Comparison { Less, LessEqual, Equal, GreaterEqual, Greater };

// Whether `lhs comparison rhs` holds.
inline bool comparisonHolds(Comparison comparison, double lhs, double rhs) {
  switch (comparison) {
    case Comparison::Less:
      return lhs < rhs;
    case Comparison::LessEqual:
      return lhs <= rhs;
    case Comparison::Equal:
      return lhs == rhs;
    case Comparison::GreaterEqual:
      return lhs >= rhs;
    case Comparison::Greater:
      return lhs > rhs;
  }
  return false;
}

struct Formula {
  enum class Kind {
    True,
    False,
    Atom,     // predicate(args)
    Equal,    // args[0] = args[1] (objects, variables or object-valued function terms)
    Compare,  // numeric comparison of numbers[0] and numbers[1]
    Module,   // condition-checker call [module args]
    Not,
    And,
    Or,
    Imply,
    Exists,
    Forall
  };
  Kind kind = Kind::True;
  int symbol = 0;  // predicate or module id
  std::vector<Term> args;
  Comparison comparison = Comparison::Equal;
  std::vector<NumExpr> numbers;
  std::vector<Formula> children;
  std::vector<int> slots;  // quantified variable slots (Exists/Forall)
  SourcePos pos;
};

struct Effect {
  enum class Kind {
    And,
    Add,     // predicate(args)
    Delete,  // not predicate(args)
    Forall,
    When,       // children[0] under condition
    Assign,     // target := object term (object fluent) or number (numeric fluent)
    Increase,   // numeric target += value
    Decrease,   // numeric target -= value
    ScaleUp,    // numeric target *= value
    ScaleDown,  // numeric target /= value
    Module      // effect-applicator call [module args]
  };
  Kind kind = Kind::And;
  int symbol = 0;          // predicate or module id
  std::vector<Term> args;  // Add/Delete/Module arguments
  Term target;             // assigned function term
  Term objectValue;        // Assign to an object fluent
  NumExpr numberValue;     // Assign/Increase/... to a numeric fluent
  Formula condition;       // When
  std::vector<int> slots;  // Forall
  std::vector<Effect> children;
  SourcePos pos;
};

struct Predicate {
  std::string name;
  std::vector<int> paramTypes;
};

struct Function {
  std::string name;
  std::vector<int> paramTypes;
  int resultType = kNumberType;  // kNumberType or an object type
  bool isNumeric() const { return resultType == kNumberType; }
};

// A PDDL/M module (semantic attachment). Condition checkers test a condition; effect applicators
// return new values for the fluents listed in `writes`. `reads` are the fluents whose values the
// procedure receives; together with the arguments they form the memoization key.
struct Module {
  enum class Kind { ConditionChecker, EffectApplicator };
  std::string name;
  std::vector<int> paramTypes;
  Kind kind = Kind::ConditionChecker;
  std::vector<Term> writes;  // function terms over the module's parameter slots
  std::vector<Term> reads;
  std::string procedure;  // symbol or registered name
  std::string library;    // shared library ("" when registered in code)
  SourcePos pos;
};

struct Action {
  std::string name;
  std::vector<std::string> paramNames;
  int parameterCount = 0;
  std::vector<int> slotTypes;  // one per slot: parameters first, then quantified variables
  std::vector<std::string> slotNames;
  Formula precondition;
  Effect effect;
};

struct Domain {
  std::string file;
  std::string name;
  std::vector<std::string> requirements;
  std::vector<Type> types;  // types[0] is "object"
  std::vector<std::string> constantNames;
  std::vector<int> constantTypes;
  std::vector<Predicate> predicates;
  std::vector<Function> functions;
  std::vector<Module> modules;
  std::vector<Action> actions;
  // Names actions use that :constants does not declare, and where each is first used: constants
  // of type object that the problem must declare as objects (as Contingent-FF reads them).
  struct UndeclaredConstant {
    int constant = 0;
    SourcePos pos;
  };
  std::vector<UndeclaredConstant> undeclaredConstants;
  std::vector<std::string> warnings;  // "file:line:col: ..." of inconsistencies read anyway

  int findType(const std::string& wanted) const;
  int findPredicate(const std::string& wanted) const;
  int findFunction(const std::string& wanted) const;
  int findModule(const std::string& wanted) const;
  int findAction(const std::string& wanted) const;
  bool isSubtype(int type, int ancestor) const;
};

struct GroundAtom {
  int predicate = 0;
  std::vector<ObjectId> args;
};

// Initial value of a function term: an object id (object fluents) or a number.
struct InitialFluent {
  int function = 0;
  std::vector<ObjectId> args;
  double value = 0.0;
};

struct Problem {
  std::string file;
  std::string name;
  std::vector<std::string> objectNames;  // domain constants first, then problem objects
  std::vector<int> objectTypes;
  std::vector<GroundAtom> init;
  std::vector<InitialFluent> initFluents;
  Formula goal;
  std::vector<int> goalSlotTypes;  // slots of quantifiers in the goal
  std::vector<std::string> goalSlotNames;
  std::vector<std::string> warnings;  // "file:line:col: ..." of inconsistencies read anyway

  ObjectId findObject(const std::string& wanted) const;
  // Objects of `type` or any of its subtypes, in id order.
  std::vector<ObjectId> objectsOfType(const Domain& domain, int type) const;
};

// Parse PDDL text (`file` names it in errors). Throw InputError "file:line:col: ..." on syntax
// errors, undefined names, arity mismatches and unsupported requirements. What other planners
// read despite an inconsistency (a problem naming another domain, undeclared types) is read and
// reported in `warnings`; docs/formats.md lists both.
Domain parseDomain(std::string_view text, const std::string& file);
Problem parseProblem(std::string_view text, const std::string& file, const Domain& domain);
// Same from already read S-expressions (front ends that rewrite the tree first, e.g. contingent).
Domain parseDomain(const std::vector<SExpr>& top, const std::string& file);
Problem parseProblem(const std::vector<SExpr>& top, const std::string& file, const Domain& domain);
Domain loadDomain(const std::string& path);
Problem loadProblem(const std::string& path, const Domain& domain);

// Renders an object or a ground atom/term as PDDL text, e.g. "(on a b)".
std::string describeAtom(const Domain& domain, const Problem& problem, int predicate,
                         const std::vector<ObjectId>& args);

}  // namespace kaboum::symbolic
