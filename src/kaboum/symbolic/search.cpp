#include "kaboum/symbolic/search.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <tuple>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/heuristic.hpp"
#include "kaboum/symbolic/packed_set.hpp"
#include "kaboum/symbolic/state.hpp"

namespace kaboum::symbolic {
namespace {

using StateId = std::uint32_t;
constexpr StateId kNoState = PackedSet::kMissing;

// Thrown inside a search when a limit is reached; turned into the matching status.
struct LimitReached {
  PlannerStatus status;
};

// Finds applicable operators: each operator is watched by its rarest positive precondition atom,
// so only operators whose watched atom holds are tested.
class SuccessorGenerator {
 public:
  explicit SuccessorGenerator(const GroundTask& task) {
    std::vector<std::size_t> uses(task.atomNames.size(), 0);
    for (const Operator& op : task.operators) {
      for (const AtomId atom : op.precondition.positive) ++uses[atom];
    }
    watchers_.resize(task.atomNames.size());
    for (std::size_t o = 0; o < task.operators.size(); ++o) {
      const auto& positive = task.operators[o].precondition.positive;
      if (positive.empty()) {
        unwatched_.push_back(static_cast<int>(o));
        continue;
      }
      const AtomId watched = *std::min_element(
          positive.begin(), positive.end(), [&](AtomId a, AtomId b) { return uses[a] < uses[b]; });
      watchers_[watched].push_back(static_cast<int>(o));
    }
  }

  void applicable(const GroundTask& task, StateEvaluator& evaluator, StateView state,
                  std::vector<int>& out) const {
    out.clear();
    const auto atoms = static_cast<AtomId>(watchers_.size());
    for (AtomId atom = 0; atom < atoms; ++atom) {
      if (watchers_[atom].empty() || !state.atom(atom)) continue;
      for (const int op : watchers_[atom]) {
        if (evaluator.holds(task.operators[op].precondition, state)) out.push_back(op);
      }
    }
    for (const int op : unwatched_) {
      if (evaluator.holds(task.operators[op].precondition, state)) out.push_back(op);
    }
    std::sort(out.begin(), out.end());
  }

 private:
  std::vector<std::vector<int>> watchers_;
  std::vector<int> unwatched_;
};

class Search {
 public:
  Search(const GroundTask& task, AttachmentRuntime& attachments, const SearchOptions& options)
      : task_(task),
        options_(options),
        evaluator_(task, attachments),
        generator_(task),
        registry_(evaluator_.layout().words()),
        scratch_(evaluator_.layout().words()),
        deadline_(options.limits) {}

  SearchResult run() {
    static const std::map<std::string, void (Search::*)()> kModes = {
        {"dfs", &Search::depthFirst},
        {"bfs", &Search::breadthFirst},
        {"ids", &Search::iterativeDeepening},
        {"gbfs", &Search::greedyBestFirst},
        {"astar", &Search::astar}};
    const auto mode = kModes.find(options_.mode);
    if (mode == kModes.end()) {
      throw InputError("unknown search mode '" + options_.mode +
                       "' (expected dfs, bfs, ids, gbfs or astar)");
    }
    if (options_.mode == "gbfs" || options_.mode == "astar") {
      heuristics_.push_back(makeHeuristic(options_.heuristic, task_));
    }
    if (options_.mode == "gbfs" && options_.landmarks && options_.heuristic != "lmcount") {
      heuristics_.push_back(makeHeuristic("lmcount", task_));
    }
    try {
      evaluator_.initialState(scratch_);
      const StateId initial = insert().first;
      parent_[initial] = kNoState;
      if (!task_.goal.reachable) {
        result_.status = PlannerStatus::Unsolvable;
      } else if (evaluator_.isGoal(view(initial))) {
        solved(initial);
      } else {
        (this->*(mode->second))();
      }
    } catch (const LimitReached& limit) {
      result_.status = limit.status;
    } catch (const std::bad_alloc&) {
      result_.status = PlannerStatus::MemoryLimit;
    }
    auto& stats = result_.statistics;
    stats.storedStates = registry_.size();
    stats.memoryBytes = memoryBytes();
    stats.seconds = deadline_.elapsedSeconds();
    return std::move(result_);
  }

 private:
  StateView view(StateId id) const { return evaluator_.view(registry_.get(id)); }

  std::size_t memoryBytes() const {
    return registry_.bytes() + parent_.capacity() * sizeof(StateId) +
           (op_.capacity() + g_.capacity() + h_.capacity()) * sizeof(int) + openBytes_;
  }

  // Inserts the state in scratch_; new states get node slots.
  std::pair<StateId, bool> insert() {
    const auto [id, isNew] = registry_.insert(scratch_);
    if (isNew) {
      parent_.push_back(kNoState);
      op_.push_back(-1);
      g_.push_back(0);
      h_.push_back(-1);
    }
    return {id, isNew};
  }

  void checkLimits() {
    if (const auto limit = deadline_.reached(result_.statistics.expanded, memoryBytes())) {
      throw LimitReached{*limit};
    }
  }

  // Expands `state`: fills successors_ with (operator, successor) pairs, in operator order.
  void expand(StateId state) {
    checkLimits();
    ++result_.statistics.expanded;
    generator_.applicable(task_, evaluator_, view(state), applicable_);
    successors_.clear();
    for (const int op : applicable_) {
      // view() is taken again after each insert: the registry may have moved its storage.
      if (!evaluator_.apply(task_.operators[op], view(state), scratch_)) continue;
      ++result_.statistics.generated;
      const auto [successor, isNew] = insert();
      successors_.push_back({op, successor, isNew});
    }
  }

  void link(StateId child, StateId parent, int op) {
    parent_[child] = parent;
    op_[child] = op;
    g_[child] = g_[parent] + 1;
  }

  void solved(StateId goal) {
    result_.status = PlannerStatus::Solved;
    for (StateId s = goal; parent_[s] != kNoState; s = parent_[s]) result_.plan.push_back(op_[s]);
    std::reverse(result_.plan.begin(), result_.plan.end());
  }

  // The first heuristic's value of `state`, computed once.
  int evaluate(StateId state) {
    if (h_[state] < 0) {
      ++result_.statistics.evaluated;
      h_[state] = heuristics_.front()->evaluate(view(state), nullptr);
      if (h_[state] == Heuristic::kDeadEnd) ++result_.statistics.deadEnds;
    }
    return h_[state];
  }

  // Breadth-first search: optimal in plan length; goal test on generation.
  void breadthFirst() {
    std::deque<StateId> open{0};
    while (!open.empty()) {
      const StateId state = open.front();
      open.pop_front();
      expand(state);
      for (const auto& [op, successor, isNew] : successors_) {
        if (!isNew) continue;
        link(successor, state, op);
        if (evaluator_.isGoal(view(successor))) return solved(successor);
        open.push_back(successor);
      }
      openBytes_ = open.size() * sizeof(StateId);
    }
  }

  // Depth-first graph search: follows the first applicable operator, never revisits a state.
  void depthFirst() {
    std::vector<StateId> open{0};
    std::vector<StateId> children;
    while (!open.empty()) {
      const StateId state = open.back();
      open.pop_back();
      expand(state);
      children.clear();
      for (const auto& [op, successor, isNew] : successors_) {
        if (!isNew) continue;
        link(successor, state, op);
        if (evaluator_.isGoal(view(successor))) return solved(successor);
        children.push_back(successor);
      }
      open.insert(open.end(), children.rbegin(), children.rend());
      openBytes_ = open.capacity() * sizeof(StateId);
    }
  }

  // Iterative deepening: depth-bounded DFS with bounds 0, 1, 2, ...; a state is re-entered in an
  // iteration only on a strictly shorter path, so plans are shortest.
  void iterativeDeepening() {
    std::vector<int> bestDepth;
    struct Frame {
      StateId state;
      std::size_t next;
    };
    std::vector<Frame> stack;
    std::vector<std::vector<std::pair<int, StateId>>> children;
    for (int bound = 1;; ++bound) {
      ++result_.statistics.iterations;
      bestDepth.assign(registry_.size(), std::numeric_limits<int>::max());
      bestDepth[0] = 0;
      bool cutOff = false;
      stack.assign(1, {0, 0});
      children.resize(std::max<std::size_t>(children.size(), static_cast<std::size_t>(bound) + 1));
      expandInto(0, children[0]);
      while (!stack.empty()) {
        Frame& frame = stack.back();
        const auto depth = static_cast<int>(stack.size()) - 1;
        auto& list = children[static_cast<std::size_t>(depth)];
        if (frame.next >= list.size()) {
          stack.pop_back();
          continue;
        }
        const auto [op, child] = list[frame.next++];
        if (child >= bestDepth.size())
          bestDepth.resize(registry_.size(), std::numeric_limits<int>::max());
        if (bestDepth[child] <= depth + 1) continue;
        bestDepth[child] = depth + 1;
        parent_[child] = frame.state;
        op_[child] = op;
        g_[child] = depth + 1;
        if (evaluator_.isGoal(view(child))) return solved(child);
        if (depth + 1 >= bound) {
          cutOff = true;
          continue;
        }
        stack.push_back({child, 0});
        expandInto(child, children[static_cast<std::size_t>(depth) + 1]);
      }
      if (!cutOff) return;  // the whole reachable space is shallower than the bound
    }
  }

  void expandInto(StateId state, std::vector<std::pair<int, StateId>>& out) {
    expand(state);
    out.clear();
    for (const auto& [op, successor, isNew] : successors_) {
      if (successor != state) out.push_back({op, successor});
    }
  }

  // Min-queue entry; `order` breaks ties first-in first-out so results are deterministic.
  struct Entry {
    int key1;
    int key2;
    std::size_t order;
    StateId state;
    bool operator>(const Entry& other) const {
      return std::tie(key1, key2, order) > std::tie(other.key1, other.key2, other.order);
    }
  };
  using Queue = std::priority_queue<Entry, std::vector<Entry>, std::greater<>>;

  // Evaluates `state` with every heuristic into values_; the union of their preferred operators
  // goes into `preferred` (if non-null) and is flagged in isPreferred_. False at a dead end.
  bool evaluateAll(StateId state, std::vector<int>* preferred) {
    values_.clear();
    if (preferred != nullptr) preferred->clear();
    for (const auto& heuristic : heuristics_) {
      ++result_.statistics.evaluated;
      const int h = heuristic->evaluate(view(state), preferred ? &ownPreferred_ : nullptr);
      values_.push_back(h);
      if (h == Heuristic::kDeadEnd) break;
      if (preferred == nullptr) continue;
      for (const int op : ownPreferred_) {
        if (isPreferred_[op] == 0) preferred->push_back(op);
        isPreferred_[op] = 1;
      }
    }
    if (values_.back() != Heuristic::kDeadEnd) return true;
    ++result_.statistics.deadEnds;
    if (preferred != nullptr) {
      for (const int op : *preferred) isPreferred_[op] = 0;
      preferred->clear();
    }
    return false;
  }

  // Greedy best-first search with two open lists per heuristic (all states; states reached by a
  // preferred operator), alternated, with the preferred lists boosted whenever a heuristic value
  // improves (as in Fast Downward's eager/lazy greedy search and LAMA). Lazy: successors are
  // queued with the parent's values and evaluated when expanded.
  void greedyBestFirst() {
    const std::size_t queues = 2 * heuristics_.size();
    std::vector<Queue> open(queues);
    std::vector<int> priority(queues, 0);
    std::vector<std::uint8_t> closed;
    std::vector<int> preferred;
    isPreferred_.assign(task_.operators.size(), 0);
    std::size_t order = 0;
    const bool usePreferred = options_.preferredOperators;
    if (!evaluateAll(0, nullptr)) return;
    std::vector<int> best = values_;
    for (std::size_t i = 0; i < heuristics_.size(); ++i) open[2 * i].push({best[i], 0, order++, 0});
    while (true) {
      std::size_t which = queues;
      for (std::size_t q = 0; q < queues; ++q) {
        if (!open[q].empty() && (which == queues || priority[q] < priority[which])) which = q;
      }
      if (which == queues) return;
      ++priority[which];
      const StateId state = open[which].top().state;
      open[which].pop();
      if (state < closed.size() && closed[state] != 0) continue;
      if (closed.size() <= state) closed.resize(registry_.size(), 0);
      closed[state] = 1;
      if (!evaluateAll(state, usePreferred ? &preferred : nullptr)) continue;
      bool progress = false;
      for (std::size_t i = 0; i < best.size(); ++i) {
        if (values_[i] < best[i]) {
          best[i] = values_[i];
          progress = true;
        }
      }
      if (progress) {
        for (std::size_t q = 1; q < queues; q += 2) priority[q] -= 1000;
      }
      parentValues_ = values_;
      expand(state);
      for (const auto& [op, successor, isNew] : successors_) {
        if (!isNew) continue;
        link(successor, state, op);
        if (evaluator_.isGoal(view(successor))) {
          for (const int p : preferred) isPreferred_[p] = 0;
          return solved(successor);
        }
        if (!options_.lazy && !evaluateAll(successor, nullptr)) continue;
        const std::vector<int>& keys = options_.lazy ? parentValues_ : values_;
        const bool viaPreferred = usePreferred && isPreferred_[op] != 0;
        for (std::size_t i = 0; i < heuristics_.size(); ++i) {
          open[2 * i].push({keys[i], 0, order++, successor});
          if (viaPreferred) open[2 * i + 1].push({keys[i], 0, order++, successor});
        }
      }
      for (const int p : preferred) isPreferred_[p] = 0;
      openBytes_ = closed.capacity();
      for (const Queue& queue : open) openBytes_ += queue.size() * sizeof(Entry);
    }
  }

  // A*: f = g + h, ties broken by smaller h; states are reopened when reached more cheaply.
  // Optimal with an admissible heuristic (max, blind).
  void astar() {
    Queue open;
    std::size_t order = 0;
    const int h0 = evaluate(0);
    if (h0 == Heuristic::kDeadEnd) return;
    open.push({h0, h0, order++, 0});
    std::vector<std::uint8_t> closed;
    while (!open.empty()) {
      const Entry entry = open.top();
      open.pop();
      const StateId state = entry.state;
      if (entry.key1 - entry.key2 != g_[state]) continue;  // stale entry
      if (closed.size() <= state) closed.resize(registry_.size(), 0);
      if (evaluator_.isGoal(view(state))) return solved(state);
      if (closed[state] != 0) ++result_.statistics.reopened;
      closed[state] = 1;
      expand(state);
      for (const auto& [op, successor, isNew] : successors_) {
        const int g = g_[state] + 1;
        if (!isNew && (successor == 0 || g >= g_[successor])) continue;
        link(successor, state, op);
        const int h = evaluate(successor);
        if (h == Heuristic::kDeadEnd) continue;
        open.push({g + h, h, order++, successor});
      }
      openBytes_ = open.size() * sizeof(Entry) + closed.capacity();
    }
  }

  struct Successor {
    int op;
    StateId state;
    bool isNew;
  };

  const GroundTask& task_;
  const SearchOptions& options_;
  StateEvaluator evaluator_;
  SuccessorGenerator generator_;
  PackedSet registry_;
  std::vector<std::uint64_t> scratch_;
  Deadline deadline_;
  std::vector<std::unique_ptr<Heuristic>> heuristics_;
  std::vector<int> values_, parentValues_, ownPreferred_;
  std::vector<std::uint8_t> isPreferred_;
  std::vector<StateId> parent_;
  std::vector<int> op_, g_, h_;
  std::vector<int> applicable_;
  std::vector<Successor> successors_;
  std::size_t openBytes_ = 0;
  SearchResult result_;
};

}  // namespace

const std::vector<std::string>& searchModes() {
  static const std::vector<std::string> modes = {"dfs", "bfs", "ids", "gbfs", "astar"};
  return modes;
}

SearchResult search(const GroundTask& task, AttachmentRuntime& attachments,
                    const SearchOptions& options) {
  return Search(task, attachments, options).run();
}

std::string formatPlan(const GroundTask& task, const std::vector<int>& plan) {
  std::string out;
  for (const int op : plan) out += "(" + task.operators[op].name + ")\n";
  return out;
}

}  // namespace kaboum::symbolic
