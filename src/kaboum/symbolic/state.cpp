#include "kaboum/symbolic/state.hpp"

#include <algorithm>
#include <cmath>

namespace kaboum::symbolic {

StateEvaluator::StateEvaluator(const GroundTask& task, AttachmentRuntime& attachments)
    : task_(task),
      attachments_(attachments),
      layout_(task.atomNames.size(), task.fluentNames.size()) {
  std::size_t deepest = 1;
  const auto measure = [&](const NumericCode& code) {
    deepest = std::max(deepest, code.code.size());
  };
  const auto measureCondition = [&](const Condition& c) {
    for (const NumericTest& test : c.numericTests) {
      measure(test.lhs);
      measure(test.rhs);
    }
  };
  const auto measureEffect = [&](const EffectList& e) {
    for (const Assignment& a : e.assignments) measure(a.value);
  };
  for (const Operator& op : task.operators) {
    measureCondition(op.precondition);
    measureEffect(op.effect);
    for (const ConditionalEffect& c : op.conditional) {
      for (const Condition& d : c.disjuncts) measureCondition(d);
      measureEffect(c.effect);
    }
  }
  measureCondition(task.goal.conjunction);
  for (const std::vector<Condition>& clause : task.goal.clauses) {
    for (const Condition& c : clause) measureCondition(c);
  }
  stack_.resize(deepest);
}

void StateEvaluator::initialState(std::span<std::uint64_t> out) const {
  std::fill(out.begin(), out.end(), 0);
  for (const AtomId atom : task_.initialAtoms) out[atom >> 6] |= std::uint64_t{1} << (atom & 63);
  for (std::size_t f = 0; f < task_.initialFluents.size(); ++f) {
    out[layout_.fluentOffset() + f] = std::bit_cast<std::uint64_t>(task_.initialFluents[f]);
  }
}

double StateEvaluator::evaluate(const NumericCode& code, StateView state) {
  using Op = NumericCode::Op;
  std::size_t top = 0;
  for (const auto& instruction : code.code) {
    switch (instruction.op) {
      case Op::Push:
        stack_[top++] = instruction.value;
        break;
      case Op::Load:
        stack_[top++] = state.fluent(instruction.fluent);
        break;
      case Op::Neg:
        stack_[top - 1] = -stack_[top - 1];
        break;
      default: {
        const double rhs = stack_[--top];
        double& lhs = stack_[top - 1];
        if (instruction.op == Op::Add) lhs += rhs;
        if (instruction.op == Op::Sub) lhs -= rhs;
        if (instruction.op == Op::Mul) lhs *= rhs;
        if (instruction.op == Op::Div) lhs /= rhs;
      }
    }
  }
  return top == 0 ? kUndefined : stack_[0];
}

bool StateEvaluator::holds(const Condition& condition, StateView state) {
  for (const AtomId atom : condition.positive) {
    if (!state.atom(atom)) return false;
  }
  for (const AtomId atom : condition.negative) {
    if (state.atom(atom)) return false;
  }
  for (const FluentTest& test : condition.fluentTests) {
    if ((state.fluent(test.fluent) == test.value) != test.positive) return false;
  }
  for (const NumericTest& test : condition.numericTests) {
    const double lhs = evaluate(test.lhs, state);
    const double rhs = evaluate(test.rhs, state);
    // A comparison with an undefined value is false, and so is its negation.
    if (std::isnan(lhs) || std::isnan(rhs)) return false;
    if (comparisonHolds(test.comparison, lhs, rhs) != test.positive) return false;
  }
  for (const ModuleCheck& check : condition.moduleChecks) {
    const GroundModuleCall& call = task_.moduleCalls[check.call];
    reads_.clear();
    for (const FluentId read : call.reads) reads_.push_back(state.fluent(read));
    if (attachments_.check(call.module, call.args, reads_) != check.positive) return false;
  }
  return true;
}

bool StateEvaluator::holdsAny(const std::vector<Condition>& disjuncts, StateView state) {
  return std::any_of(disjuncts.begin(), disjuncts.end(),
                     [&](const Condition& c) { return holds(c, state); });
}

bool StateEvaluator::isGoal(StateView state) {
  const Goal& goal = task_.goal;
  return goal.reachable && holds(goal.conjunction, state) &&
         std::all_of(goal.clauses.begin(), goal.clauses.end(),
                     [&](const std::vector<Condition>& clause) { return holdsAny(clause, state); });
}

// Evaluates the assignments and module effects of `effect` on the old state into pendingWrites_.
bool StateEvaluator::collect(const EffectList& effect, StateView state, bool effectApplicators) {
  for (const Assignment& assignment : effect.assignments) {
    double value = assignment.objectValued ? assignment.object : evaluate(assignment.value, state);
    const double current = state.fluent(assignment.target);
    switch (assignment.kind) {
      case Effect::Kind::Increase:
        value = current + value;
        break;
      case Effect::Kind::Decrease:
        value = current - value;
        break;
      case Effect::Kind::ScaleUp:
        value = current * value;
        break;
      case Effect::Kind::ScaleDown:
        value = current / value;
        break;
      default:
        break;
    }
    pendingWrites_.push_back({assignment.target, value});
  }
  if (!effectApplicators) return true;
  for (const int index : effect.moduleCalls) {
    const GroundModuleCall& call = task_.moduleCalls[index];
    reads_.clear();
    for (const FluentId read : call.reads) reads_.push_back(state.fluent(read));
    writes_.assign(call.writes.size(), kUndefined);
    if (!attachments_.apply(call.module, call.args, reads_, writes_)) return false;
    for (std::size_t i = 0; i < call.writes.size(); ++i) {
      pendingWrites_.push_back({call.writes[i], writes_[i]});
    }
  }
  return true;
}

bool StateEvaluator::apply(const Operator& op, StateView state, std::span<std::uint64_t> out,
                           bool effectApplicators) {
  std::copy_n(state.words(), layout_.words(), out.begin());
  firing_.clear();
  pendingWrites_.clear();
  firing_.push_back(&op.effect);
  for (const ConditionalEffect& conditional : op.conditional) {
    if (holdsAny(conditional.disjuncts, state)) firing_.push_back(&conditional.effect);
  }
  for (const EffectList* effect : firing_) {
    if (!collect(*effect, state, effectApplicators)) return false;
  }
  for (const EffectList* effect : firing_) {
    for (const AtomId atom : effect->deletes) out[atom >> 6] &= ~(std::uint64_t{1} << (atom & 63));
  }
  for (const EffectList* effect : firing_) {
    for (const AtomId atom : effect->adds) out[atom >> 6] |= std::uint64_t{1} << (atom & 63);
  }
  for (const auto& [fluent, value] : pendingWrites_) {
    out[layout_.fluentOffset() + static_cast<std::size_t>(fluent)] =
        std::bit_cast<std::uint64_t>(value);
  }
  return true;
}

}  // namespace kaboum::symbolic
