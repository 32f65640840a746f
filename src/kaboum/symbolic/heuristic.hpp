// Goal-distance heuristics over the delete relaxation (Bonet & Geffner's h_max/h_add, Hoffmann &
// Nebel's FF relaxed plan with preferred operators) and the blind heuristic. Negative literals,
// numeric tests and attachment calls are treated optimistically (as satisfiable), so a dead end
// reported by a relaxation is a true dead end (thesis §6.2 search modes).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "kaboum/symbolic/state.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

class Heuristic {
 public:
  static constexpr int kDeadEnd = std::numeric_limits<int>::max();
  virtual ~Heuristic() = default;
  // Estimated number of actions to the goal, or kDeadEnd. If `preferred` is non-null, it receives
  // the operators the heuristic recommends (may be empty; order is deterministic).
  virtual int evaluate(StateView state, std::vector<int>* preferred) = 0;
  virtual bool admissible() const = 0;
  // Whether the heuristic can leave operators out (exclude()); the relaxation heuristics can.
  virtual bool excludes() const { return false; }
  // Leaves ground operator `op` out of the relaxation, or puts it back: the estimate becomes that
  // of the task without the operators found infeasible (by geometry, say). No-op unless excludes().
  virtual void exclude(int /*op*/, bool /*excluded*/) {}
};

// Names accepted by makeHeuristic: "ff", "add", "max", "blind", "lmcount" (landmarks.hpp).
const std::vector<std::string>& heuristicNames();
// Throws InputError for an unknown name.
std::unique_ptr<Heuristic> makeHeuristic(const std::string& name, const GroundTask& task);

}  // namespace kaboum::symbolic
