#include "kaboum/symbolic/heuristic.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/landmarks.hpp"
#include "kaboum/symbolic/relaxation.hpp"

namespace kaboum::symbolic {
namespace {

class BlindHeuristic : public Heuristic {
 public:
  explicit BlindHeuristic(const GroundTask& task) : task_(task) {}
  int evaluate(StateView, std::vector<int>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    return task_.goal.reachable ? 0 : kDeadEnd;
  }
  bool admissible() const override { return true; }

 private:
  const GroundTask& task_;
};

// Generalized Dijkstra over the unary relaxed operators with precondition counters and a bucket
// queue (Bonet & Geffner's h_max/h_add; FF's relaxed plan from h_add's best supporters).
class RelaxedHeuristic : public Heuristic {
 public:
  enum class Kind { Max, Add, FF };

  RelaxedHeuristic(const GroundTask& task, Kind kind) : relaxed_(task), kind_(kind) {
    const auto facts = static_cast<std::size_t>(relaxed_.factCount());
    const auto unaries = static_cast<std::size_t>(relaxed_.unaryCount());
    factCost_.resize(facts);
    supporter_.resize(facts);
    unsatisfied_.resize(unaries);
    for (int u = 0; u < relaxed_.unaryCount(); ++u) {
      preCount_.push_back(static_cast<int>(relaxed_.preconditions(u).size()));
    }
    operatorCost_.resize(unaries);
    marked_.assign(task.operators.size(), 0);
    excluded_.assign(task.operators.size(), 0);
    factMarked_.assign(facts, 0);
  }

  bool admissible() const override { return kind_ == Kind::Max; }
  bool excludes() const override { return true; }
  void exclude(int op, bool excluded) override {
    excluded_[static_cast<std::size_t>(op)] = excluded ? 1 : 0;
  }

  int evaluate(StateView state, std::vector<int>* preferred) override {
    if (preferred != nullptr) preferred->clear();
    explore(state);
    const int h = factCost_[relaxed_.goalFact()];
    if (h == kInfinity) return kDeadEnd;
    if (kind_ != Kind::FF) return h;
    return relaxedPlan(preferred);
  }

 private:
  static constexpr int kInfinity = std::numeric_limits<int>::max() / 4;

  void reach(int fact, int cost, int unary) {
    if (cost >= factCost_[fact]) return;
    factCost_[fact] = cost;
    supporter_[fact] = unary;
    if (static_cast<std::size_t>(cost) >= buckets_.size()) buckets_.resize(cost + 1);
    buckets_[cost].push_back(fact);
  }

  void fire(int unary) {
    const int op = relaxed_.source(unary);
    if (op >= 0 && excluded_[static_cast<std::size_t>(op)] != 0) return;
    const int cost = operatorCost_[unary] + (relaxed_.source(unary) >= 0 ? 1 : 0);
    for (const int fact : relaxed_.effects(unary)) reach(fact, cost, unary);
  }

  void explore(StateView state) {
    std::fill(factCost_.begin(), factCost_.end(), kInfinity);
    std::fill(operatorCost_.begin(), operatorCost_.end(), 0);
    std::copy(preCount_.begin(), preCount_.end(), unsatisfied_.begin());
    relaxed_.stateFacts(state, stateFacts_);
    for (const int fact : stateFacts_) reach(fact, 0, -1);
    for (const int unary : relaxed_.unconditional()) fire(unary);
    // Bucket queue over integer costs; the current bucket may grow while it is scanned.
    // (indexed access: reach() may grow buckets_ and move the buckets)
    bool goalReached = false;
    for (std::size_t cost = 0; cost < buckets_.size() && !goalReached; ++cost) {
      for (std::size_t k = 0; k < buckets_[cost].size(); ++k) {
        const int fact = buckets_[cost][k];
        if (static_cast<std::size_t>(factCost_[fact]) != cost) continue;
        if (fact == relaxed_.goalFact()) {
          goalReached = true;
          break;
        }
        const int c = static_cast<int>(cost);
        for (const int unary : relaxed_.consumers(fact)) {
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
    stack_.push_back(relaxed_.goalFact());
    touchedFacts_.clear();
    touchedOps_.clear();
    while (!stack_.empty()) {
      const int fact = stack_.back();
      stack_.pop_back();
      if (factMarked_[fact] != 0 || factCost_[fact] == 0) continue;
      factMarked_[fact] = 1;
      touchedFacts_.push_back(fact);
      const int unary = supporter_[fact];
      const int op = relaxed_.source(unary);
      if (op >= 0 && marked_[op] == 0) {
        marked_[op] = 1;
        touchedOps_.push_back(op);
        ++count;
        if (preferred != nullptr && operatorCost_[unary] == 0) preferred->push_back(op);
      }
      for (const int pre : relaxed_.preconditions(unary)) stack_.push_back(pre);
    }
    for (const int fact : touchedFacts_) factMarked_[fact] = 0;
    for (const int op : touchedOps_) marked_[op] = 0;
    if (preferred != nullptr) std::sort(preferred->begin(), preferred->end());
    return count;
  }

  RelaxedTask relaxed_;
  Kind kind_;
  std::vector<int> preCount_, factCost_, supporter_, unsatisfied_, operatorCost_;
  std::vector<std::vector<int>> buckets_;
  std::vector<int> stack_, touchedFacts_, touchedOps_, stateFacts_;
  std::vector<std::uint8_t> marked_, excluded_, factMarked_;
};

}  // namespace

const std::vector<std::string>& heuristicNames() {
  static const std::vector<std::string> names = {"ff", "add", "max", "blind", "lmcount"};
  return names;
}

std::unique_ptr<Heuristic> makeHeuristic(const std::string& name, const GroundTask& task) {
  if (name == "ff") return std::make_unique<RelaxedHeuristic>(task, RelaxedHeuristic::Kind::FF);
  if (name == "add") return std::make_unique<RelaxedHeuristic>(task, RelaxedHeuristic::Kind::Add);
  if (name == "max") return std::make_unique<RelaxedHeuristic>(task, RelaxedHeuristic::Kind::Max);
  if (name == "blind") return std::make_unique<BlindHeuristic>(task);
  if (name == "lmcount") return std::make_unique<LandmarkCountHeuristic>(task);
  throw InputError("unknown heuristic '" + name + "' (expected ff, add, max, blind or lmcount)");
}

}  // namespace kaboum::symbolic
