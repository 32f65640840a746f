// Ground planning task (thesis §3.1, §3.2): atoms, fluents, operators with conjunctive conditions
// (disjunctive preconditions are split into several operators), conditional effects, numeric
// tests and attachment calls. Produced by the grounder, consumed by search, heuristics and output.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "kaboum/symbolic/pddl.hpp"

namespace kaboum::symbolic {

using AtomId = std::int32_t;
using FluentId = std::int32_t;

// Value of a fluent with no value yet (object fluents hold object ids, numeric fluents numbers).
inline constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

// Numeric expression in postfix form, evaluated with a small fixed stack.
struct NumericCode {
  enum class Op : std::uint8_t { Push, Load, Add, Sub, Mul, Div, Neg };
  struct Instruction {
    Op op = Op::Push;
    double value = 0.0;
    FluentId fluent = 0;
  };
  std::vector<Instruction> code;
};

// (= fluent object), or its negation.
struct FluentTest {
  FluentId fluent = 0;
  ObjectId value = 0;
  bool positive = true;
};

struct NumericTest {
  Comparison comparison = Comparison::Equal;
  NumericCode lhs;
  NumericCode rhs;
  bool positive = true;
};

// One ground attachment call: a condition checker or an effect applicator.
struct GroundModuleCall {
  int module = 0;
  std::vector<ObjectId> args;
  std::vector<FluentId> reads;
  std::vector<FluentId> writes;
};

struct ModuleCheck {
  int call = 0;  // index into GroundTask::moduleCalls
  bool positive = true;
};

// Conjunction of literals. Attachment checks are evaluated last (they are the expensive part).
struct Condition {
  std::vector<AtomId> positive;
  std::vector<AtomId> negative;
  std::vector<FluentTest> fluentTests;
  std::vector<NumericTest> numericTests;
  std::vector<ModuleCheck> moduleChecks;
};

struct Assignment {
  FluentId target = 0;
  Effect::Kind kind = Effect::Kind::Assign;
  bool objectValued = false;
  ObjectId object = 0;  // objectValued: the assigned object
  NumericCode value;    // otherwise: the numeric operand
};

struct EffectList {
  std::vector<AtomId> adds;
  std::vector<AtomId> deletes;
  std::vector<Assignment> assignments;
  std::vector<int> moduleCalls;  // effect applicators, indices into GroundTask::moduleCalls
  bool empty() const {
    return adds.empty() && deletes.empty() && assignments.empty() && moduleCalls.empty();
  }
};

// Fires if any of its disjuncts holds in the state the operator is applied to.
struct ConditionalEffect {
  std::vector<Condition> disjuncts;
  EffectList effect;
};

struct Operator {
  std::string name;  // "action arg1 arg2", printed in plans as "(action arg1 arg2)"
  Condition precondition;
  EffectList effect;
  std::vector<ConditionalEffect> conditional;
};

// The goal formula in conjunctive form (thesis §3.1): `conjunction` and, for each clause, one of
// its conditions. A clause is the disjunctive normal form of one conjunct of the goal that keeps a
// disjunction, so a goal ∧_i (φ_i ∨ ψ_i) over n objects is n clauses of two conditions instead of a
// normal form of 2^n disjuncts, and each clause reads only its object's atoms.
struct Goal {
  bool reachable = true;  // false: statically false, no state satisfies it
  Condition conjunction;
  std::vector<std::vector<Condition>> clauses;  // each of at least two conditions
  bool conjunctive() const { return reachable && clauses.empty(); }
};

struct GroundingStatistics {
  std::size_t reachableAtoms = 0;
  std::size_t operators = 0;
  std::size_t fixpointPasses = 0;
};

struct GroundTask {
  std::vector<std::string> atomNames;    // "(on a b)"
  std::vector<std::string> fluentNames;  // "(getonebelow o1)"
  std::vector<bool> fluentIsNumeric;
  std::vector<AtomId> initialAtoms;
  std::vector<double> initialFluents;
  std::vector<Operator> operators;
  Goal goal;
  std::vector<GroundModuleCall> moduleCalls;
  std::vector<std::string> objectNames;

  // Facts of the delete relaxation: atoms [0, atomCount) then one fact per reachable value of each
  // object fluent. valueFacts[f] lists (value, fact) pairs, sorted by value.
  std::size_t factCount = 0;
  std::vector<std::vector<std::pair<ObjectId, int>>> valueFacts;
  int valueFact(FluentId fluent, ObjectId value) const;  // -1 if the value is unreachable

  GroundingStatistics statistics;
};

// Grounds with relaxed-reachability pruning (only operators whose preconditions can hold in the
// delete relaxation are produced). Throws InputError when a formula's disjunctive normal form
// (for the goal: one clause's) exceeds `maxDisjuncts`. `varyingPredicates` are kept as atoms even
// if no action changes them (their initial value may be unknown, as in contingent problems),
// instead of being folded, and each of their reachable atoms gets an id even if no condition or
// effect mentions it.
GroundTask ground(const Domain& domain, const Problem& problem, std::size_t maxDisjuncts = 4096,
                  std::span<const int> varyingPredicates = {});

}  // namespace kaboum::symbolic
