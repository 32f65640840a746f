// Delete relaxation of a ground task as unary operators (Fast Downward style, thesis §6.2 search
// modes): one per effect group of each operator, plus one per condition of each goal clause
// reaching an artificial clause fact, and one from the goal's conjunction and clause facts to an
// artificial goal fact. Shared by the h_max/h_add/FF heuristics and by landmark generation.
#pragma once

#include <span>
#include <vector>

#include "kaboum/symbolic/state.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

class RelaxedTask {
 public:
  explicit RelaxedTask(const GroundTask& task);

  const GroundTask& task() const { return task_; }
  // Facts are the task's relaxation facts [0, factCount), the goal fact, one fact ¬p per atom
  // p no operator deletes (a negative literal over such an atom holds only where p is false; the
  // others are treated optimistically, as satisfiable, so a static fact such as a sensed
  // property that a goal disjunct negates is not taken for reachable), then one fact per goal
  // clause.
  int factCount() const {
    return goalFact_ + 1 + static_cast<int>(undeletable_.size()) + clauseFactCount_;
  }
  int goalFact() const { return goalFact_; }
  int unaryCount() const { return static_cast<int>(source_.size()); }
  // The ground operator a unary operator comes from, or -1 for a goal clause's condition or the
  // goal.
  int source(int unary) const { return source_[static_cast<std::size_t>(unary)]; }
  // Sorted, distinct precondition facts.
  std::span<const int> preconditions(int unary) const { return range(pre_, preStart_, unary); }
  std::span<const int> effects(int unary) const { return range(effects_, effectStart_, unary); }
  // Unary operators with `fact` among their preconditions.
  std::span<const int> consumers(int fact) const { return range(consumers_, consumerStart_, fact); }
  // Unary operators without preconditions.
  std::span<const int> unconditional() const { return unconditional_; }
  // Facts of the relaxed goal when the goal is one conjunction (else empty).
  std::span<const int> goalFacts() const { return goalFacts_; }
  // The facts true in `state` (atoms, then the value fact of each object fluent), into `out`.
  void stateFacts(StateView state, std::vector<int>& out) const;
  // The facts true in the task's initial state.
  std::vector<int> initialFacts() const;

 private:
  static std::span<const int> range(const std::vector<int>& items, const std::vector<int>& start,
                                    int index) {
    const auto i = static_cast<std::size_t>(index);
    return {items.data() + start[i], static_cast<std::size_t>(start[i + 1] - start[i])};
  }
  void addUnary(int op, std::initializer_list<const Condition*> conditions,
                const EffectList& effect);
  bool appendPreconditions(std::initializer_list<const Condition*> conditions,
                           std::span<const int> facts = {});
  void pushConditionFacts(const Condition& condition);
  void finishUnary(int op);

  const GroundTask& task_;
  int goalFact_;
  int clauseFactCount_ = 0;
  std::vector<AtomId> undeletable_;  // atoms no operator deletes, in order of their ¬p facts
  std::vector<int> negationFact_;    // per atom: its ¬p fact, or -1
  std::vector<int> pre_, preStart_, effects_, effectStart_, source_;
  std::vector<int> consumers_, consumerStart_, unconditional_, goalFacts_;
};

}  // namespace kaboum::symbolic
