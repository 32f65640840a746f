// Fact landmarks of the delete relaxation with greedy-necessary orderings (backchaining from the
// goal over first achievers, after Zhu & Givan and Richter, Helmert & Westphal's LAMA), and the
// landmark-count heuristic that guides greedy search through the plateaus and local minima of the
// delete relaxation (thesis §6.2, Stacked n Objects, Table 6.4).
#pragma once

#include <span>
#include <vector>

#include "kaboum/symbolic/heuristic.hpp"
#include "kaboum/symbolic/relaxation.hpp"

namespace kaboum::symbolic {

struct LandmarkGraph {
  std::vector<int> facts;                // relaxation fact of each landmark
  std::vector<std::vector<int>> before;  // before[i]: landmarks ordered greedy-necessarily before i
  std::vector<bool> goal;                // landmark i is a fact of the goal
  int find(int fact) const;              // landmark of `fact`, or -1
};

// A fact L is a landmark if it is a goal fact, or a precondition of every first achiever of a
// landmark L' that is false initially (an achiever of L' applicable in the relaxed exploration
// from the initial state that never achieves L'); then L is ordered before L'. Facts only (no
// disjunctive landmarks); empty when the goal is a disjunction.
LandmarkGraph findLandmarks(const RelaxedTask& relaxed);

// Landmark count, state-based: the landmarks false in the state that are still needed (a goal,
// or ordered before a needed landmark), so a destroyed goal or precondition counts again, as in
// LAMA's "required again". Preferred operators: applicable operators achieving a needed landmark
// none of whose predecessors is needed.
class LandmarkCountHeuristic : public Heuristic {
 public:
  explicit LandmarkCountHeuristic(const GroundTask& task);
  int evaluate(StateView state, std::vector<int>* preferred) override;
  bool admissible() const override { return false; }
  const LandmarkGraph& graph() const { return graph_; }

 private:
  RelaxedTask relaxed_;
  LandmarkGraph graph_;
  std::vector<std::vector<int>> achievers_;  // unary operators adding each landmark
  std::vector<std::uint8_t> factTrue_, needed_;
  std::vector<int> stateFacts_, stack_, neededList_;
};

}  // namespace kaboum::symbolic
