#include "kaboum/symbolic/validator.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {

std::vector<PlanStep> parsePlan(std::string_view text, const std::string& file,
                                const Domain& domain, const Problem& problem) {
  std::vector<PlanStep> plan;
  for (const SExpr& expr : readSExprs(text, file)) {
    const auto fail = [&](const SExpr& where, const std::string& what) {
      throw InputError(locate(file, what, where.pos.line, where.pos.column));
    };
    if (expr.kind != SExpr::Kind::List || expr.items.empty() || !expr.items[0].isAtom()) {
      fail(expr, "expected '(action args ...)'");
    }
    PlanStep step;
    step.pos = expr.pos;
    step.text = toString(expr);
    step.action = domain.findAction(expr.items[0].text);
    if (step.action < 0) fail(expr.items[0], "undefined action '" + expr.items[0].text + "'");
    const Action& action = domain.actions[step.action];
    if (expr.items.size() - 1 != static_cast<std::size_t>(action.parameterCount)) {
      fail(expr, "action '" + action.name + "' takes " + std::to_string(action.parameterCount) +
                     " argument(s), " + std::to_string(expr.items.size() - 1) + " given");
    }
    for (std::size_t i = 1; i < expr.items.size(); ++i) {
      if (!expr.items[i].isAtom()) fail(expr.items[i], "expected an object name");
      const ObjectId object = problem.findObject(expr.items[i].text);
      if (object < 0) fail(expr.items[i], "undefined object '" + expr.items[i].text + "'");
      step.args.push_back(object);
    }
    plan.push_back(std::move(step));
  }
  return plan;
}

namespace {

using Key = std::vector<int>;  // symbol id then arguments

// Replays actions on an explicit lifted state: a set of atoms and a map of fluent values.
class Replay {
 public:
  Replay(const Domain& domain, const Problem& problem, AttachmentRuntime& attachments)
      : domain_(domain), problem_(problem), attachments_(attachments) {
    for (const GroundAtom& atom : problem.init) atoms_.insert(key(atom.predicate, atom.args));
    for (const InitialFluent& value : problem.initFluents) {
      fluents_[key(value.function, value.args)] = value.value;
    }
  }

  ValidationResult run(const std::vector<PlanStep>& plan) {
    ValidationResult result;
    for (std::size_t s = 0; s < plan.size(); ++s) {
      const PlanStep& step = plan[s];
      const Action& action = domain_.actions[step.action];
      const auto stepFailure = [&](const std::string& what) {
        result.failedStep = s + 1;
        result.message = "step " + std::to_string(s + 1) + " " + step.text + ": " + what;
        return result;
      };
      for (int p = 0; p < action.parameterCount; ++p) {
        const int type = action.slotTypes[p];
        if (!domain_.isSubtype(problem_.objectTypes[step.args[p]], type)) {
          return stepFailure("argument '" + problem_.objectNames[step.args[p]] +
                             "' is not of type '" + domain_.types[type].name + "'");
        }
      }
      std::vector<ObjectId> binding(action.slotTypes.size(), 0);
      std::copy(step.args.begin(), step.args.end(), binding.begin());
      slotTypes_ = &action.slotTypes;
      slotNames_ = &action.slotNames;
      if (!holds(action.precondition, binding)) {
        return stepFailure("precondition " + explain(action.precondition, binding, true));
      }
      adds_.clear();
      deletes_.clear();
      writes_.clear();
      if (!collect(action.effect, binding)) {
        return stepFailure("an effect applicator reported the effect infeasible");
      }
      for (const Key& atom : deletes_) atoms_.erase(atom);
      for (const Key& atom : adds_) atoms_.insert(atom);
      for (const auto& [fluent, value] : writes_) fluents_[fluent] = value;
    }
    std::vector<ObjectId> binding(problem_.goalSlotTypes.size(), 0);
    slotTypes_ = &problem_.goalSlotTypes;
    slotNames_ = &problem_.goalSlotNames;
    if (!holds(problem_.goal, binding)) {
      result.message = "goal not reached after " + std::to_string(plan.size()) +
                       " step(s): " + explain(problem_.goal, binding, true);
      return result;
    }
    result.valid = true;
    result.message = "valid plan of " + std::to_string(plan.size()) + " step(s)";
    return result;
  }

 private:
  static Key key(int symbol, const std::vector<ObjectId>& args) {
    Key out{symbol};
    out.insert(out.end(), args.begin(), args.end());
    return out;
  }

  ObjectId resolve(const Term& term, const std::vector<ObjectId>& binding) const {
    return term.kind == Term::Kind::Variable ? binding[term.index] : term.index;
  }

  std::vector<ObjectId> resolveAll(const std::vector<Term>& terms,
                                   const std::vector<ObjectId>& binding) const {
    std::vector<ObjectId> out;
    for (const Term& term : terms) out.push_back(resolve(term, binding));
    return out;
  }

  double fluent(const Term& term, const std::vector<ObjectId>& binding) const {
    const auto it = fluents_.find(key(term.index, resolveAll(term.args, binding)));
    return it == fluents_.end() ? std::nan("") : it->second;
  }

  // Value of a term: an object id, or (function terms) the fluent's value.
  double value(const Term& term, const std::vector<ObjectId>& binding) const {
    return term.kind == Term::Kind::Function ? fluent(term, binding) : resolve(term, binding);
  }

  double number(const NumExpr& expr, const std::vector<ObjectId>& binding) const {
    switch (expr.kind) {
      case NumExpr::Kind::Number:
        return expr.value;
      case NumExpr::Kind::Fluent:
        return fluent(expr.fluent, binding);
      case NumExpr::Kind::Neg:
        return -number(expr.args[0], binding);
      case NumExpr::Kind::Add:
        return number(expr.args[0], binding) + number(expr.args[1], binding);
      case NumExpr::Kind::Sub:
        return number(expr.args[0], binding) - number(expr.args[1], binding);
      case NumExpr::Kind::Mul:
        return number(expr.args[0], binding) * number(expr.args[1], binding);
      case NumExpr::Kind::Div:
        return number(expr.args[0], binding) / number(expr.args[1], binding);
    }
    return std::nan("");
  }

  std::vector<double> moduleReads(const Module& module, const std::vector<ObjectId>& args) const {
    std::vector<double> reads;
    for (const Term& read : module.reads) reads.push_back(fluent(read, args));
    return reads;
  }

  // Calls body for each binding of `slots`; stops when body returns false. Returns false if
  // stopped.
  template <typename Body>
  bool forEach(const std::vector<int>& slots, std::size_t at, std::vector<ObjectId>& binding,
               Body&& body) {
    if (at == slots.size()) return body();
    const int slot = slots[at];
    for (std::size_t o = 0; o < problem_.objectTypes.size(); ++o) {
      if (!domain_.isSubtype(problem_.objectTypes[o], (*slotTypes_)[slot])) continue;
      binding[slot] = static_cast<ObjectId>(o);
      if (!forEach(slots, at + 1, binding, body)) return false;
    }
    return true;
  }

  bool holds(const Formula& formula, std::vector<ObjectId>& binding) {
    switch (formula.kind) {
      case Formula::Kind::True:
        return true;
      case Formula::Kind::False:
        return false;
      case Formula::Kind::Atom:
        return atoms_.count(key(formula.symbol, resolveAll(formula.args, binding))) > 0;
      case Formula::Kind::Equal: {
        const double lhs = value(formula.args[0], binding);
        const double rhs = value(formula.args[1], binding);
        return !std::isnan(lhs) && lhs == rhs;
      }
      case Formula::Kind::Compare: {
        const double lhs = number(formula.numbers[0], binding);
        const double rhs = number(formula.numbers[1], binding);
        if (std::isnan(lhs) || std::isnan(rhs)) return false;
        return comparisonHolds(formula.comparison, lhs, rhs);
      }
      case Formula::Kind::Module: {
        const std::vector<ObjectId> args = resolveAll(formula.args, binding);
        const std::vector<double> reads = moduleReads(domain_.modules[formula.symbol], args);
        return attachments_.check(formula.symbol, args, reads);
      }
      case Formula::Kind::Not:
        return !holds(formula.children[0], binding);
      case Formula::Kind::And:
        for (const Formula& child : formula.children) {
          if (!holds(child, binding)) return false;
        }
        return true;
      case Formula::Kind::Or:
        for (const Formula& child : formula.children) {
          if (holds(child, binding)) return true;
        }
        return false;
      case Formula::Kind::Imply:
        return !holds(formula.children[0], binding) || holds(formula.children[1], binding);
      case Formula::Kind::Exists:
        return !forEach(formula.slots, 0, binding,
                        [&]() { return !holds(formula.children[0], binding); });
      case Formula::Kind::Forall:
        return forEach(formula.slots, 0, binding,
                       [&]() { return holds(formula.children[0], binding); });
    }
    return false;
  }

  // PDDL text of `formula` with bound variables replaced by object names.
  std::string text(const Formula& formula, const std::vector<ObjectId>& binding) const {
    const auto list = [&](const std::string& head) {
      std::string out = "(" + head;
      for (const Formula& child : formula.children) out += " " + text(child, binding);
      return out + ")";
    };
    switch (formula.kind) {
      case Formula::Kind::True:
        return "(and)";
      case Formula::Kind::False:
        return "(or)";
      case Formula::Kind::Atom: {
        std::string out = "(" + domain_.predicates[formula.symbol].name;
        for (const Term& arg : formula.args) out += " " + termText(arg, binding);
        return out + ")";
      }
      case Formula::Kind::Equal:
        return "(= " + termText(formula.args[0], binding) + " " +
               termText(formula.args[1], binding) + ")";
      case Formula::Kind::Compare:
        return "(numeric comparison)";
      case Formula::Kind::Module: {
        std::string out = "[" + domain_.modules[formula.symbol].name;
        for (const Term& arg : formula.args) out += " " + termText(arg, binding);
        return out + "]";
      }
      case Formula::Kind::Not:
        return list("not");
      case Formula::Kind::And:
        return list("and");
      case Formula::Kind::Or:
        return list("or");
      case Formula::Kind::Imply:
        return list("imply");
      case Formula::Kind::Exists:
      case Formula::Kind::Forall: {
        std::string out = formula.kind == Formula::Kind::Exists ? "(exists (" : "(forall (";
        for (std::size_t i = 0; i < formula.slots.size(); ++i) {
          const int slot = formula.slots[i];
          out += (i > 0 ? " " : "") + (*slotNames_)[slot] + " - " +
                 domain_.types[(*slotTypes_)[slot]].name;
        }
        return out + ") " + text(formula.children[0], binding) + ")";
      }
    }
    return "";
  }

  std::string termText(const Term& term, const std::vector<ObjectId>& binding) const {
    if (term.kind == Term::Kind::Variable && unbound(term.index)) {
      return (*slotNames_)[term.index];
    }
    if (term.kind != Term::Kind::Function) return problem_.objectNames[resolve(term, binding)];
    std::string out = "(" + domain_.functions[term.index].name;
    for (const Term& arg : term.args) out += " " + termText(arg, binding);
    return out + ")";
  }

  bool unbound(int slot) const {
    return std::find(quantified_.begin(), quantified_.end(), slot) != quantified_.end();
  }

  // Describes why `formula` does not evaluate to `want`, down to the first failing literal of
  // conjunctions and universal quantifiers.
  std::string explain(const Formula& formula, std::vector<ObjectId>& binding, bool want) {
    if (formula.kind == Formula::Kind::Not) return explain(formula.children[0], binding, !want);
    const bool conjunctive = (formula.kind == Formula::Kind::And && want) ||
                             (formula.kind == Formula::Kind::Or && !want);
    if (conjunctive) {
      for (const Formula& child : formula.children) {
        if (holds(child, binding) != want) return explain(child, binding, want);
      }
    }
    if ((formula.kind == Formula::Kind::Forall && want) ||
        (formula.kind == Formula::Kind::Exists && !want)) {
      std::string out;
      forEach(formula.slots, 0, binding, [&]() {
        if (holds(formula.children[0], binding) == want) return true;
        out = explain(formula.children[0], binding, want);
        return false;
      });
      if (!out.empty()) return out;
    }
    quantified_.clear();
    collectQuantified(formula);
    return text(formula, binding) + (want ? " is false" : " is true");
  }

  void collectQuantified(const Formula& formula) {
    quantified_.insert(quantified_.end(), formula.slots.begin(), formula.slots.end());
    for (const Formula& child : formula.children) collectQuantified(child);
  }

  // Evaluates an effect on the current (old) state into adds_, deletes_ and writes_.
  bool collect(const Effect& effect, std::vector<ObjectId>& binding) {
    switch (effect.kind) {
      case Effect::Kind::And:
        for (const Effect& child : effect.children) {
          if (!collect(child, binding)) return false;
        }
        return true;
      case Effect::Kind::Add:
        adds_.push_back(key(effect.symbol, resolveAll(effect.args, binding)));
        return true;
      case Effect::Kind::Delete:
        deletes_.push_back(key(effect.symbol, resolveAll(effect.args, binding)));
        return true;
      case Effect::Kind::Forall:
        return forEach(effect.slots, 0, binding,
                       [&]() { return collect(effect.children[0], binding); });
      case Effect::Kind::When:
        return !holds(effect.condition, binding) || collect(effect.children[0], binding);
      case Effect::Kind::Module: {
        const Module& module = domain_.modules[effect.symbol];
        const std::vector<ObjectId> args = resolveAll(effect.args, binding);
        const std::vector<double> reads = moduleReads(module, args);
        std::vector<double> writes(module.writes.size(), std::nan(""));
        if (!attachments_.apply(effect.symbol, args, reads, writes)) return false;
        for (std::size_t i = 0; i < writes.size(); ++i) {
          writes_.push_back(
              {key(module.writes[i].index, resolveAll(module.writes[i].args, args)), writes[i]});
        }
        return true;
      }
      default: {
        const Key target = key(effect.target.index, resolveAll(effect.target.args, binding));
        if (!domain_.functions[effect.target.index].isNumeric()) {
          writes_.push_back({target, static_cast<double>(resolve(effect.objectValue, binding))});
          return true;
        }
        const double operand = number(effect.numberValue, binding);
        const double current = fluent(effect.target, binding);
        double result = operand;
        if (effect.kind == Effect::Kind::Increase) result = current + operand;
        if (effect.kind == Effect::Kind::Decrease) result = current - operand;
        if (effect.kind == Effect::Kind::ScaleUp) result = current * operand;
        if (effect.kind == Effect::Kind::ScaleDown) result = current / operand;
        writes_.push_back({target, result});
        return true;
      }
    }
  }

  const Domain& domain_;
  const Problem& problem_;
  AttachmentRuntime& attachments_;
  const std::vector<int>* slotTypes_ = nullptr;
  const std::vector<std::string>* slotNames_ = nullptr;
  std::vector<int> quantified_;  // slots printed as variables by explain()
  std::set<Key> atoms_;
  std::map<Key, double> fluents_;
  std::vector<Key> adds_, deletes_;
  std::vector<std::pair<Key, double>> writes_;
};

}  // namespace

ValidationResult validatePlan(const Domain& domain, const Problem& problem,
                              const std::vector<PlanStep>& plan, AttachmentRuntime& attachments) {
  return Replay(domain, problem, attachments).run(plan);
}

}  // namespace kaboum::symbolic
