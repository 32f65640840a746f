// Grounding with relaxed reachability (in the spirit of Fast Downward's translator): a fixpoint
// over reachable atoms instantiates actions by joining their positive preconditions, then each
// reachable instance is compiled into operators with conjunctive conditions.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

int GroundTask::valueFact(FluentId fluent, ObjectId value) const {
  const auto& facts = valueFacts[fluent];
  const auto it = std::lower_bound(facts.begin(), facts.end(), std::make_pair(value, -1));
  return it != facts.end() && it->first == value ? it->second : -1;
}

namespace {

using Tuple = std::vector<ObjectId>;
using Binding = std::vector<ObjectId>;

// A conjunction under construction; `impossible` marks a conjunction simplified to false.
struct Conjunction {
  Condition condition;
  bool impossible = false;
};
using Dnf = std::vector<Condition>;

// Positive literal of an action's top-level precondition, used to enumerate bindings by joining.
struct JoinLiteral {
  int relation = 0;
  std::vector<Term> args;  // variables (parameter slots) or objects
};

class Grounder {
 public:
  Grounder(const Domain& domain, const Problem& problem, std::size_t maxDisjuncts,
           std::span<const int> varyingPredicates)
      : domain_(domain),
        problem_(problem),
        maxDisjuncts_(maxDisjuncts),
        varyingPredicates_(varyingPredicates),
        relationCount_(domain.predicates.size() + domain.functions.size()),
        reachable_(relationCount_),
        tuples_(relationCount_) {}

  GroundTask run() {
    classifySymbols();
    for (const GroundAtom& atom : problem_.init) addTuple(atom.predicate, atom.args);
    for (const InitialFluent& value : problem_.initFluents) {
      Tuple key{value.function};
      key.insert(key.end(), value.args.begin(), value.args.end());
      initialValues_[key] = value.value;
      if (!domain_.functions[value.function].isNumeric()) {
        Tuple tuple = value.args;
        tuple.push_back(static_cast<ObjectId>(value.value));
        addTuple(functionRelation(value.function), tuple);
      }
    }
    task_.objectNames = problem_.objectNames;
    computeReachability();
    for (std::size_t a = 0; a < domain_.actions.size(); ++a) {
      for (const Binding& binding : applicable_[a]) instantiate(domain_.actions[a], binding);
    }
    Binding goalBinding(problem_.goalSlotTypes.size(), 0);
    slotTypes_ = &problem_.goalSlotTypes;
    addGoalConjuncts(problem_.goal, goalBinding, true);
    if (!task_.goal.reachable) task_.goal = Goal{false, {}, {}};
    finishFluents();
    task_.statistics.reachableAtoms = task_.atomNames.size();
    task_.statistics.operators = task_.operators.size();
    return std::move(task_);
  }

 private:
  int functionRelation(int function) const {
    return static_cast<int>(domain_.predicates.size()) + function;
  }

  bool addTuple(int relation, const Tuple& tuple) {
    if (!reachable_[relation].insert(tuple).second) return false;
    tuples_[relation].push_back(tuple);
    return true;
  }

  bool isReachable(int relation, const Tuple& tuple) const {
    return reachable_[relation].count(tuple) > 0;
  }

  // --- which predicates and functions can change ------------------------------------------

  void markEffects(const Effect& effect) {
    switch (effect.kind) {
      case Effect::Kind::Add:
      case Effect::Kind::Delete:
        fluentPredicate_[effect.symbol] = true;
        break;
      case Effect::Kind::Module:
        for (const Term& write : domain_.modules[effect.symbol].writes) {
          fluentFunction_[write.index] = true;
        }
        break;
      case Effect::Kind::And:
      case Effect::Kind::Forall:
      case Effect::Kind::When:
        break;
      default:
        fluentFunction_[effect.target.index] = true;
    }
    for (const Effect& child : effect.children) markEffects(child);
  }

  void classifySymbols() {
    fluentPredicate_.assign(domain_.predicates.size(), false);
    fluentFunction_.assign(domain_.functions.size(), false);
    for (const Action& action : domain_.actions) markEffects(action.effect);
    for (const int predicate : varyingPredicates_) fluentPredicate_[predicate] = true;
    objectsOfType_.resize(domain_.types.size());
    for (std::size_t t = 0; t < domain_.types.size(); ++t) {
      objectsOfType_[t] = problem_.objectsOfType(domain_, static_cast<int>(t));
    }
    applicable_.resize(domain_.actions.size());
    applicableSet_.resize(domain_.actions.size());
  }

  // --- relaxed reachability -------------------------------------------------------------------

  ObjectId resolve(const Term& term, const Binding& binding) const {
    return term.kind == Term::Kind::Variable ? binding[term.index] : term.index;
  }

  Tuple groundArgs(const std::vector<Term>& args, const Binding& binding) const {
    Tuple out;
    out.reserve(args.size() + 1);
    for (const Term& arg : args) out.push_back(resolve(arg, binding));
    return out;
  }

  // Value of a static function term in the initial state (kUndefined if none).
  double initialValue(int function, const Tuple& args) const {
    Tuple key{function};
    key.insert(key.end(), args.begin(), args.end());
    const auto it = initialValues_.find(key);
    return it == initialValues_.end() ? kUndefined : it->second;
  }

  // Whether `formula` can evaluate to `want` in some relaxed-reachable state (over-approximation).
  bool mayHold(const Formula& formula, Binding& binding, bool want) const {
    switch (formula.kind) {
      case Formula::Kind::True:
        return want;
      case Formula::Kind::False:
        return !want;
      case Formula::Kind::Atom: {
        const bool reached = isReachable(formula.symbol, groundArgs(formula.args, binding));
        if (!fluentPredicate_[formula.symbol]) return reached == want;
        return want ? reached : true;
      }
      case Formula::Kind::Equal:
        return mayEqual(formula.args[0], formula.args[1], binding, want);
      case Formula::Kind::Compare:
      case Formula::Kind::Module:
        return true;
      case Formula::Kind::Not:
        return mayHold(formula.children[0], binding, !want);
      case Formula::Kind::And:
      case Formula::Kind::Or: {
        const bool conjunctive = (formula.kind == Formula::Kind::And) == want;
        for (const Formula& child : formula.children) {
          const bool may = mayHold(child, binding, want);
          if (conjunctive && !may) return false;
          if (!conjunctive && may) return true;
        }
        return conjunctive;
      }
      case Formula::Kind::Imply:
        if (want) {
          return mayHold(formula.children[0], binding, false) ||
                 mayHold(formula.children[1], binding, true);
        }
        return mayHold(formula.children[0], binding, true) &&
               mayHold(formula.children[1], binding, false);
      case Formula::Kind::Exists:
      case Formula::Kind::Forall: {
        const bool conjunctive = (formula.kind == Formula::Kind::Forall) == want;
        bool result = conjunctive;
        forEachInstance(formula.slots, 0, binding, [&]() {
          const bool may = mayHold(formula.children[0], binding, want);
          if (conjunctive && !may) result = false;
          if (!conjunctive && may) result = true;
          return result == conjunctive;  // continue while undecided
        });
        return result;
      }
    }
    return true;
  }

  bool mayEqual(const Term& lhs, const Term& rhs, const Binding& binding, bool want) const {
    const Term* function = lhs.kind == Term::Kind::Function ? &lhs : nullptr;
    const Term* other = function != nullptr ? &rhs : &lhs;
    if (function == nullptr && rhs.kind == Term::Kind::Function) {
      function = &rhs;
      other = &lhs;
    }
    if (function == nullptr) return (resolve(lhs, binding) == resolve(rhs, binding)) == want;
    if (other->kind == Term::Kind::Function) return true;
    const Tuple args = groundArgs(function->args, binding);
    const ObjectId value = resolve(*other, binding);
    if (!fluentFunction_[function->index]) {
      return (initialValue(function->index, args) == value) == want;
    }
    if (!want) return true;
    Tuple tuple = args;
    tuple.push_back(value);
    return isReachable(functionRelation(function->index), tuple);
  }

  // Calls `body` for every binding of `slots` (from `at`); stops when body returns false.
  template <typename Body>
  bool forEachInstance(const std::vector<int>& slots, std::size_t at, Binding& binding,
                       Body&& body) const {
    if (at == slots.size()) return body();
    const int slot = slots[at];
    for (const ObjectId object : objectsOfType_[slotType(slot)]) {
      binding[slot] = object;
      if (!forEachInstance(slots, at + 1, binding, body)) return false;
    }
    return true;
  }

  int slotType(int slot) const { return (*slotTypes_)[slot]; }

  // Relaxed effects: every atom and object-fluent value the effect may produce becomes reachable.
  void relaxedEffects(const Effect& effect, Binding& binding, bool& changed) {
    switch (effect.kind) {
      case Effect::Kind::Add:
        changed |= addTuple(effect.symbol, groundArgs(effect.args, binding));
        return;
      case Effect::Kind::Assign:
        if (!domain_.functions[effect.target.index].isNumeric()) {
          Tuple tuple = groundArgs(effect.target.args, binding);
          tuple.push_back(resolve(effect.objectValue, binding));
          changed |= addTuple(functionRelation(effect.target.index), tuple);
        }
        return;
      case Effect::Kind::When:
        if (mayHold(effect.condition, binding, true)) {
          relaxedEffects(effect.children[0], binding, changed);
        }
        return;
      case Effect::Kind::Forall:
        forEachInstance(effect.slots, 0, binding, [&]() {
          relaxedEffects(effect.children[0], binding, changed);
          return true;
        });
        return;
      case Effect::Kind::And:
        for (const Effect& child : effect.children) relaxedEffects(child, binding, changed);
        return;
      default:
        return;
    }
  }

  static void collectJoinLiterals(const Formula& formula, int relationOffset,
                                  std::vector<JoinLiteral>& out) {
    if (formula.kind == Formula::Kind::And) {
      for (const Formula& child : formula.children) collectJoinLiterals(child, relationOffset, out);
    } else if (formula.kind == Formula::Kind::Atom) {
      out.push_back({formula.symbol, formula.args});
    } else if (formula.kind == Formula::Kind::Equal) {
      for (int side = 0; side < 2; ++side) {
        const Term& function = formula.args[side];
        const Term& value = formula.args[1 - side];
        if (function.kind == Term::Kind::Function && value.kind != Term::Kind::Function) {
          JoinLiteral literal{relationOffset + function.index, function.args};
          literal.args.push_back(value);
          out.push_back(std::move(literal));
          return;
        }
      }
    }
  }

  // Enumerates parameter bindings consistent with the join literals, then calls `body`.
  template <typename Body>
  void join(const Action& action, std::vector<const JoinLiteral*>& pending, Binding& binding,
            std::vector<bool>& bound, Body&& body) {
    if (pending.empty()) {
      std::vector<int> freeSlots;
      for (int p = 0; p < action.parameterCount; ++p) {
        if (!bound[p]) freeSlots.push_back(p);
      }
      forEachInstance(freeSlots, 0, binding, [&]() {
        body();
        return true;
      });
      return;
    }
    // Next literal: most bound arguments, then fewest tuples.
    auto best = pending.begin();
    int bestScore = -1;
    for (auto it = pending.begin(); it != pending.end(); ++it) {
      int boundArgs = 0;
      for (const Term& arg : (*it)->args) {
        boundArgs += arg.kind == Term::Kind::Object || bound[arg.index] ? 1 : 0;
      }
      const int score = boundArgs * 1000000 - static_cast<int>(std::min<std::size_t>(
                                                  tuples_[(*it)->relation].size(), 999999));
      if (score > bestScore) {
        bestScore = score;
        best = it;
      }
    }
    const JoinLiteral* literal = *best;
    pending.erase(best);
    std::vector<int> newlyBound;
    const std::vector<Tuple>& candidates = tuples_[literal->relation];
    for (std::size_t t = 0; t < candidates.size(); ++t) {
      const Tuple tuple = candidates[t];  // copy: the relation may grow during the body
      bool match = true;
      newlyBound.clear();
      for (std::size_t i = 0; i < tuple.size() && match; ++i) {
        const Term& arg = literal->args[i];
        if (arg.kind == Term::Kind::Object) {
          match = arg.index == tuple[i];
        } else if (bound[arg.index]) {
          match = binding[arg.index] == tuple[i];
        } else if (domain_.isSubtype(problem_.objectTypes[tuple[i]], slotType(arg.index))) {
          binding[arg.index] = tuple[i];
          bound[arg.index] = true;
          newlyBound.push_back(arg.index);
        } else {
          match = false;
        }
      }
      if (match) join(action, pending, binding, bound, body);
      for (const int slot : newlyBound) bound[slot] = false;
    }
    pending.insert(pending.begin(), literal);
  }

  void computeReachability() {
    std::vector<std::vector<JoinLiteral>> literals(domain_.actions.size());
    for (std::size_t a = 0; a < domain_.actions.size(); ++a) {
      collectJoinLiterals(domain_.actions[a].precondition,
                          static_cast<int>(domain_.predicates.size()), literals[a]);
    }
    bool changed = true;
    while (changed) {
      changed = false;
      ++task_.statistics.fixpointPasses;
      for (std::size_t a = 0; a < domain_.actions.size(); ++a) {
        const Action& action = domain_.actions[a];
        slotTypes_ = &action.slotTypes;
        Binding binding(action.slotTypes.size(), 0);
        std::vector<bool> bound(action.slotTypes.size(), false);
        std::vector<const JoinLiteral*> pending;
        for (const JoinLiteral& literal : literals[a]) pending.push_back(&literal);
        join(action, pending, binding, bound, [&]() {
          const Tuple key(binding.begin(), binding.begin() + action.parameterCount);
          const bool known = applicableSet_[a].count(key) > 0;
          if (!known && !mayHold(action.precondition, binding, true)) return;
          if (!known) {
            applicableSet_[a].insert(key);
            applicable_[a].push_back(key);
            changed = true;
          }
          relaxedEffects(action.effect, binding, changed);
        });
      }
    }
  }

  // --- compilation of reachable instances -----------------------------------------------------

  AtomId atomId(int predicate, const Tuple& args) {
    const auto [it, inserted] =
        atomIds_.try_emplace({predicate, args}, static_cast<AtomId>(task_.atomNames.size()));
    if (inserted) task_.atomNames.push_back(describeAtom(domain_, problem_, predicate, args));
    return it->second;
  }

  FluentId fluentId(int function, const Tuple& args) {
    const auto [it, inserted] =
        fluentIds_.try_emplace({function, args}, static_cast<FluentId>(task_.fluentNames.size()));
    if (inserted) {
      std::string name = "(" + domain_.functions[function].name;
      for (const ObjectId arg : args) name += " " + problem_.objectNames[arg];
      task_.fluentNames.push_back(name + ")");
      task_.fluentIsNumeric.push_back(domain_.functions[function].isNumeric());
      task_.initialFluents.push_back(initialValue(function, args));
      fluentFunctions_.push_back(function);
      fluentArgs_.push_back(args);
    }
    return it->second;
  }

  void compileNumber(const NumExpr& expr, const Binding& binding, NumericCode& out) {
    using Op = NumericCode::Op;
    switch (expr.kind) {
      case NumExpr::Kind::Number:
        out.code.push_back({Op::Push, expr.value, 0});
        return;
      case NumExpr::Kind::Fluent: {
        const Tuple args = groundArgs(expr.fluent.args, binding);
        if (fluentFunction_[expr.fluent.index]) {
          out.code.push_back({Op::Load, 0.0, fluentId(expr.fluent.index, args)});
        } else {
          out.code.push_back({Op::Push, initialValue(expr.fluent.index, args), 0});
        }
        return;
      }
      default:
        break;
    }
    for (const NumExpr& arg : expr.args) compileNumber(arg, binding, out);
    static constexpr Op kOps[] = {Op::Push, Op::Load, Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Neg};
    out.code.push_back({kOps[static_cast<int>(expr.kind)], 0.0, 0});
  }

  NumExpr fluentExpr(const Term& term) const {
    NumExpr out;
    out.kind = NumExpr::Kind::Fluent;
    out.fluent = term;
    return out;
  }

  int moduleCall(const Module& module, int moduleIndex, const std::vector<Term>& args,
                 const Binding& binding) {
    GroundModuleCall call;
    call.module = moduleIndex;
    call.args = groundArgs(args, binding);
    // Module fluents are written over the module's own parameter slots.
    const auto fluentsOf = [&](const std::vector<Term>& terms) {
      std::vector<FluentId> out;
      for (const Term& term : terms)
        out.push_back(fluentId(term.index, groundArgs(term.args, call.args)));
      return out;
    };
    call.reads = fluentsOf(module.reads);
    call.writes = fluentsOf(module.writes);
    task_.moduleCalls.push_back(std::move(call));
    return static_cast<int>(task_.moduleCalls.size()) - 1;
  }

  [[noreturn]] void tooComplex(const std::string& file, SourcePos pos) const {
    throw InputError(locate(file,
                            "formula has more than " + std::to_string(maxDisjuncts_) +
                                " disjuncts after grounding; simplify it",
                            pos.line, pos.column));
  }

  static void append(Condition& into, const Condition& from) {
    const auto cat = [](auto& a, const auto& b) { a.insert(a.end(), b.begin(), b.end()); };
    cat(into.positive, from.positive);
    cat(into.negative, from.negative);
    cat(into.fluentTests, from.fluentTests);
    cat(into.numericTests, from.numericTests);
    cat(into.moduleChecks, from.moduleChecks);
  }

  // Splits the goal (or its negation when !positive) at its conjunctions — `and`, `forall`, and
  // under a negation `or`, `exists` — and adds each other conjunct's disjunctive normal form to
  // task_.goal: one condition to the conjunction, several as a clause, none makes it unreachable.
  void addGoalConjuncts(const Formula& formula, Binding& binding, bool positive) {
    using Kind = Formula::Kind;
    const Kind conjunction = positive ? Kind::And : Kind::Or;
    const Kind universal = positive ? Kind::Forall : Kind::Exists;
    if (formula.kind == Kind::Not) {
      addGoalConjuncts(formula.children[0], binding, !positive);
    } else if (formula.kind == conjunction) {
      for (const Formula& child : formula.children) addGoalConjuncts(child, binding, positive);
    } else if (formula.kind == universal) {
      forEachInstance(formula.slots, 0, binding, [&]() {
        addGoalConjuncts(formula.children[0], binding, positive);
        return true;
      });
    } else {
      Dnf conjunct =
          dnf(formula, binding, problem_.goalSlotTypes, positive, problem_.goal.pos, problem_.file);
      if (conjunct.empty()) {
        task_.goal.reachable = false;
      } else if (conjunct.size() == 1) {
        append(task_.goal.conjunction, conjunct[0]);
      } else {
        task_.goal.clauses.push_back(std::move(conjunct));
      }
    }
  }

  // Disjunctive normal form of `formula` (or of its negation when !positive), simplified with
  // static facts and reachability. An empty result is false; one empty conjunction is true.
  Dnf dnf(const Formula& formula, Binding& binding, const std::vector<int>& slotTypes,
          bool positive, SourcePos pos, const std::string& file) {
    slotTypes_ = &slotTypes;
    const Dnf kTrue(1);
    const Dnf kFalse;
    switch (formula.kind) {
      case Formula::Kind::True:
        return positive ? kTrue : kFalse;
      case Formula::Kind::False:
        return positive ? kFalse : kTrue;
      case Formula::Kind::Atom: {
        const Tuple args = groundArgs(formula.args, binding);
        const bool reached = isReachable(formula.symbol, args);
        if (!fluentPredicate_[formula.symbol] || !reached) {
          return reached == positive ? kTrue : kFalse;
        }
        Dnf out(1);
        (positive ? out[0].positive : out[0].negative).push_back(atomId(formula.symbol, args));
        return out;
      }
      case Formula::Kind::Equal:
        return equality(formula.args[0], formula.args[1], binding, positive);
      case Formula::Kind::Compare: {
        Dnf out(1);
        NumericTest test{formula.comparison, {}, {}, positive};
        compileNumber(formula.numbers[0], binding, test.lhs);
        compileNumber(formula.numbers[1], binding, test.rhs);
        out[0].numericTests.push_back(std::move(test));
        return out;
      }
      case Formula::Kind::Module: {
        Dnf out(1);
        const int call =
            moduleCall(domain_.modules[formula.symbol], formula.symbol, formula.args, binding);
        out[0].moduleChecks.push_back({call, positive});
        return out;
      }
      case Formula::Kind::Not:
        return dnf(formula.children[0], binding, slotTypes, !positive, pos, file);
      case Formula::Kind::Imply: {
        Formula asOr;
        asOr.kind = Formula::Kind::Or;
        Formula negated;
        negated.kind = Formula::Kind::Not;
        negated.children.push_back(formula.children[0]);
        asOr.children = {negated, formula.children[1]};
        return dnf(asOr, binding, slotTypes, positive, pos, file);
      }
      case Formula::Kind::And:
      case Formula::Kind::Or: {
        std::vector<Dnf> parts;
        for (const Formula& child : formula.children) {
          parts.push_back(dnf(child, binding, slotTypes, positive, pos, file));
        }
        return combine(parts, (formula.kind == Formula::Kind::And) == positive, pos, file);
      }
      case Formula::Kind::Exists:
      case Formula::Kind::Forall: {
        std::vector<Dnf> parts;
        forEachInstance(formula.slots, 0, binding, [&]() {
          parts.push_back(dnf(formula.children[0], binding, slotTypes, positive, pos, file));
          return true;
        });
        return combine(parts, (formula.kind == Formula::Kind::Forall) == positive, pos, file);
      }
    }
    return kTrue;
  }

  Dnf combine(const std::vector<Dnf>& parts, bool conjunctive, SourcePos pos,
              const std::string& file) const {
    if (!conjunctive) {
      Dnf out;
      for (const Dnf& part : parts) {
        for (const Condition& c : part) {
          if (c.positive.empty() && c.negative.empty() && c.fluentTests.empty() &&
              c.numericTests.empty() && c.moduleChecks.empty()) {
            return Dnf(1);  // a true disjunct
          }
          out.push_back(c);
        }
        if (out.size() > maxDisjuncts_) tooComplex(file, pos);
      }
      return out;
    }
    Dnf out(1);
    for (const Dnf& part : parts) {
      if (part.empty()) return {};
      if (part.size() * out.size() > maxDisjuncts_) tooComplex(file, pos);
      Dnf next;
      for (const Condition& left : out) {
        for (const Condition& right : part) {
          next.push_back(left);
          append(next.back(), right);
        }
      }
      out = std::move(next);
    }
    return out;
  }

  Dnf equality(const Term& lhs, const Term& rhs, const Binding& binding, bool positive) {
    const Dnf kTrue(1);
    const Dnf kFalse;
    const bool lhsFunction = lhs.kind == Term::Kind::Function;
    const bool rhsFunction = rhs.kind == Term::Kind::Function;
    if (!lhsFunction && !rhsFunction) {
      return (resolve(lhs, binding) == resolve(rhs, binding)) == positive ? kTrue : kFalse;
    }
    Dnf out(1);
    if (lhsFunction && rhsFunction) {
      NumericTest test{Comparison::Equal, {}, {}, positive};
      compileNumber(fluentExpr(lhs), binding, test.lhs);
      compileNumber(fluentExpr(rhs), binding, test.rhs);
      out[0].numericTests.push_back(std::move(test));
      return out;
    }
    const Term& function = lhsFunction ? lhs : rhs;
    const ObjectId value = resolve(lhsFunction ? rhs : lhs, binding);
    const Tuple args = groundArgs(function.args, binding);
    if (!fluentFunction_[function.index]) {
      return (initialValue(function.index, args) == value) == positive ? kTrue : kFalse;
    }
    Tuple tuple = args;
    tuple.push_back(value);
    if (!isReachable(functionRelation(function.index), tuple)) return positive ? kFalse : kTrue;
    out[0].fluentTests.push_back({fluentId(function.index, args), value, positive});
    return out;
  }

  static bool alwaysTrue(const Dnf& condition) {
    const Condition& c = condition[0];
    return condition.size() == 1 && c.positive.empty() && c.negative.empty() &&
           c.fluentTests.empty() && c.numericTests.empty() && c.moduleChecks.empty();
  }

  static EffectList& effectList(Operator& op, int conditional) {
    return conditional < 0 ? op.effect : op.conditional[conditional].effect;
  }

  // Flattens an effect into `op`: into its unconditional list (conditional < 0) or into
  // op.conditional[conditional], whose condition is `condition`. Nested whens conjoin conditions.
  void compileEffect(const Effect& effect, Binding& binding, const Action& action,
                     const Dnf& condition, int conditional, Operator& op) {
    switch (effect.kind) {
      case Effect::Kind::And:
        for (const Effect& child : effect.children) {
          compileEffect(child, binding, action, condition, conditional, op);
        }
        return;
      case Effect::Kind::Add:
      case Effect::Kind::Delete: {
        const Tuple args = groundArgs(effect.args, binding);
        if (effect.kind == Effect::Kind::Delete && !isReachable(effect.symbol, args)) return;
        const AtomId atom = atomId(effect.symbol, args);
        EffectList& list = effectList(op, conditional);
        (effect.kind == Effect::Kind::Add ? list.adds : list.deletes).push_back(atom);
        return;
      }
      case Effect::Kind::Forall:
        forEachInstance(effect.slots, 0, binding, [&]() {
          compileEffect(effect.children[0], binding, action, condition, conditional, op);
          return true;
        });
        return;
      case Effect::Kind::When: {
        std::vector<Dnf> parts{condition, dnf(effect.condition, binding, action.slotTypes, true,
                                              effect.pos, domain_.file)};
        const Dnf both = combine(parts, true, effect.pos, domain_.file);
        if (both.empty()) return;
        if (alwaysTrue(both)) {
          compileEffect(effect.children[0], binding, action, condition, conditional, op);
          return;
        }
        op.conditional.push_back({both, {}});
        const int inner = static_cast<int>(op.conditional.size()) - 1;
        compileEffect(effect.children[0], binding, action, both, inner, op);
        return;
      }
      case Effect::Kind::Module: {
        const int call =
            moduleCall(domain_.modules[effect.symbol], effect.symbol, effect.args, binding);
        effectList(op, conditional).moduleCalls.push_back(call);
        return;
      }
      default: {
        Assignment assignment;
        assignment.kind = effect.kind;
        assignment.target = fluentId(effect.target.index, groundArgs(effect.target.args, binding));
        assignment.objectValued = !domain_.functions[effect.target.index].isNumeric();
        if (assignment.objectValued) {
          assignment.object = resolve(effect.objectValue, binding);
        } else {
          compileNumber(effect.numberValue, binding, assignment.value);
        }
        effectList(op, conditional).assignments.push_back(std::move(assignment));
        return;
      }
    }
  }

  void instantiate(const Action& action, const Binding& parameters) {
    Binding binding(action.slotTypes.size(), 0);
    std::copy(parameters.begin(), parameters.end(), binding.begin());
    const Dnf preconditions = dnf(action.precondition, binding, action.slotTypes, true,
                                  action.precondition.pos, domain_.file);
    std::string name = action.name;
    for (const ObjectId arg : parameters) name += " " + problem_.objectNames[arg];
    for (const Condition& precondition : preconditions) {
      Operator op;
      op.name = name;
      op.precondition = precondition;
      compileEffect(action.effect, binding, action, Dnf(1), -1, op);
      std::erase_if(op.conditional, [](const ConditionalEffect& c) { return c.effect.empty(); });
      if (op.effect.empty() && op.conditional.empty()) continue;
      task_.operators.push_back(std::move(op));
    }
  }

  // Initial atoms, fluent values and the relaxed facts of object fluents.
  void finishFluents() {
    for (const int predicate : varyingPredicates_) {
      for (const Tuple& tuple : tuples_[predicate]) atomId(predicate, tuple);
    }
    for (const GroundAtom& atom : problem_.init) {
      const auto it = atomIds_.find({atom.predicate, atom.args});
      if (it != atomIds_.end()) task_.initialAtoms.push_back(it->second);
    }
    std::sort(task_.initialAtoms.begin(), task_.initialAtoms.end());
    task_.initialAtoms.erase(std::unique(task_.initialAtoms.begin(), task_.initialAtoms.end()),
                             task_.initialAtoms.end());
    int fact = static_cast<int>(task_.atomNames.size());
    task_.valueFacts.resize(task_.fluentNames.size());
    for (std::size_t f = 0; f < task_.fluentNames.size(); ++f) {
      if (task_.fluentIsNumeric[f]) continue;
      const Tuple& args = fluentArgs_[f];
      for (const Tuple& tuple : tuples_[functionRelation(fluentFunctions_[f])]) {
        if (std::equal(args.begin(), args.end(), tuple.begin())) {
          task_.valueFacts[f].push_back({tuple.back(), fact++});
        }
      }
      std::sort(task_.valueFacts[f].begin(), task_.valueFacts[f].end());
    }
    task_.factCount = static_cast<std::size_t>(fact);
  }

  const Domain& domain_;
  const Problem& problem_;
  std::size_t maxDisjuncts_;
  std::span<const int> varyingPredicates_;
  std::size_t relationCount_;
  std::vector<std::set<Tuple>> reachable_;
  std::vector<std::vector<Tuple>> tuples_;
  std::map<Tuple, double> initialValues_;  // key: function id then arguments
  std::vector<bool> fluentPredicate_;
  std::vector<bool> fluentFunction_;
  std::vector<std::vector<ObjectId>> objectsOfType_;
  std::vector<std::vector<Tuple>> applicable_;
  std::vector<std::set<Tuple>> applicableSet_;
  const std::vector<int>* slotTypes_ = nullptr;
  std::map<std::pair<int, Tuple>, AtomId> atomIds_;
  std::map<std::pair<int, Tuple>, FluentId> fluentIds_;
  std::vector<int> fluentFunctions_;
  std::vector<Tuple> fluentArgs_;
  GroundTask task_;
};

}  // namespace

GroundTask ground(const Domain& domain, const Problem& problem, std::size_t maxDisjuncts,
                  std::span<const int> varyingPredicates) {
  return Grounder(domain, problem, maxDisjuncts, varyingPredicates).run();
}

}  // namespace kaboum::symbolic
