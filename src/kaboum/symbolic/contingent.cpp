#include "kaboum/symbolic/contingent.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/heuristic.hpp"

namespace kaboum::symbolic {
namespace {

struct BeliefHash {
  std::size_t operator()(const Belief& belief) const {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint32_t w : belief) h = (h ^ w) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

struct LimitReached {
  PlannerStatus status;
};

// Symbolic plans refined before the search with effect applicators takes over (symbolicFirst),
// and the share of the time limit they may take.
constexpr std::size_t kMaxRefinements = 32;
constexpr double kRefiningShare = 0.5;

enum class OrMode { Greedy, AStar, BreadthFirst, DepthFirst, IterativeDeepening };

OrMode orMode(const std::string& name) {
  const std::vector<std::string>& names = contingentSearchModes();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    throw InputError("unknown contingent search mode '" + name +
                     "' (expected gbfs, astar, bfs, dfs or ids)");
  }
  return static_cast<OrMode>(it - names.begin());
}

// Whether a condition (a precondition, a conditional effect's condition, the goal) or a numeric
// assignment reads a fluent that an effect applicator writes. If none does, the symbolic part of a
// search does not depend on the values effect applicators compute.
bool readsAttachmentValues(const GroundTask& task) {
  std::vector<bool> written(task.fluentNames.size(), false);
  for (const GroundModuleCall& call : task.moduleCalls) {
    for (const FluentId f : call.writes) written[static_cast<std::size_t>(f)] = true;
  }
  const auto isWritten = [&](FluentId f) { return written[static_cast<std::size_t>(f)]; };
  const auto codeReads = [&](const NumericCode& code) {
    return std::any_of(code.code.begin(), code.code.end(), [&](const NumericCode::Instruction& i) {
      return i.op == NumericCode::Op::Load && isWritten(i.fluent);
    });
  };
  const auto conditionReads = [&](const Condition& c) {
    return std::any_of(c.fluentTests.begin(), c.fluentTests.end(),
                       [&](const FluentTest& t) { return isWritten(t.fluent); }) ||
           std::any_of(
               c.numericTests.begin(), c.numericTests.end(),
               [&](const NumericTest& t) { return codeReads(t.lhs) || codeReads(t.rhs); }) ||
           std::any_of(c.moduleChecks.begin(), c.moduleChecks.end(), [&](const ModuleCheck& m) {
             const GroundModuleCall& call = task.moduleCalls[static_cast<std::size_t>(m.call)];
             return std::any_of(call.reads.begin(), call.reads.end(), isWritten);
           });
  };
  const auto effectReads = [&](const EffectList& effect) {
    return std::any_of(effect.assignments.begin(), effect.assignments.end(),
                       [&](const Assignment& a) { return !a.objectValued && codeReads(a.value); });
  };
  for (const Operator& op : task.operators) {
    if (conditionReads(op.precondition) || effectReads(op.effect)) return true;
    for (const ConditionalEffect& conditional : op.conditional) {
      if (effectReads(conditional.effect) ||
          std::any_of(conditional.disjuncts.begin(), conditional.disjuncts.end(), conditionReads)) {
        return true;
      }
    }
  }
  return conditionReads(task.goal.conjunction) ||
         std::any_of(task.goal.clauses.begin(), task.goal.clauses.end(),
                     [&](const std::vector<Condition>& clause) {
                       return std::any_of(clause.begin(), clause.end(), conditionReads);
                     });
}

// A symbolic transition: a knowledge state's symbolicKey and an operator.
std::uint64_t transitionKey(std::uint64_t symbolic, int op) {
  return symbolic ^ (static_cast<std::uint64_t>(op) * 0x9e3779b97f4a7c15ull);
}

class AndOrSearch {
 public:
  // With `blocked` (symbolicOnly()), actions change knowledge states by their symbolic effects
  // alone (the values effect applicators write stay as they are), except the transitions
  // (transitionKey) in `blocked`, which are left out: the symbolic search of symbolicFirst.
  AndOrSearch(KnowledgeTask& task, const ContingentOptions& options,
              const std::unordered_set<std::uint64_t>* blocked = nullptr)
      : task_(task),
        options_(options),
        blocked_(blocked),
        mode_(orMode(options.mode)),
        heuristic_(makeHeuristic(mode_ == OrMode::Greedy || mode_ == OrMode::AStar
                                     ? options.heuristic
                                     : std::string("blind"),
                                 task.task())),
        deadline_(options.limits, clockPeriod(task)),
        nextProgress_(options.progressPeriod) {
    if (heuristic_->excludes()) learned_ = makeHeuristic(options.heuristic, task.task());
    const std::size_t operators = task.task().operators.size();
    failures_.assign(operators, 0);
    successes_.assign(operators, 0);
  }

  ContingentResult run() {
    ContingentResult result;
    try {
      result.plan.root = solve(intern(Belief(task_.initialBelief())), 0);
      result.status = result.plan.root >= 0 ? PlannerStatus::Solved : PlannerStatus::Unsolvable;
    } catch (const LimitReached& limit) {
      result.status = limit.status;
      result.plan.root = -1;
    }
    if (result.status == PlannerStatus::Solved) result.plan.nodes = std::move(nodes_);
    stats_.beliefs = beliefs_.size();
    stats_.worlds = task_.worldCount();
    stats_.seconds = deadline_.elapsedSeconds();
    result.statistics = stats_;
    return result;
  }

 private:
  // Result of one action: a tree of branches over the atoms it lets the agent observe.
  struct Outcome {
    AtomId atom = -1;      // -1: a leaf knowledge state or a value branch
    FluentId fluent = -1;  // value branch: (= fluent value)
    double value = 0.0;
    int belief = -1;
    int onTrue = -1;
    int onFalse = -1;
  };
  struct Candidate {
    int score = 0;
    int op = 0;
    std::uint32_t sample = 0;  // of its effect applicators
    // Its effect applicators (geometry) run when the search reaches it; `score` is its preview's.
    bool deferred = false;
    int root = 0;  // index into the candidate's outcomes
    std::vector<Outcome> outcomes;
  };

  // Knowledge states with the same sharing key (equal up to settled components, factored
  // knowledge) share one id, whose plan is that of the first one seen.
  // The symbolic search of symbolicFirst: effect applicators are not called.
  bool symbolicOnly() const { return blocked_ != nullptr; }

  int intern(Belief&& belief) {
    if (task_.factored()) task_.sharingKey(belief, key_);
    const bool keyed = task_.factored() && key_ != belief;
    const auto [it, added] = ids_.try_emplace(keyed ? std::move(key_) : std::move(belief),
                                              static_cast<int>(beliefs_.size()));
    if (added) {
      if (keyed) representatives_.push_back(std::move(belief));
      beliefs_.push_back(keyed ? &representatives_.back() : &it->first);
      solved_.push_back(-1);
      state_.push_back(kOpen);
    }
    return it->second;
  }

  // Worst-world value of `belief`. Once actions that call effect applicators have failed and never
  // succeeded (geometrically infeasible so far), the value is that of a relaxation without them,
  // so that the search heads for what the geometry allows (bottles through the shared region when
  // one robot cannot reach the goal); a state that relaxation cannot solve comes after all the
  // others (kUnlearned plus the full value). Dead ends are those of the full relaxation only.
  int heuristic(const Belief& belief) {
    const int full = worstValue(belief, *heuristic_, worldValue_);
    if (full == Heuristic::kDeadEnd || excluded_ == 0) return full;
    const int learned = worstValue(belief, *learned_, learnedValue_);
    return learned == Heuristic::kDeadEnd ? kUnlearned + full : learned;
  }

  int worstValue(const Belief& belief, Heuristic& estimate, std::vector<int>& cache) {
    int worst = 0;
    for (const std::uint32_t w : task_.heuristicWorlds(belief)) {
      if (w >= cache.size()) cache.resize(task_.worldCount(), -1);
      if (cache[w] < 0) {
        cache[w] = estimate.evaluate(task_.world(w), nullptr);
        ++stats_.evaluated;
      }
      worst = std::max(worst, cache[w]);
      if (worst == Heuristic::kDeadEnd) break;
    }
    return worst;
  }

  // Counts whether action `op`, which calls effect applicators, was feasible, and leaves it out of
  // the learned relaxation while it has only failed.
  void learn(int op, bool feasible) {
    if (!learned_) return;
    const auto o = static_cast<std::size_t>(op);
    const bool wasExcluded = failures_[o] > 0 && successes_[o] == 0;
    ++(feasible ? successes_ : failures_)[o];
    const bool excluded = failures_[o] > 0 && successes_[o] == 0;
    if (excluded == wasExcluded) return;
    learned_->exclude(op, excluded);
    excluded_ += excluded ? 1 : -1;
    learnedValue_.assign(learnedValue_.size(), -1);
  }

  // Splits `belief` eagerly on every atom the agent now knows whether (Figure 3.2's branch(φ))
  // and on every sensed value, one (= f value) branch per value the worlds allow.
  int outcome(Belief&& belief, std::vector<Outcome>& out) {
    const AtomId atom = task_.pendingObservation(belief);
    const int index = static_cast<int>(out.size());
    out.push_back({});
    FluentId fluent = -1;
    double value = 0.0;
    if (atom < 0 && !task_.pendingValue(belief, fluent, value)) {
      out[index].belief = intern(std::move(belief));
      return index;
    }
    Belief onTrue;
    Belief onFalse;
    if (atom >= 0) {
      task_.split(atom, belief, onTrue, onFalse);
    } else {
      task_.splitValue(fluent, value, belief, onTrue, onFalse);
    }
    out[index].atom = atom;
    out[index].fluent = fluent;
    out[index].value = value;
    const int t = outcome(std::move(onTrue), out);
    const int f = outcome(std::move(onFalse), out);
    out[index].onTrue = t;
    out[index].onFalse = f;
    return index;
  }

  int addNode(PlanTree::Node node) {
    nodes_.push_back(node);
    return static_cast<int>(nodes_.size()) - 1;
  }

  int solveOutcome(const std::vector<Outcome>& outcomes, int index, std::size_t depth) {
    const Outcome& o = outcomes[index];
    if (o.belief >= 0) return solve(o.belief, depth);
    const int t = solveOutcome(outcomes, o.onTrue, depth);
    if (t < 0) return -1;
    const int f = solveOutcome(outcomes, o.onFalse, depth);
    if (f < 0) return -1;
    PlanTree::Node node;
    node.kind = PlanTree::Node::Kind::Branch;
    node.atom = o.atom;
    node.fluent = o.fluent;
    node.value = o.value;
    node.next = t;
    node.onFalse = f;
    return addNode(node);
  }

  // Expansions between readings of the clock: every one when effect applicators (geometry) may
  // make a single step take long.
  static std::size_t clockPeriod(const KnowledgeTask& task) {
    for (std::size_t op = 0; op < task.task().operators.size(); ++op) {
      if (task.callsEffectApplicator(static_cast<int>(op))) return 1;
    }
    return kClockPeriod;
  }

  void checkLimits() {
    if (options_.progress && deadline_.elapsedSeconds() >= nextProgress_) {
      stats_.seconds = deadline_.elapsedSeconds();
      stats_.beliefs = beliefs_.size();
      stats_.worlds = task_.worldCount();
      options_.progress(stats_);
      nextProgress_ = stats_.seconds + options_.progressPeriod;
    }
    const std::size_t bytes = task_.worldCount() * 8 * 4 + beliefs_.size() * 64;
    if (const auto limit = deadline_.reached(stats_.expanded, bytes)) throw LimitReached{*limit};
  }

  // Applies `op` to knowledge state `id`, effect applicators included, into `candidate` with its
  // outcome tree and worst-world heuristic value. False if infeasible, a no-op or a relaxed dead
  // end.
  bool evaluate(int op, std::uint32_t sample, int id, Candidate& candidate) {
    const Belief& belief = *beliefs_[id];
    Belief next;
    bool feasible = true;
    if (symbolicOnly()) {
      task_.preview(op, belief, next);
    } else {
      feasible = task_.apply(op, belief, next, sample);
      if (task_.callsEffectApplicator(op)) learn(op, feasible);
    }
    if (!feasible || next == belief) return false;
    ++stats_.generated;
    candidate.op = op;
    candidate.sample = sample;
    candidate.deferred = false;
    candidate.outcomes.clear();
    candidate.root = outcome(std::move(next), candidate.outcomes);
    candidate.score = 0;
    for (const Outcome& o : candidate.outcomes) {
      if (o.belief >= 0)
        candidate.score = std::max(candidate.score, heuristic(*beliefs_[o.belief]));
    }
    if (candidate.score == Heuristic::kDeadEnd) {
      ++stats_.deadEnds;
      return false;
    }
    return true;
  }

  // Applicable actions of knowledge state `id`; relaxed dead ends dropped. An action that calls
  // effect applicators is deferred: scored by its preview (its symbolic effects), its geometry
  // computed only when the search reaches it, as a lazy search evaluates successors, once per
  // geometric sample (ContingentOptions::samples). The others come with their outcome trees;
  // sensing actions (outcomes that branch) first, then by score.
  std::vector<Candidate> expand(int id) {
    const Belief& belief = *beliefs_[id];
    std::vector<Candidate> candidates;
    Belief preview;
    const bool anyBlocked = blocked_ != nullptr && !blocked_->empty();
    const std::uint64_t symbolic = anyBlocked ? task_.symbolicKey(belief) : 0;
    for (std::size_t op = 0; op < task_.task().operators.size(); ++op) {
      const int o = static_cast<int>(op);
      if (!task_.applicable(o, belief)) continue;
      if (anyBlocked && blocked_->count(transitionKey(symbolic, o)) > 0) continue;
      Candidate candidate;
      if (!symbolicOnly() && task_.callsEffectApplicator(o)) {
        task_.preview(o, belief, preview);
        candidate.op = o;
        candidate.deferred = true;
        candidate.score = heuristic(preview);
        if (candidate.score == Heuristic::kDeadEnd) {
          ++stats_.deadEnds;
          continue;
        }
        for (std::uint32_t sample = 0; sample < options_.samples; ++sample) {
          candidates.push_back(candidate);
          candidates.back().sample = sample;
        }
      } else if (evaluate(o, 0, id, candidate)) {
        candidates.push_back(std::move(candidate));
      }
    }
    // Splitting only adds knowledge, so a plan for the unsplit state also works in every branch.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) {
                       const bool aSenses = a.outcomes.size() > 1;
                       const bool bSenses = b.outcomes.size() > 1;
                       if (aSenses != bSenses) return aSenses;
                       return a.score < b.score;
                     });
    return candidates;
  }

  int actionNode(int op, std::uint32_t sample, int next) {
    PlanTree::Node node;
    node.kind = PlanTree::Node::Kind::Action;
    node.op = op;
    node.sample = sample;
    node.next = next;
    return addNode(node);
  }

  // Greedy best-first search from knowledge state `root` until it finds a goal, an already solved
  // state, or a sensing action every branch of which is solved (recursively). Returns the plan
  // node of `root`, or -1; every state on the found path is recorded as solved (shared later).
  int solve(int root, std::size_t depth) {
    if (solved_[root] >= 0) {
      ++stats_.reused;
      return solved_[root];
    }
    if (state_[root] != kOpen || depth > options_.maxDepth) return -1;
    struct SearchNode {
      int belief;  // -1 until a deferred action is evaluated
      int parent;
      int op;
      std::uint32_t sample;
      long steps;  // actions from `root`
    };
    std::vector<SearchNode> nodes;
    state_[root] = kOnPath;
    std::size_t found = 0;
    int ending = -1;
    // Ends the search at node `index` with the plan node `next` after it.
    const auto finish = [&](std::size_t index, int next) {
      found = index;
      ending = next;
    };
    // ids: depth-first searches to 1, 2, … actions from `root`, until one finds a plan or none is
    // cut short by its bound; the other modes search once, unbounded.
    const bool deepening = mode_ == OrMode::IterativeDeepening;
    for (long bound = deepening ? 1 : std::numeric_limits<long>::max(); ending < 0; ++bound) {
      bool cut = false;
      nodes.assign(1, {root, -1, -1, 0, 0});
      std::unordered_set<int> seen{root};
      // Times each symbolic transition (the parent's symbolicKey and the action) was generated.
      std::unordered_map<std::uint64_t, int> transitions;
      // Round, priority, node (ties: first in, first out). A transition generated before (from
      // another geometric state of the same symbolic state) waits for the next round: a new
      // geometric state is another sample of that transition, as the thesis's random-seed argument
      // gives (§6.1.2), tried once the untried transitions are used up, so the search stays
      // complete without enumerating geometric variants of one symbolic state.
      using Entry = std::tuple<int, long, std::size_t>;
      std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
      open.push({0, 0, 0});
      while (!open.empty() && ending < 0) {
        const std::size_t index = std::get<2>(open.top());
        open.pop();
        checkLimits();
        if (nodes[index].belief < 0) {
          const auto parent = static_cast<std::size_t>(nodes[index].parent);
          Candidate candidate;
          if (!evaluate(nodes[index].op, nodes[index].sample, nodes[parent].belief, candidate)) {
            continue;
          }
          if (candidate.outcomes.size() > 1) {
            const int rest = solveOutcome(candidate.outcomes, candidate.root, depth + 1);
            if (rest >= 0) finish(parent, actionNode(candidate.op, candidate.sample, rest));
            continue;
          }
          const int child = candidate.outcomes[0].belief;
          if (state_[child] != kOpen || !seen.insert(child).second) continue;
          nodes[index].belief = child;
        }
        const int id = nodes[index].belief;
        if (solved_[id] >= 0) {
          ++stats_.reused;
          finish(index, solved_[id]);
          break;
        }
        if (task_.isGoal(*beliefs_[id])) {
          finish(index, addNode({}));
          break;
        }
        ++stats_.expanded;
        const std::vector<Candidate> candidates = expand(id);
        const std::uint64_t symbolic = task_.symbolicKey(*beliefs_[id]);
        for (const Candidate& candidate : candidates) {
          if (candidate.deferred || candidate.outcomes.size() == 1) {
            const int child = candidate.deferred ? -1 : candidate.outcomes[0].belief;
            if (child >= 0 && (state_[child] != kOpen || !seen.insert(child).second)) continue;
            const long steps = nodes[index].steps + 1;
            int& generated = transitions[transitionKey(symbolic, candidate.op)];
            // ids bounds the round of a transition as it bounds the depth: an iteration tries at
            // most `bound` geometric variants of each symbolic transition, so that a shallow
            // iteration does not exhaust every geometric state within its depth.
            if (steps > bound || (deepening && generated >= bound)) {
              cut = true;
              continue;
            }
            nodes.push_back(
                {child, static_cast<int>(index), candidate.op, candidate.sample, steps});
            open.push({generated++, priority(steps, candidate.score, nodes.size() - 1),
                       nodes.size() - 1});
            continue;
          }
          const int rest = solveOutcome(candidate.outcomes, candidate.root, depth + 1);
          if (rest < 0) continue;
          finish(index, actionNode(candidate.op, candidate.sample, rest));
          break;
        }
      }
      if (!cut) break;
    }
    if (ending < 0) {
      state_[root] = kFailed;
      return -1;
    }
    state_[root] = kOpen;
    int next = ending;
    for (std::size_t i = found; i != 0; i = static_cast<std::size_t>(nodes[i].parent)) {
      if (solved_[nodes[i].belief] < 0) solved_[nodes[i].belief] = next;
      next = actionNode(nodes[i].op, nodes[i].sample, next);
    }
    solved_[root] = next;
    return next;
  }

  // Open-list key of a node `steps` actions from the search root, with heuristic value `score`,
  // the `index`-th generated: smallest first.
  long priority(long steps, int score, std::size_t index) const {
    switch (mode_) {
      case OrMode::Greedy:
        return score;
      case OrMode::AStar:
        return steps + score;
      case OrMode::BreadthFirst:
        return steps;
      case OrMode::DepthFirst:
      case OrMode::IterativeDeepening:
        return -static_cast<long>(index);
    }
    return score;
  }

  static constexpr std::size_t kClockPeriod = 64;  // expansions between readings of the clock
  static constexpr char kOpen = 0;
  static constexpr char kOnPath = 1;
  static constexpr char kFailed = 2;

  KnowledgeTask& task_;
  const ContingentOptions& options_;
  const std::unordered_set<std::uint64_t>* blocked_;  // not owned
  OrMode mode_;
  std::unique_ptr<Heuristic> heuristic_;
  std::unique_ptr<Heuristic> learned_;  // heuristic_ without the actions found infeasible
  std::vector<int> failures_;           // per operator: infeasible applications
  std::vector<int> successes_;          // per operator: feasible applications
  int excluded_ = 0;                    // operators left out of learned_
  std::vector<int> learnedValue_;       // per world: learned_'s value, -1 until computed
  static constexpr int kUnlearned = 1 << 16;
  Deadline deadline_;
  double nextProgress_;  // seconds
  std::unordered_map<Belief, int, BeliefHash> ids_;
  std::vector<const Belief*> beliefs_;
  std::deque<Belief> representatives_;  // of the ids whose key is not the knowledge state itself
  Belief key_;
  std::vector<int> solved_;  // plan node of each solved knowledge state, -1 otherwise
  std::vector<char> state_;
  std::vector<int> worldValue_;
  std::vector<PlanTree::Node> nodes_;
  ContingentStatistics stats_;
};

}  // namespace

std::vector<int> inDegrees(const PlanTree& plan) {
  std::vector<int> degree(plan.nodes.size(), 0);
  std::vector<int> stack{plan.root};
  degree[plan.root] = 1;
  while (!stack.empty()) {
    const PlanTree::Node& node = plan.nodes[stack.back()];
    stack.pop_back();
    for (const int child : {node.next, node.onFalse}) {
      if (child < 0) continue;
      if (degree[child]++ == 0) stack.push_back(child);
    }
  }
  degree[plan.root] -= 1;
  return degree;
}

std::string branchTest(const KnowledgeTask& task, const PlanTree::Node& node) {
  if (node.fluent < 0) return task.task().atomNames[node.atom];
  std::string value;
  if (std::isnan(node.value)) {
    value = "undefined";
  } else if (!task.task().fluentIsNumeric[node.fluent]) {
    value = task.contingent().problem.objectNames[static_cast<std::size_t>(node.value)];
  } else {
    std::ostringstream text;
    text << std::setprecision(17) << node.value;
    value = text.str();
  }
  return "(= " + task.task().fluentNames[node.fluent] + " " + value + ")";
}

const std::vector<std::string>& contingentSearchModes() {
  static const std::vector<std::string> names{"gbfs", "astar", "bfs", "dfs", "ids"};
  return names;
}

ContingentResult solveContingent(KnowledgeTask& task, const ContingentOptions& options) {
  const std::vector<Operator>& operators = task.task().operators;
  bool effectApplicators = false;
  for (std::size_t op = 0; op < operators.size(); ++op) {
    effectApplicators = effectApplicators || task.callsEffectApplicator(static_cast<int>(op));
  }
  if (!options.symbolicFirst || !effectApplicators || readsAttachmentValues(task.task())) {
    return AndOrSearch(task, options).run();
  }
  // The symbolic plans and their refinements get at most half of the time limit.
  PlannerLimits refining = options.limits;
  refining.seconds *= kRefiningShare;
  const Deadline clock(refining);
  ContingentStatistics total;
  // Each limit counts over every search; the searches after the first get what is left (of
  // `seconds`).
  const auto remaining = [&](double seconds) {
    ContingentOptions rest = options;
    rest.limits.seconds = std::max(0.0, seconds - clock.elapsedSeconds());
    rest.limits.expansions -= std::min(total.expanded, rest.limits.expansions - 1);
    return rest;
  };
  const auto add = [&](ContingentResult& result) {
    ContingentStatistics& s = result.statistics;
    total.expanded += s.expanded;
    total.generated += s.generated;
    total.evaluated += s.evaluated;
    total.deadEnds += s.deadEnds;
    total.reused += s.reused;
    total.beliefs += s.beliefs;
    total.worlds = s.worlds;
    total.seconds = clock.elapsedSeconds();
    s = total;
  };
  // Symbolic plans, each refined by applying its effect applicators along every branch; a
  // transition whose effect failed is left out of the next symbolic search.
  std::unordered_set<std::uint64_t> blocked;
  while (total.refinements < kMaxRefinements) {
    ContingentResult symbolic = AndOrSearch(task, remaining(refining.seconds), &blocked).run();
    add(symbolic);
    // Without blocked transitions the symbolic search is a relaxation of the search with effect
    // applicators (the same symbolic transitions, none made infeasible by geometry): no plan
    // there is the answer of both, and so is any limit but time's (time is shared).
    if (symbolic.status != PlannerStatus::Solved && symbolic.status != PlannerStatus::TimeLimit &&
        (blocked.empty() || symbolic.status != PlannerStatus::Unsolvable)) {
      return symbolic;
    }
    if (symbolic.status != PlannerStatus::Solved) break;
    const TreeValidation refinement =
        validatePlanTree(task, symbolic.plan, "symbolic plan", &clock);
    if (refinement.stoppedBy && *refinement.stoppedBy != PlannerStatus::TimeLimit) {
      symbolic.status = *refinement.stoppedBy;
      symbolic.plan = {};
      return symbolic;
    }
    if (refinement.stoppedBy) break;
    if (refinement.valid) {
      symbolic.statistics.refinedSymbolicPlan = true;
      symbolic.statistics.seconds = clock.elapsedSeconds();
      return symbolic;
    }
    ++total.refinements;
    total.refinementFailure = refinement.message;
    if (refinement.infeasibleOperator < 0) break;
    const std::uint64_t key =
        transitionKey(task.symbolicKey(refinement.infeasibleIn), refinement.infeasibleOperator);
    if (!blocked.insert(key).second) break;
  }
  ContingentResult result = AndOrSearch(task, remaining(options.limits.seconds)).run();
  add(result);
  result.statistics.refinementFailed = true;
  return result;
}

TreeMetrics measure(const PlanTree& plan) {
  TreeMetrics out;
  if (plan.root < 0) return out;
  struct Sizes {
    double actions = 0, branches = 0, leaves = 0;
    std::size_t depth = 0;
  };
  std::vector<Sizes> memo(plan.nodes.size());
  std::vector<char> done(plan.nodes.size(), 0);  // 0 new, 1 in progress (a loop), 2 done
  // Post-order over an explicit stack: plans may be far longer than the call stack is deep. A
  // child still in progress is an ancestor (a loop) and counts as empty.
  std::vector<int> stack{plan.root};
  while (!stack.empty()) {
    const int index = stack.back();
    const PlanTree::Node& node = plan.nodes[index];
    if (done[index] == 2) {
      stack.pop_back();
      continue;
    }
    if (done[index] == 0) {
      done[index] = 1;
      for (const int child : {node.next, node.onFalse}) {
        if (child >= 0 && node.kind != PlanTree::Node::Kind::Goal && done[child] == 0) {
          stack.push_back(child);
        }
      }
      continue;
    }
    Sizes& s = memo[index];
    if (node.kind == PlanTree::Node::Kind::Goal) {
      s.leaves = 1;
    } else if (node.kind == PlanTree::Node::Kind::Action) {
      s = memo[node.next];
      s.actions += 1;
      s.depth += 1;
    } else {
      const Sizes& t = memo[node.next];
      const Sizes& f = memo[node.onFalse];
      s = {t.actions + f.actions, t.branches + f.branches + 1, t.leaves + f.leaves,
           std::max(t.depth, f.depth)};
    }
    done[index] = 2;
    stack.pop_back();
  }
  const Sizes& root = memo[plan.root];
  out.actions = root.actions;
  out.branches = root.branches;
  out.leaves = root.leaves;
  out.depth = root.depth;
  out.dagNodes = static_cast<std::size_t>(std::count(done.begin(), done.end(), 2));
  return out;
}

std::string formatPlanTree(const KnowledgeTask& task, const PlanTree& plan) {
  if (plan.root < 0) return "";
  const std::vector<int> degree = inDegrees(plan);
  std::vector<char> printed(plan.nodes.size(), 0);
  std::vector<std::string> lines{"(plan"};
  const std::function<void(int, int)> sequence = [&](int index, int indent) {
    const std::string pad(static_cast<std::size_t>(indent), ' ');
    while (true) {
      if (degree[index] >= 2) {
        const std::string label = "n" + std::to_string(index);
        if (printed[index]) {
          lines.push_back(pad + "(goto " + label + ")");
          return;
        }
        printed[index] = 1;
        lines.push_back(pad + "(label " + label + ")");
      }
      const PlanTree::Node& node = plan.nodes[index];
      if (node.kind == PlanTree::Node::Kind::Goal) return;
      if (node.kind == PlanTree::Node::Kind::Action) {
        const std::string action = "(" + task.task().operators[node.op].name + ")";
        lines.push_back(pad + (node.sample == 0 ? action
                                                : "(sample " + std::to_string(node.sample) + " " +
                                                      action + ")"));
        index = node.next;
        continue;
      }
      lines.push_back(pad + "(branch " + branchTest(task, node));
      lines.push_back(pad + "  (true");
      sequence(node.next, indent + 4);
      lines.back() += ")";
      lines.push_back(pad + "  (false");
      sequence(node.onFalse, indent + 4);
      lines.back() += "))";
      return;
    }
  };
  sequence(plan.root, 2);
  lines.back() += ")";
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

std::string resolveBranchTest(const SExpr& test, const KnowledgeTask& task, PlanTree::Node& node,
                              const SExpr*& where) {
  where = &test;
  if (!test.startsWith("=")) {
    node.atom = task.findAtom(toString(test));
    return node.atom < 0 ? "unknown atom " + toString(test) : "";
  }
  if (test.items.size() != 3 || !test.items[2].isAtom()) return "expected '(= (f …) value)'";
  node.fluent = task.findFluent(toString(test.items[1]));
  where = &test.items[1];
  if (node.fluent < 0) return "unknown function term " + toString(test.items[1]);
  where = &test.items[2];
  const std::string& written = test.items[2].text;
  const ObjectId object = task.contingent().problem.findObject(written);
  if (written == "undefined") {
    node.value = kUndefined;
  } else if (!task.task().fluentIsNumeric[node.fluent] && object >= 0) {
    node.value = object;
  } else {
    char* end = nullptr;
    node.value = std::strtod(written.c_str(), &end);
    if (end != written.c_str() + written.size()) return "expected a value: " + written;
  }
  return "";
}

PlanTree parsePlanTree(std::string_view text, const std::string& file, const KnowledgeTask& task) {
  const std::vector<SExpr> top = readSExprs(text, file);
  const auto fail = [&](const SExpr& where, const std::string& what) {
    throw InputError(locate(file, what, where.pos.line, where.pos.column));
  };
  if (top.size() != 1 || !top[0].startsWith("plan")) {
    if (top.empty()) throw InputError(locate(file, "expected '(plan …)'"));
    fail(top[0], "expected one '(plan …)'");
  }
  PlanTree plan;
  std::map<std::string, int> labels;
  std::vector<std::pair<int, const SExpr*>> gotos;
  const auto add = [&](PlanTree::Node node) {
    plan.nodes.push_back(node);
    return static_cast<int>(plan.nodes.size()) - 1;
  };
  const std::function<int(const SExpr&, std::size_t)> sequence = [&](const SExpr& list,
                                                                     std::size_t i) -> int {
    if (i == list.items.size()) {
      PlanTree::Node goal;
      goal.pos = list.pos;
      return add(goal);
    }
    const SExpr& item = list.items[i];
    if (!item.isList() || item.items.empty()) fail(item, "expected an action, branch or label");
    const bool last = i + 1 == list.items.size();
    if (item.startsWith("label") || item.startsWith("goto")) {
      if (item.items.size() != 2 || !item.items[1].isAtom()) fail(item, "expected a label name");
      const std::string& name = item.items[1].text;
      if (item.startsWith("goto")) {
        if (!last) fail(list.items[i + 1], "nothing may follow '(goto …)'");
        PlanTree::Node placeholder;
        placeholder.pos = item.pos;
        const int index = add(placeholder);
        gotos.push_back({index, &item});
        return index;
      }
      if (labels.count(name) > 0) fail(item, "duplicate label '" + name + "'");
      labels[name] = -1;
      const int index = sequence(list, i + 1);
      labels[name] = index;
      return index;
    }
    if (item.startsWith("branch")) {
      if (!last) fail(list.items[i + 1], "nothing may follow a branch");
      if (item.items.size() != 4 || !item.items[2].startsWith("true") ||
          !item.items[3].startsWith("false")) {
        fail(item, "expected '(branch (p …) (true …) (false …))'");
      }
      PlanTree::Node node;
      node.kind = PlanTree::Node::Kind::Branch;
      node.pos = item.pos;
      const SExpr* where = &item.items[1];
      const std::string error = resolveBranchTest(item.items[1], task, node, where);
      if (!error.empty()) fail(*where, error);
      node.next = sequence(item.items[2], 1);
      node.onFalse = sequence(item.items[3], 1);
      return add(node);
    }
    PlanTree::Node node;
    node.kind = PlanTree::Node::Kind::Action;
    node.pos = item.pos;
    const SExpr* action = &item;
    if (item.startsWith("sample") && item.items.size() == 3 && item.items[2].isList()) {
      const std::string& written = item.items[1].text;
      char* end = nullptr;
      const unsigned long sample = std::strtoul(written.c_str(), &end, 10);
      if (!item.items[1].isAtom() || written.empty() || written[0] == '-' ||
          end != written.c_str() + written.size() || sample > UINT32_MAX) {
        fail(item.items[1], "expected a sample number: " + toString(item.items[1]));
      }
      node.sample = static_cast<std::uint32_t>(sample);
      action = &item.items[2];
    }
    node.op = task.findOperator(toString(*action));
    if (node.op < 0) fail(*action, "unknown or never applicable action " + toString(*action));
    node.next = sequence(list, i + 1);
    return add(node);
  };
  plan.root = sequence(top[0], 1);
  for (const auto& [index, item] : gotos) {
    const auto it = labels.find(item->items[1].text);
    if (it == labels.end() || it->second < 0) {
      fail(*item, "undefined label '" + item->items[1].text + "' (labels must come first)");
    }
    const SourcePos pos = plan.nodes[index].pos;
    plan.nodes[index] = plan.nodes[it->second];
    plan.nodes[index].pos = pos;
  }
  return plan;
}

TreeValidation validatePlanTree(KnowledgeTask& task, const PlanTree& plan, const std::string& file,
                                const Deadline* deadline) {
  TreeValidation out;
  std::set<std::pair<int, Belief>> checked;  // by sharing key: equal keys have the same plans
  Belief key;
  std::vector<char> onPath(plan.nodes.size(), 0);
  const auto at = [&](const PlanTree::Node& node, const std::string& what) {
    return locate(file, what, node.pos.line, node.pos.column);
  };
  // Follows a sequence of actions in a loop (plans may be far longer than the call stack is
  // deep) and recurses at branches.
  const std::function<std::string(int, Belief)> walk = [&](int index, Belief belief) {
    std::vector<int> path;  // the nodes this call marked on the path
    std::string failure;
    while (failure.empty()) {
      const PlanTree::Node& node = plan.nodes[index];
      if (onPath[index]) {
        failure = at(node, "the plan loops back to an earlier step");
        break;
      }
      task.sharingKey(belief, key);
      if (!checked.insert({index, key}).second) break;
      onPath[index] = 1;
      path.push_back(index);
      if (node.kind == PlanTree::Node::Kind::Goal) {
        if (!task.isGoal(belief)) failure = at(node, "this branch ends without knowing the goal");
        break;
      }
      if (node.kind == PlanTree::Node::Kind::Action) {
        const std::string name = "(" + task.task().operators[node.op].name + ")";
        if (deadline != nullptr) out.stoppedBy = deadline->reached(0, 0);
        if (out.stoppedBy) {
          failure = at(node, "stopped before " + name + ": " + toString(*out.stoppedBy));
          break;
        }
        Belief next;
        const std::vector<int>& variants = task.variants(node.op);
        const auto op = std::find_if(variants.begin(), variants.end(),
                                     [&](int v) { return task.applicable(v, belief); });
        if (op == variants.end()) {
          failure = at(node, "precondition of " + name + " is not known to hold");
        } else if (!task.apply(*op, belief, next, node.sample)) {
          failure = at(node, "an attachment reports " + name + " infeasible");
          out.infeasibleOperator = *op;
          out.infeasibleIn = belief;
        } else {
          index = node.next;
          belief = std::move(next);
        }
        continue;
      }
      Belief onTrue;
      Belief onFalse;
      if (node.fluent >= 0) {
        if (!task.knowsValue(node.fluent, belief)) {
          failure = at(node, "branch on " + task.task().fluentNames[node.fluent] +
                                 ", whose value no sensing action observed");
          break;
        }
        task.splitValue(node.fluent, node.value, belief, onTrue, onFalse);
      } else {
        if (!task.knowsWhether(node.atom, belief)) {
          failure = at(node, "branch on " + task.task().atomNames[node.atom] +
                                 ", whose value no sensing action observed");
          break;
        }
        task.split(node.atom, belief, onTrue, onFalse);
      }
      if (!onTrue.empty()) failure = walk(node.next, std::move(onTrue));
      if (failure.empty() && !onFalse.empty()) failure = walk(node.onFalse, std::move(onFalse));
      break;
    }
    for (const int marked : path) onPath[marked] = 0;
    return failure;
  };
  out.message = walk(plan.root, task.initialBelief());
  out.valid = out.message.empty();
  out.metrics = measure(plan);
  return out;
}

Execution executePlanTree(KnowledgeTask& task, const PlanTree& plan, std::uint32_t world) {
  Execution out;
  int index = plan.root;
  constexpr std::size_t kMaxSteps = 1000000;
  while (out.steps.size() < kMaxSteps) {
    const PlanTree::Node& node = plan.nodes[index];
    if (node.kind == PlanTree::Node::Kind::Goal) {
      out.reachedGoal = task.isGoalIn(world);
      if (!out.reachedGoal) out.message = "the plan ended but the goal does not hold";
      return out;
    }
    if (node.kind == PlanTree::Node::Kind::Branch) {
      const bool value = node.fluent >= 0
                             ? sameValue(task.world(world).fluent(node.fluent), node.value)
                             : task.world(world).atom(node.atom);
      out.steps.push_back("branch " + branchTest(task, node) + " -> " + (value ? "true" : "false"));
      index = value ? node.next : node.onFalse;
      continue;
    }
    const std::string name = "(" + task.task().operators[node.op].name + ")";
    const std::vector<int>& variants = task.variants(node.op);
    const auto op = std::find_if(variants.begin(), variants.end(), [&](int v) {
      return task.holdsIn(task.task().operators[v].precondition, world);
    });
    if (op == variants.end()) {
      out.message = "precondition of " + name + " is false in the true state";
      return out;
    }
    world = task.applyIn(*op, world, node.sample);
    if (world == PackedSet::kMissing) {
      out.message = "an attachment reports " + name + " infeasible";
      return out;
    }
    out.steps.push_back(name);
    index = node.next;
  }
  out.message = "execution exceeded " + std::to_string(kMaxSteps) + " steps";
  return out;
}

}  // namespace kaboum::symbolic
