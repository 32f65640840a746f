// Branched plans over knowledge states (thesis §3.3.1 and Figure 3.2; seed 003 §III-A): AND–OR
// search that branches on sensed atoms, shares solved sub-problems between branches, and a
// validator that checks every branch and simulates execution against hidden true states.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kaboum/core/deadline.hpp"
#include "kaboum/symbolic/knowledge.hpp"
#include "kaboum/symbolic/search.hpp"
#include "kaboum/symbolic/sexpr.hpp"

namespace kaboum::symbolic {

// A plan as a DAG: an action node continues at `next`; a branch node on `atom` continues at
// `next` when the atom is observed true and at `onFalse` otherwise (a branch on a sensed value,
// `fluent` >= 0, tests (= fluent value) instead); a goal node ends the branch.
// Nodes reached from several places are solved sub-problems shared between branches.
struct PlanTree {
  struct Node {
    enum class Kind { Goal, Action, Branch };
    Kind kind = Kind::Goal;
    int op = -1;           // Action: ground operator
    AtomId atom = -1;      // Branch: observed atom
    FluentId fluent = -1;  // Branch on a value: sensed function term (atom is -1)
    double value = 0.0;
    int next = -1;
    int onFalse = -1;
    // Action: which geometric sample its effect applicators computed (AttachmentArgs::sample).
    std::uint32_t sample = 0;
    SourcePos pos;  // where a parsed plan wrote the node
  };
  std::vector<Node> nodes;
  int root = -1;
};

// Sizes of the plan unfolded into a tree (shared nodes counted once per path through them).
struct TreeMetrics {
  double actions = 0;     // action nodes in the unfolded tree
  double branches = 0;    // branch nodes in the unfolded tree
  double leaves = 0;      // goal leaves = execution paths
  std::size_t depth = 0;  // most actions on one path
  std::size_t dagNodes = 0;
};
TreeMetrics measure(const PlanTree& plan);

// Names accepted by ContingentOptions::mode: "gbfs", "astar", "bfs", "dfs", "ids" (the core's
// modes), ordering the search over non-sensing actions between branch points.
const std::vector<std::string>& contingentSearchModes();

struct ContingentStatistics;

struct ContingentOptions {
  std::string mode = "gbfs";     // one of contingentSearchModes()
  std::string heuristic = "ff";  // one of heuristicNames(), evaluated per world (maximum);
                                 // ignored by bfs and dfs
  PlannerLimits limits;
  std::size_t maxDepth = 5000;  // nested branch points on one path
  // Geometric samples per (knowledge state, action): an action that calls effect applicators has
  // up to this many successors, sample s computed by its applicators as AttachmentArgs::sample. 1
  // is the thesis's geometric branching factor of one (§6.1.2); sample s > 0 of a transition waits
  // for the search's (s+1)-th round (docs/contingent.md, "Search").
  std::uint32_t samples = 1;
  // Plan symbolically first, then refine (docs/contingent.md, "Symbolic first"): where no
  // condition reads a value that effect applicators write, search with every action's symbolic
  // effects only, then apply the plan's effect applicators along every branch; the plan stands
  // if they all succeed, and the search with effect applicators runs otherwise.
  bool symbolicFirst = true;
  // Called every `progressPeriod` seconds of search with the statistics so far (seconds and
  // beliefs set), for progress reports on long runs; none if empty.
  std::function<void(const ContingentStatistics&)> progress;
  double progressPeriod = 1.0;
};

struct ContingentStatistics {
  std::size_t expanded = 0;   // knowledge states expanded
  std::size_t generated = 0;  // successor knowledge states
  std::size_t evaluated = 0;  // per-world heuristic evaluations
  std::size_t deadEnds = 0;
  std::size_t reused = 0;  // solved sub-problems shared
  std::size_t beliefs = 0;
  std::size_t worlds = 0;
  double seconds = 0.0;
  // How the plan was found (ContingentOptions::symbolicFirst): by a symbolic plan whose effect
  // applicators all succeeded, after `refinements` symbolic plans that failed; or by the search
  // with effect applicators, after `refinements` failed ones (refinementFailed, the last failure
  // in refinementFailure) or none tried.
  bool refinedSymbolicPlan = false;
  bool refinementFailed = false;
  std::size_t refinements = 0;
  std::string refinementFailure;
};

struct ContingentResult {
  PlannerStatus status = PlannerStatus::Unsolvable;
  PlanTree plan;
  ContingentStatistics statistics;
};

// AND–OR search: an OR search in `options.mode` (greedy best-first or A* on the worst world's
// heuristic value, breadth- or depth-first) over knowledge states until a goal or a sensing
// action whose branches are all solved by the same search, recursively. Throws InputError for an
// unknown mode or heuristic.
// Sensing outcomes split eagerly into branch nodes; solved knowledge states are shared, failed
// ones memoized. Sound; incomplete where a branch fails only because it would loop back to a
// knowledge state an enclosing search is still solving.
ContingentResult solveContingent(KnowledgeTask& task, const ContingentOptions& options);

// The plan as an S-expression tree, one step per line, indented by branch depth:
//   (plan (grasp o1) (senseweight o1)
//     (branch (isspillable o1) (true (transferupright o1) …) (false …)))
// A shared node is introduced by `(label nK)` at its first occurrence and reused by `(goto nK)`.
// An action whose geometric sample is s > 0 is written `(sample s (a x y))`.
std::string formatPlanTree(const KnowledgeTask& task, const PlanTree& plan);

// How many edges enter each node of the plan; nodes not reachable from the root have 0, and the
// root counts only edges back to it.
std::vector<int> inDegrees(const PlanTree& plan);
// What a branch node tests, as formatPlanTree writes it: "(p a)" or "(= (f a) 3)" (an
// object-valued term names the object).
std::string branchTest(const KnowledgeTask& task, const PlanTree::Node& node);

// Resolves a branch test as branchTest() writes it — (p a) or (= (f a) v) — into `node`'s atom,
// or fluent and value. Returns "" or what is wrong, with the sub-expression at fault in `where`.
std::string resolveBranchTest(const SExpr& test, const KnowledgeTask& task, PlanTree::Node& node,
                              const SExpr*& where);

// Parses formatPlanTree's output. Throws InputError (file:line:col) for unknown actions, atoms,
// labels and malformed branches.
PlanTree parsePlanTree(std::string_view text, const std::string& file, const KnowledgeTask& task);

struct TreeValidation {
  bool valid = false;
  std::string message;  // first failure: "file:line:col: …" of the step, or "" when valid
  TreeMetrics metrics;
  // When an effect applicator reported an action infeasible: the operator (variant) and the
  // knowledge state it was applied in; otherwise -1.
  int infeasibleOperator = -1;
  Belief infeasibleIn;
  // The limit that stopped the validation (a deadline was given), if one did.
  std::optional<PlannerStatus> stoppedBy;
};

// Checks every branch from the initial knowledge: each action's precondition is known to hold,
// each branch atom is known-whether (sensed), and every leaf knows the goal.
// With `deadline`, stops once one of its limits is reached (its expansion limit does not count),
// before an action.
TreeValidation validatePlanTree(KnowledgeTask& task, const PlanTree& plan, const std::string& file,
                                const Deadline* deadline = nullptr);

struct Execution {
  bool reachedGoal = false;
  std::vector<std::string> steps;  // actions executed and "branch (p) -> true|false"
  std::string message;             // why execution stopped early
};

// Executes the plan in one true initial world (from a hidden state), following branches by the
// world's value of each sensed atom.
Execution executePlanTree(KnowledgeTask& task, const PlanTree& plan, std::uint32_t world);

}  // namespace kaboum::symbolic
