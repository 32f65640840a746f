#include "kaboum/symbolic/heuristic.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {
namespace {

class BlindHeuristic : public Heuristic {
 public:
  explicit BlindHeuristic(const GroundTask& task) : task_(task) {}
  int evaluate(StateView, std::vector<int>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    return task_.goal.empty() ? kDeadEnd : 0;
  }
  bool admissible() const override { return true; }

 private:
  const GroundTask& task_;
};

// Generalized Dijkstra over unary relaxed operators (one per effect group of each operator, plus
// one per goal disjunct reaching an artificial goal fact).
class RelaxedHeuristic : public Heuristic {
 public:
  enum class Kind { Max, Add, FF };

  RelaxedHeuristic(const GroundTask& task, Kind kind)
      : task_(task), kind_(kind), goalFact_(static_cast<int>(task.factCount)) {
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
    for (const Condition& disjunct : task.goal) {
      if (!appendPreconditions({&disjunct})) continue;
      effects_.push_back(goalFact_);
      finishUnary(-1);
    }
    const std::size_t facts = task.factCount + 1;
    consumerStart_.assign(facts + 1, 0);
    for (const int fact : pre_) ++consumerStart_[fact + 1];
    for (std::size_t f = 0; f < facts; ++f) consumerStart_[f + 1] += consumerStart_[f];
    consumers_.resize(pre_.size());
    std::vector<int> fill(consumerStart_.begin(), consumerStart_.end() - 1);
    for (std::size_t u = 0; u + 1 < preStart_.size(); ++u) {
      for (int i = preStart_[u]; i < preStart_[u + 1]; ++i) {
        consumers_[fill[pre_[i]]++] = static_cast<int>(u);
      }
      if (preStart_[u] == preStart_[u + 1]) unconditional_.push_back(static_cast<int>(u));
    }
    factCost_.resize(facts);
    supporter_.resize(facts);
    unsatisfied_.resize(source_.size());
    for (std::size_t u = 0; u < source_.size(); ++u) {
      preCount_.push_back(preStart_[u + 1] - preStart_[u]);
    }
    operatorCost_.resize(source_.size());
    marked_.assign(task.operators.size(), 0);
    factMarked_.assign(facts, 0);
  }

  bool admissible() const override { return kind_ == Kind::Max; }

  int evaluate(StateView state, std::vector<int>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    explore(state);
    const int h = factCost_[goalFact_];
    if (h == kInfinity) return kDeadEnd;
    if (kind_ != Kind::FF) return h;
    return relaxedPlan(preferred);
  }

 private:
  static constexpr int kInfinity = std::numeric_limits<int>::max() / 4;

  void pushConditionFacts(const Condition& condition) {
    for (const AtomId atom : condition.positive) pre_.push_back(atom);
    for (const FluentTest& test : condition.fluentTests) {
      if (!test.positive) continue;
      const int fact = task_.valueFact(test.fluent, test.value);
      pre_.push_back(fact < 0 ? kUnreachable : fact);
    }
  }

  void addUnary(int op, std::initializer_list<const Condition*> conditions,
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

  // Appends the sorted, distinct precondition facts of `conditions`; false (and nothing appended)
  // if one of them can never hold.
  bool appendPreconditions(std::initializer_list<const Condition*> conditions) {
    const std::size_t firstPre = pre_.size();
    for (const Condition* condition : conditions) pushConditionFacts(*condition);
    const auto first = pre_.begin() + static_cast<long>(firstPre);
    if (std::find(first, pre_.end(), kUnreachable) != pre_.end()) {
      pre_.resize(firstPre);
      return false;
    }
    std::sort(first, pre_.end());
    pre_.erase(std::unique(first, pre_.end()), pre_.end());
    return true;
  }

  void finishUnary(int op) {
    source_.push_back(op);
    preStart_.push_back(static_cast<int>(pre_.size()));
    effectStart_.push_back(static_cast<int>(effects_.size()));
  }

  void reach(int fact, int cost, int unary) {
    if (cost >= factCost_[fact]) return;
    factCost_[fact] = cost;
    supporter_[fact] = unary;
    if (static_cast<std::size_t>(cost) >= buckets_.size()) buckets_.resize(cost + 1);
    buckets_[cost].push_back(fact);
  }

  void fire(int unary) {
    const int cost = operatorCost_[unary] + (source_[unary] >= 0 ? 1 : 0);
    for (int i = effectStart_[unary]; i < effectStart_[unary + 1]; ++i) {
      reach(effects_[i], cost, unary);
    }
  }

  void explore(StateView state) {
    std::fill(factCost_.begin(), factCost_.end(), kInfinity);
    std::fill(operatorCost_.begin(), operatorCost_.end(), 0);
    std::copy(preCount_.begin(), preCount_.end(), unsatisfied_.begin());
    const auto atoms = static_cast<AtomId>(task_.atomNames.size());
    for (AtomId atom = 0; atom < atoms; ++atom) {
      if (state.atom(atom)) reach(atom, 0, -1);
    }
    for (std::size_t f = 0; f < task_.valueFacts.size(); ++f) {
      if (task_.valueFacts[f].empty()) continue;
      const double value = state.fluent(static_cast<FluentId>(f));
      if (std::isnan(value)) continue;
      const int fact = task_.valueFact(static_cast<FluentId>(f), static_cast<ObjectId>(value));
      if (fact >= 0) reach(fact, 0, -1);
    }
    for (const int unary : unconditional_) fire(unary);
    // Bucket queue over integer costs; the current bucket may grow while it is scanned.
    // (indexed access: reach() may grow buckets_ and move the buckets)
    bool goalReached = false;
    for (std::size_t cost = 0; cost < buckets_.size() && !goalReached; ++cost) {
      for (std::size_t k = 0; k < buckets_[cost].size(); ++k) {
        const int fact = buckets_[cost][k];
        if (static_cast<std::size_t>(factCost_[fact]) != cost) continue;
        if (fact == goalFact_) {
          goalReached = true;
          break;
        }
        const int c = static_cast<int>(cost);
        for (int i = consumerStart_[fact]; i < consumerStart_[fact + 1]; ++i) {
          const int unary = consumers_[i];
          operatorCost_[unary] = kind_ == Kind::Max ? std::max(operatorCost_[unary], c)
                                                    : std::min(operatorCost_[unary] + c, kInfinity);
          if (--unsatisfied_[unary] == 0) fire(unary);
        }
      }
    }
    for (auto& bucket : buckets_) bucket.clear();
  }

  // FF: counts the distinct operators of a relaxed plan built from h_add's best supporters;
  // preferred operators are those of its operators whose preconditions already hold.
  int relaxedPlan(std::vector<int>* preferred) {
    int count = 0;
    stack_.clear();
    stack_.push_back(goalFact_);
    touchedFacts_.clear();
    touchedOps_.clear();
    while (!stack_.empty()) {
      const int fact = stack_.back();
      stack_.pop_back();
      if (factMarked_[fact] != 0 || factCost_[fact] == 0) continue;
      factMarked_[fact] = 1;
      touchedFacts_.push_back(fact);
      const int unary = supporter_[fact];
      const int op = source_[unary];
      if (op >= 0 && marked_[op] == 0) {
        marked_[op] = 1;
        touchedOps_.push_back(op);
        ++count;
        if (preferred != nullptr && operatorCost_[unary] == 0) preferred->push_back(op);
      }
      for (int i = preStart_[unary]; i < preStart_[unary + 1]; ++i) stack_.push_back(pre_[i]);
    }
    for (const int fact : touchedFacts_) factMarked_[fact] = 0;
    for (const int op : touchedOps_) marked_[op] = 0;
    if (preferred != nullptr) std::sort(preferred->begin(), preferred->end());
    return count;
  }

  static constexpr int kUnreachable = -1;

  const GroundTask& task_;
  Kind kind_;
  int goalFact_;
  std::vector<int> pre_, preStart_, effects_, effectStart_, source_;
  std::vector<int> consumers_, consumerStart_, unconditional_;
  std::vector<int> preCount_, factCost_, supporter_, unsatisfied_, operatorCost_;
  std::vector<std::vector<int>> buckets_;
  std::vector<int> stack_, touchedFacts_, touchedOps_;
  std::vector<std::uint8_t> marked_, factMarked_;
};

}  // namespace

const std::vector<std::string>& heuristicNames() {
  static const std::vector<std::string> names = {"ff", "add", "max", "blind"};
  return names;
}

std::unique_ptr<Heuristic> makeHeuristic(const std::string& name, const GroundTask& task) {
  if (name == "ff") return std::make_unique<RelaxedHeuristic>(task, RelaxedHeuristic::Kind::FF);
  if (name == "add") return std::make_unique<RelaxedHeuristic>(task, RelaxedHeuristic::Kind::Add);
  if (name == "max") return std::make_unique<RelaxedHeuristic>(task, RelaxedHeuristic::Kind::Max);
  if (name == "blind") return std::make_unique<BlindHeuristic>(task);
  throw InputError("unknown heuristic '" + name + "' (expected ff, add, max or blind)");
}

}  // namespace kaboum::symbolic
