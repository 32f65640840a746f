#include "kaboum/symbolic/landmarks.hpp"

#include <algorithm>
#include <iterator>

namespace kaboum::symbolic {
namespace {

// Relaxed reachability from `initial` using no unary operator that achieves `excluded`.
class RestrictedExploration {
 public:
  explicit RestrictedExploration(const RelaxedTask& relaxed)
      : relaxed_(relaxed),
        reached_(static_cast<std::size_t>(relaxed.factCount())),
        unsatisfied_(static_cast<std::size_t>(relaxed.unaryCount())) {}

  // Marks reachable facts; reached(fact) answers afterwards.
  void run(std::span<const int> initial, int excluded) {
    std::fill(reached_.begin(), reached_.end(), 0);
    for (int u = 0; u < relaxed_.unaryCount(); ++u) {
      unsatisfied_[static_cast<std::size_t>(u)] =
          static_cast<int>(relaxed_.preconditions(u).size());
    }
    queue_.clear();
    for (const int fact : initial) reach(fact, excluded);
    for (const int unary : relaxed_.unconditional()) fire(unary, excluded);
    for (std::size_t next = 0; next < queue_.size(); ++next) {
      for (const int unary : relaxed_.consumers(queue_[next])) {
        if (--unsatisfied_[static_cast<std::size_t>(unary)] == 0) fire(unary, excluded);
      }
    }
  }
  bool reached(int fact) const { return reached_[static_cast<std::size_t>(fact)] != 0; }

 private:
  void reach(int fact, int excluded) {
    if (fact == excluded || reached(fact)) return;
    reached_[static_cast<std::size_t>(fact)] = 1;
    queue_.push_back(fact);
  }
  void fire(int unary, int excluded) {
    const auto effects = relaxed_.effects(unary);
    if (std::find(effects.begin(), effects.end(), excluded) != effects.end()) return;
    for (const int fact : effects) reach(fact, excluded);
  }

  const RelaxedTask& relaxed_;
  std::vector<std::uint8_t> reached_;
  std::vector<int> unsatisfied_;
  std::vector<int> queue_;
};

// Unary operators that add each fact.
std::vector<std::vector<int>> achieversByFact(const RelaxedTask& relaxed) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(relaxed.factCount()));
  for (int u = 0; u < relaxed.unaryCount(); ++u) {
    for (const int fact : relaxed.effects(u)) out[static_cast<std::size_t>(fact)].push_back(u);
  }
  return out;
}

}  // namespace

int LandmarkGraph::find(int fact) const {
  const auto it = std::find(facts.begin(), facts.end(), fact);
  return it == facts.end() ? -1 : static_cast<int>(it - facts.begin());
}

LandmarkGraph findLandmarks(const RelaxedTask& relaxed) {
  LandmarkGraph graph;
  const std::vector<int> initial = relaxed.initialFacts();
  std::vector<std::uint8_t> initiallyTrue(static_cast<std::size_t>(relaxed.factCount()), 0);
  for (const int fact : initial) initiallyTrue[static_cast<std::size_t>(fact)] = 1;
  std::vector<int> landmarkOf(static_cast<std::size_t>(relaxed.factCount()), -1);
  const auto add = [&](int fact, bool goal) {
    int& id = landmarkOf[static_cast<std::size_t>(fact)];
    if (id < 0) {
      id = static_cast<int>(graph.facts.size());
      graph.facts.push_back(fact);
      graph.before.emplace_back();
      graph.goal.push_back(goal);
    }
    return id;
  };
  for (const int fact : relaxed.goalFacts()) add(fact, true);

  const auto achievers = achieversByFact(relaxed);
  RestrictedExploration exploration(relaxed);
  std::vector<int> shared, next;
  // graph.facts grows while it is scanned (indexed access)
  for (std::size_t l = 0; l < graph.facts.size(); ++l) {
    const int fact = graph.facts[l];
    if (initiallyTrue[static_cast<std::size_t>(fact)] != 0) continue;
    exploration.run(initial, fact);
    bool first = true;
    for (const int unary : achievers[static_cast<std::size_t>(fact)]) {
      const auto pre = relaxed.preconditions(unary);
      if (!std::all_of(pre.begin(), pre.end(), [&](int p) { return exploration.reached(p); })) {
        continue;
      }
      if (first) {
        shared.assign(pre.begin(), pre.end());
        first = false;
      } else {
        next.clear();
        std::set_intersection(shared.begin(), shared.end(), pre.begin(), pre.end(),
                              std::back_inserter(next));
        shared.swap(next);
      }
      if (shared.empty()) break;
    }
    if (first) continue;  // no first achiever: the goal is unreachable
    for (const int pre : shared) {
      const int before = add(pre, false);
      auto& list = graph.before[l];
      if (std::find(list.begin(), list.end(), before) == list.end()) list.push_back(before);
    }
  }
  return graph;
}

LandmarkCountHeuristic::LandmarkCountHeuristic(const GroundTask& task)
    : relaxed_(task),
      graph_(findLandmarks(relaxed_)),
      factTrue_(static_cast<std::size_t>(relaxed_.factCount()), 0),
      needed_(graph_.facts.size(), 0) {
  const auto byFact = achieversByFact(relaxed_);
  for (const int fact : graph_.facts) achievers_.push_back(byFact[static_cast<std::size_t>(fact)]);
}

int LandmarkCountHeuristic::evaluate(StateView state, std::vector<int>* preferred) {
  if (preferred != nullptr) preferred->clear();
  relaxed_.stateFacts(state, stateFacts_);
  for (const int fact : stateFacts_) factTrue_[static_cast<std::size_t>(fact)] = 1;
  const auto isTrue = [&](int landmark) {
    return factTrue_[static_cast<std::size_t>(graph_.facts[static_cast<std::size_t>(landmark)])] !=
           0;
  };
  const auto markNeeded = [&](int landmark) {
    if (needed_[static_cast<std::size_t>(landmark)] != 0 || isTrue(landmark)) return;
    needed_[static_cast<std::size_t>(landmark)] = 1;
    neededList_.push_back(landmark);
    stack_.push_back(landmark);
  };
  neededList_.clear();
  stack_.clear();
  for (std::size_t l = 0; l < graph_.facts.size(); ++l) {
    if (graph_.goal[l]) markNeeded(static_cast<int>(l));
  }
  while (!stack_.empty()) {
    const int landmark = stack_.back();
    stack_.pop_back();
    for (const int before : graph_.before[static_cast<std::size_t>(landmark)]) markNeeded(before);
  }
  if (preferred != nullptr) {
    for (const int landmark : neededList_) {
      const auto& before = graph_.before[static_cast<std::size_t>(landmark)];
      if (std::any_of(before.begin(), before.end(),
                      [&](int b) { return needed_[static_cast<std::size_t>(b)] != 0; })) {
        continue;
      }
      for (const int unary : achievers_[static_cast<std::size_t>(landmark)]) {
        const auto pre = relaxed_.preconditions(unary);
        const int op = relaxed_.source(unary);
        if (op >= 0 && std::all_of(pre.begin(), pre.end(), [&](int p) {
              return factTrue_[static_cast<std::size_t>(p)] != 0;
            })) {
          preferred->push_back(op);
        }
      }
    }
    std::sort(preferred->begin(), preferred->end());
    preferred->erase(std::unique(preferred->begin(), preferred->end()), preferred->end());
  }
  for (const int fact : stateFacts_) factTrue_[static_cast<std::size_t>(fact)] = 0;
  for (const int landmark : neededList_) needed_[static_cast<std::size_t>(landmark)] = 0;
  return static_cast<int>(neededList_.size());
}

}  // namespace kaboum::symbolic
