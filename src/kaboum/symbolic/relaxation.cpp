#include "kaboum/symbolic/relaxation.hpp"

#include <algorithm>
#include <cmath>

namespace kaboum::symbolic {
namespace {

constexpr int kUnreachable = -1;

}  // namespace

RelaxedTask::RelaxedTask(const GroundTask& task)
    : task_(task), goalFact_(static_cast<int>(task.factCount)) {
  std::vector<bool> deleted(task.atomNames.size(), false);
  for (const Operator& op : task.operators) {
    for (const AtomId atom : op.effect.deletes) deleted[static_cast<std::size_t>(atom)] = true;
    for (const ConditionalEffect& conditional : op.conditional) {
      for (const AtomId atom : conditional.effect.deletes) {
        deleted[static_cast<std::size_t>(atom)] = true;
      }
    }
  }
  negationFact_.assign(task.atomNames.size(), -1);
  for (std::size_t atom = 0; atom < deleted.size(); ++atom) {
    if (deleted[atom]) continue;
    negationFact_[atom] = goalFact_ + 1 + static_cast<int>(undeletable_.size());
    undeletable_.push_back(static_cast<AtomId>(atom));
  }
  preStart_.push_back(0);
  effectStart_.push_back(0);
  for (std::size_t o = 0; o < task.operators.size(); ++o) {
    const Operator& op = task.operators[o];
    addUnary(static_cast<int>(o), {&op.precondition}, op.effect);
    for (const ConditionalEffect& conditional : op.conditional) {
      for (const Condition& disjunct : conditional.disjuncts) {
        addUnary(static_cast<int>(o), {&op.precondition, &disjunct}, conditional.effect);
      }
    }
  }
  // Each condition of a goal clause reaches the clause's fact; the conjunction and every clause
  // fact reach the goal fact.
  const int firstClauseFact = goalFact_ + 1 + static_cast<int>(undeletable_.size());
  std::vector<int> clauseFacts;
  if (task.goal.reachable) {
    for (const std::vector<Condition>& clause : task.goal.clauses) {
      clauseFacts.push_back(firstClauseFact + static_cast<int>(clauseFacts.size()));
      for (const Condition& disjunct : clause) {
        if (!appendPreconditions({&disjunct})) continue;
        effects_.push_back(clauseFacts.back());
        finishUnary(-1);
      }
    }
    if (appendPreconditions({&task.goal.conjunction}, clauseFacts)) {
      if (task.goal.conjunctive()) goalFacts_.assign(pre_.begin() + preStart_.back(), pre_.end());
      effects_.push_back(goalFact_);
      finishUnary(-1);
    }
  }
  clauseFactCount_ = static_cast<int>(clauseFacts.size());
  const auto facts = static_cast<std::size_t>(factCount());
  consumerStart_.assign(facts + 1, 0);
  for (const int fact : pre_) ++consumerStart_[static_cast<std::size_t>(fact) + 1];
  for (std::size_t f = 0; f < facts; ++f) consumerStart_[f + 1] += consumerStart_[f];
  consumers_.resize(pre_.size());
  std::vector<int> fill(consumerStart_.begin(), consumerStart_.end() - 1);
  for (int u = 0; u < unaryCount(); ++u) {
    for (const int fact : preconditions(u)) consumers_[fill[fact]++] = u;
    if (preconditions(u).empty()) unconditional_.push_back(u);
  }
}

void RelaxedTask::stateFacts(StateView state, std::vector<int>& out) const {
  out.clear();
  const auto atoms = static_cast<AtomId>(task_.atomNames.size());
  for (AtomId atom = 0; atom < atoms; ++atom) {
    if (state.atom(atom)) out.push_back(atom);
  }
  for (const AtomId atom : undeletable_) {
    if (!state.atom(atom)) out.push_back(negationFact_[static_cast<std::size_t>(atom)]);
  }
  for (std::size_t f = 0; f < task_.valueFacts.size(); ++f) {
    if (task_.valueFacts[f].empty()) continue;
    const double value = state.fluent(static_cast<FluentId>(f));
    if (std::isnan(value)) continue;
    const int fact = task_.valueFact(static_cast<FluentId>(f), static_cast<ObjectId>(value));
    if (fact >= 0) out.push_back(fact);
  }
}

std::vector<int> RelaxedTask::initialFacts() const {
  std::vector<int> out(task_.initialAtoms.begin(), task_.initialAtoms.end());
  std::vector<bool> initial(task_.atomNames.size(), false);
  for (const AtomId atom : task_.initialAtoms) initial[static_cast<std::size_t>(atom)] = true;
  for (const AtomId atom : undeletable_) {
    if (!initial[static_cast<std::size_t>(atom)]) {
      out.push_back(negationFact_[static_cast<std::size_t>(atom)]);
    }
  }
  for (std::size_t f = 0; f < task_.valueFacts.size(); ++f) {
    const double value = task_.initialFluents[f];
    if (task_.valueFacts[f].empty() || std::isnan(value)) continue;
    const int fact = task_.valueFact(static_cast<FluentId>(f), static_cast<ObjectId>(value));
    if (fact >= 0) out.push_back(fact);
  }
  return out;
}

void RelaxedTask::pushConditionFacts(const Condition& condition) {
  for (const AtomId atom : condition.positive) pre_.push_back(atom);
  for (const AtomId atom : condition.negative) {
    const int fact = negationFact_[static_cast<std::size_t>(atom)];
    if (fact >= 0) pre_.push_back(fact);
  }
  for (const FluentTest& test : condition.fluentTests) {
    if (!test.positive) continue;
    const int fact = task_.valueFact(test.fluent, test.value);
    pre_.push_back(fact < 0 ? kUnreachable : fact);
  }
}

void RelaxedTask::addUnary(int op, std::initializer_list<const Condition*> conditions,
                           const EffectList& effect) {
  const std::size_t firstEffect = effects_.size();
  for (const AtomId atom : effect.adds) effects_.push_back(atom);
  for (const Assignment& assignment : effect.assignments) {
    if (!assignment.objectValued) continue;
    const int fact = task_.valueFact(assignment.target, assignment.object);
    if (fact >= 0) effects_.push_back(fact);
  }
  if (effects_.size() == firstEffect) return;
  if (!appendPreconditions(conditions)) {
    effects_.resize(firstEffect);
    return;
  }
  finishUnary(op);
}

// Appends the sorted, distinct precondition facts of `conditions` and `facts`; false (and nothing
// appended) if one of them can never hold.
bool RelaxedTask::appendPreconditions(std::initializer_list<const Condition*> conditions,
                                      std::span<const int> facts) {
  const std::size_t firstPre = pre_.size();
  for (const Condition* condition : conditions) pushConditionFacts(*condition);
  pre_.insert(pre_.end(), facts.begin(), facts.end());
  const auto first = pre_.begin() + static_cast<long>(firstPre);
  if (std::find(first, pre_.end(), kUnreachable) != pre_.end()) {
    pre_.resize(firstPre);
    return false;
  }
  std::sort(first, pre_.end());
  pre_.erase(std::unique(first, pre_.end()), pre_.end());
  return true;
}

void RelaxedTask::finishUnary(int op) {
  source_.push_back(op);
  preStart_.push_back(static_cast<int>(pre_.size()));
  effectStart_.push_back(static_cast<int>(effects_.size()));
}

}  // namespace kaboum::symbolic
