// Knowledge states of a contingent problem (thesis §3.3.1, PKS databases Kf/Kw/Kv and primitive
// queries; seed 003 §III-A): a knowledge state is the set of worlds consistent with what the agent
// knows, over the ground task of the compiled problem (contingent_parser.hpp); queries, actions
// with forgetting, branching on sensed atoms and values, and execution in hidden true worlds.
// Stored explicitly, or factored into independent components (knowledge_factoring.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/symbolic/contingent_parser.hpp"
#include "kaboum/symbolic/knowledge_factoring.hpp"
#include "kaboum/symbolic/packed_set.hpp"
#include "kaboum/symbolic/state.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

// A knowledge state. Explicit: the sorted ids of the worlds it admits. Factored: the id of the
// world of its known core atoms, then per component the id of its set of local worlds (the
// knowledge state admits every combination). Either way equal knowledge has equal ids.
using Belief = std::vector<std::uint32_t>;

// Whether two fluent values are the same value (an undefined, NaN value equals itself), as Kv
// sensing tells them apart.
bool sameValue(double a, double b);

// Ground knowledge-level task: worlds are packed classical states registered once; a knowledge
// state (belief) is a sorted list of world ids. Kf(p) holds if p is true in every world, Kf(¬p) if
// false in every world; Kw(p) if the auxiliary atom `(kw.p …)` (added by sensing) is true in every
// world or p is known; Kv(f) likewise with `(kv.f …)` or a value common to every world.
class KnowledgeTask {
 public:
  // Throws InputError when the initial knowledge is contradictory (no world) or admits more than
  // `maxWorlds` worlds (factored: in one component), when a goal atom can never become known, and
  // when `representation` is Factored but factoring is not exact for the task.
  KnowledgeTask(const ContingentProblem& contingent, const ProcedureRegistry& procedures,
                std::size_t maxWorlds = std::size_t{1} << 18,
                KnowledgeRepresentation representation = KnowledgeRepresentation::Automatic);

  const GroundTask& task() const { return task_; }
  const ContingentProblem& contingent() const { return contingent_; }
  const Belief& initialBelief() const { return initial_; }
  std::size_t worldCount() const { return worlds_.size(); }  // worlds (factored: parts) stored
  bool factored() const { return factored_; }
  int componentCount() const { return factoring_.components; }
  // How many worlds `belief` admits (a product of component sizes when factored).
  double possibleWorlds(const Belief& belief) const;
  // Worlds of `belief` to evaluate a heuristic in: all of them when explicit; when factored, each
  // local world of each component completed with the first local world of the others (a sample
  // of real worlds, linear in the components). Valid until the next call.
  const Belief& heuristicWorlds(const Belief& belief);
  // `belief` with each settled component (factored only) replaced by kSettled: one that the goal
  // does not read and that no action can read or change any more (by a relaxed reachability
  // analysis that holds its knowledge fixed). Knowledge states with equal keys have the same
  // plans, so the search and the validator share them. Explicit: `belief` itself.
  void sharingKey(const Belief& belief, Belief& key);
  static constexpr std::uint32_t kSettled = 0xffffffffu;
  StateView world(std::uint32_t id) const { return evaluator_.view(worlds_.get(id)); }
  AttachmentRuntime& attachments() { return *attachments_; }

  // Primitive queries over a conjunction: atoms as K/Kw/Kv literals, numeric and attachment tests
  // in every world.
  bool holds(const Condition& condition, const Belief& belief);
  bool applicable(int op, const Belief& belief);
  bool isGoal(const Belief& belief);
  // Applies operator `op` in every world; false if an attachment reports it infeasible somewhere.
  // Its effect applicators compute geometric sample `sample` (AttachmentArgs::sample).
  bool apply(int op, const Belief& belief, Belief& out, std::uint32_t sample = 0);
  // apply() without calling effect applicators (the values they write stay as they are): the
  // symbolic part of the successor, before paying for its geometry.
  void preview(int op, const Belief& belief, Belief& out);
  // Whether applying `op` calls an effect applicator (in its effect or a conditional one).
  bool callsEffectApplicator(int op) const;

  // An atom the agent will know at run time but does not know now (Kw(p), neither K(p) nor K(¬p)):
  // the planner branches on it. -1 if none.
  AtomId pendingObservation(const Belief& belief);
  // Whether `atom` may be branched on: Kw(atom) holds.
  bool knowsWhether(AtomId atom, const Belief& belief);
  // Splits `belief` on `atom` (branch(φ), Figure 3.2); either side may be empty.
  void split(AtomId atom, const Belief& belief, Belief& onTrue, Belief& onFalse);

  // Kv sensing (thesis §3.3.1): a function term whose value the agent will know at run time
  // (Kv(f)) but which differs between worlds; `value` is that of the first world. The planner
  // branches on (= f value), once per value the worlds allow. False if none.
  bool pendingValue(const Belief& belief, FluentId& fluent, double& value);
  // Whether a branch on the value of `fluent` may be taken: Kv(f) holds.
  bool knowsValue(FluentId fluent, const Belief& belief);
  // Splits `belief` into the worlds where `fluent` equals `value` (undefined equals undefined)
  // and the others; either side may be empty.
  void splitValue(FluentId fluent, double value, const Belief& belief, Belief& equal,
                  Belief& other);
  FluentId findFluent(const std::string& name) const;  // "(f a)"; -1 if unknown

  // The world of a hidden initial state; throws InputError if it is not one the knowledge admits.
  std::uint32_t hiddenWorld(const HiddenState& hidden, const std::string& file);
  // World-level evaluation for simulated execution.
  bool holdsIn(const Condition& condition, std::uint32_t world);
  bool isGoalIn(std::uint32_t world);
  // Applies `op` in one true world; each non-deterministic effect `(nondet l)` takes place or not
  // as a generator seeded by seedOutcomes (default 0) decides. PackedSet::kMissing if infeasible.
  std::uint32_t applyIn(int op, std::uint32_t world, std::uint32_t sample = 0);
  void seedOutcomes(std::uint64_t seed) { outcomes_.seed(seed); }

  // A hash of what `belief` knows apart from the values that effect applicators write (opaque
  // handles such as a geometric state's identifier, thesis Definition 5): equal for knowledge
  // states that differ only in such values, independent of world order.
  std::uint64_t symbolicKey(const Belief& belief);

  AtomId findAtom(const std::string& name) const;   // "(p a b)"; -1 if unknown
  int findOperator(const std::string& name) const;  // "(a x y)"; -1 if unknown
  // Operators sharing `op`'s name (a disjunctive precondition is split into one per disjunct).
  const std::vector<int>& variants(int op) const;

 private:
  bool known(AtomId atom, const Belief& belief, bool& value);
  bool kwHolds(AtomId atom, const Belief& belief);
  bool kvHolds(AtomId atom, const Belief& belief);
  bool kQueryHolds(AtomId atom, const Belief& belief);
  void storeForgetting(Belief& out, std::span<const std::uint64_t> mask = {});
  void applyFactored(int op, const Belief& belief, Belief& out, bool effectApplicators);
  void canonicalizeFactored(Belief& belief);
  void splitFactored(AtomId atom, const Belief& belief, Belief& onTrue, Belief& onFalse);
  std::uint32_t internLocal(Belief& localWorlds);
  void compose(const Belief& belief, int component, std::uint32_t local);
  void setUpFactoring(KnowledgeRepresentation representation);
  void setUpSettling();
  bool knowledgeLiteralHolds(AtomId atom, const Belief& belief);
  bool applyInWorlds(int op, const Belief& belief, Belief& out, bool effectApplicators);
  bool fluentKnown(FluentId fluent, const Belief& belief);
  bool holdsAtoms(const Condition& condition, const Belief& belief);
  bool allWorlds(const Condition& tests, const Belief& belief);
  bool clauseHolds(std::size_t clause, const Belief& belief);
  void canonicalize(Belief& belief);
  void summarize(const Belief& belief);
  std::uint32_t store(std::span<const std::uint64_t> words);
  void enumerateWorlds(std::size_t maxWorlds);
  std::uint32_t hiddenWorldFactored(const HiddenState& hidden, const std::string& file);
  void checkGoalKnowable();

  const ContingentProblem& contingent_;
  std::unique_ptr<AttachmentRuntime> attachments_;
  GroundTask task_;
  StateEvaluator evaluator_;
  PackedSet worlds_;
  Belief initial_;
  std::vector<Condition> preconditionTests_;  // numeric, fluent and attachment tests only
  Condition goalTests_;
  std::unordered_map<std::string, AtomId> atomIds_;
  std::unordered_map<std::string, FluentId> fluentIds_;
  std::unordered_map<std::string, std::vector<int>> operatorIds_;
  static constexpr AtomId kNotKnowledge = -1;
  // Base of a Kw atom that is never true (so always known false), or of a Kv atom over a static
  // function (known only if :init gives its value, which sets the Kv atom).
  static constexpr AtomId kNoBase = -2;
  std::vector<AtomId> kwBase_;          // per atom: base atom of a (kw.p …) atom
  std::vector<FluentId> kvBase_;        // per atom: fluent of a (kv.f …) atom
  std::vector<AtomId> knowledgeAtoms_;  // all (kw.…) and (kv.…) atoms
  // Per atom: (k.p …)/(k-not.p …) query K(p)/K(¬p) of `base`; (kf-del.p …)/(kf-del-not.p …)
  // mark del(Kf, p)/del(Kf, ¬p) in a successor world, (nondet-del.p …)/(nondet-add.p …) the same
  // loss of knowledge from a non-deterministic effect, which may also change the true world.
  struct Auxiliary {
    AtomId base = kNotKnowledge;
    bool negated = false;
    bool nondeterministic = false;
  };
  std::vector<Auxiliary> kQuery_;
  std::vector<Auxiliary> forget_;
  std::vector<AtomId> forgetAtoms_;
  std::vector<AtomId> forgotten_;
  std::vector<std::uint64_t> scratch_;
  std::mt19937_64 outcomes_{0};  // nature's choices in applyIn
  std::vector<std::uint64_t> anyWorld_;
  std::vector<std::uint64_t> allWorlds_;
  Belief summarized_;
  std::vector<bool> attachmentWritten_;      // per fluent: some effect applicator writes it
  std::vector<std::uint64_t> symbolicHash_;  // per world: symbolicKey's term, 0 until computed

  // Factored knowledge states (knowledge_factoring.hpp).
  KnowledgeFactoring factoring_;
  bool factored_ = false;
  std::vector<std::uint64_t> coreMask_;                    // atoms outside every component
  std::vector<std::vector<std::uint64_t>> componentMask_;  // per component: its atoms
  std::vector<std::vector<int>> touched_;  // per operator: components its effects change
  std::vector<Belief> localWorlds_;        // per id: sorted world ids of one component
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> localIds_;  // by hash
  Belief sample_;  // heuristicWorlds' answer
  Belief local_;   // scratch local world set
  std::array<Belief, 2>
      splitWorlds_;  // scratch local world sets of applyFactored and splitFactored
  std::vector<std::uint64_t> composed_;  // scratch world composed from a factored state
  // Settled components (sharingKey).
  std::vector<int> ownerOf_;  // per atom: component its value or knowledge is of, or -1
  std::vector<std::vector<int>> opReadsOrWrites_;  // per operator: components
  std::vector<std::vector<int>> waitingFor_;  // per fact (2 atom + 0 true / 1 false): operators
  std::vector<std::vector<std::pair<AtomId, bool>>> knowledgeLiterals_;  // per operator
  // Scratch of sharingKey: per component, per fact, per operator.
  std::vector<char> unsettled_;
  std::vector<std::vector<int>> blockedBy_;
  std::vector<char> reachable_;
  std::vector<int> missing_;
  std::vector<int> worklist_;
};

}  // namespace kaboum::symbolic
