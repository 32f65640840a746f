#include "kaboum/symbolic/knowledge.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {
namespace {

bool bit(std::span<const std::uint64_t> words, AtomId atom) {
  return (words[atom >> 6] >> (atom & 63)) & 1u;
}

void setBit(std::span<std::uint64_t> words, AtomId atom, bool value) {
  const std::uint64_t mask = std::uint64_t{1} << (atom & 63);
  if (value) {
    words[atom >> 6] |= mask;
  } else {
    words[atom >> 6] &= ~mask;
  }
}

}  // namespace

KnowledgeTask::KnowledgeTask(const ContingentProblem& contingent,
                             const ProcedureRegistry& procedures, std::size_t maxWorlds)
    : contingent_(contingent),
      attachments_(
          std::make_unique<AttachmentRuntime>(contingent.domain, contingent.problem, procedures)),
      task_(ground(contingent.domain, groundingProblem(contingent), 4096,
                   contingent.varyingPredicates)),
      evaluator_(task_, *attachments_),
      worlds_(evaluator_.layout().words()) {
  for (std::size_t a = 0; a < task_.atomNames.size(); ++a) {
    atomIds_.emplace(task_.atomNames[a], static_cast<AtomId>(a));
  }
  for (std::size_t o = 0; o < task_.operators.size(); ++o) {
    operatorIds_["(" + task_.operators[o].name + ")"].push_back(static_cast<int>(o));
  }
  for (std::size_t f = 0; f < task_.fluentNames.size(); ++f) {
    fluentIds_.emplace(task_.fluentNames[f], static_cast<FluentId>(f));
  }
  kwBase_.assign(task_.atomNames.size(), kNotKnowledge);
  kvBase_.assign(task_.atomNames.size(), kNotKnowledge);
  kQuery_.assign(task_.atomNames.size(), {});
  forget_.assign(task_.atomNames.size(), {});
  for (std::size_t a = 0; a < task_.atomNames.size(); ++a) {
    const std::string& name = task_.atomNames[a];
    const std::string base = "(" + name.substr(std::min<std::size_t>(4, name.size()));
    if (name.starts_with("(kw.")) {
      const auto it = atomIds_.find(base);
      kwBase_[a] = it == atomIds_.end() ? kNoBase : it->second;
      knowledgeAtoms_.push_back(static_cast<AtomId>(a));
    } else if (name.starts_with("(kv.")) {
      const auto it = fluentIds_.find(base);
      kvBase_[a] = it == fluentIds_.end() ? kNoBase : it->second;
      knowledgeAtoms_.push_back(static_cast<AtomId>(a));
    }
    for (const auto& [prefix, negated] : {std::pair{"(k.", false},
                                          {"(k-not.", true},
                                          {"(kf-del.", false},
                                          {"(kf-del-not.", true},
                                          {"(nondet-del.", false},
                                          {"(nondet-add.", true}}) {
      const std::string_view head(prefix);
      if (!name.starts_with(head)) continue;
      const auto it = atomIds_.find("(" + name.substr(head.size()));
      const bool query = head.starts_with("(k.") || head.starts_with("(k-not.");
      Auxiliary& target = query ? kQuery_[a] : forget_[a];
      target.base = it == atomIds_.end() ? kNoBase : it->second;
      target.negated = negated;
      target.nondeterministic = head.starts_with("(nondet-");
      if (!query) forgetAtoms_.push_back(static_cast<AtomId>(a));
      break;
    }
  }
  const auto testsOnly = [](const Condition& c) {
    Condition out;
    out.fluentTests = c.fluentTests;
    out.numericTests = c.numericTests;
    out.moduleChecks = c.moduleChecks;
    return out;
  };
  for (const Operator& op : task_.operators) {
    preconditionTests_.push_back(testsOnly(op.precondition));
  }
  if (task_.goal.size() == 1) goalTests_ = testsOnly(task_.goal[0]);
  scratch_.resize(evaluator_.layout().words());
  enumerateWorlds(maxWorlds);
  checkGoalKnowable();
}

std::uint32_t KnowledgeTask::store(std::span<const std::uint64_t> words) {
  return worlds_.insert(words).first;
}

// Possible initial worlds: every assignment to the atoms named by constraints that satisfies them,
// found by backtracking with early pruning of violated `oneof`/`or` constraints.
void KnowledgeTask::enumerateWorlds(std::size_t maxWorlds) {
  const std::string& file = contingent_.problem.file;
  std::vector<std::uint64_t> base(evaluator_.layout().words(), 0);
  evaluator_.initialState(base);
  // initialState set the union of possibly-true atoms; rebuild from the known ones.
  std::fill(base.begin(), base.begin() + static_cast<long>(evaluator_.layout().atomBitset(1)), 0);
  std::vector<std::int8_t> fixed(task_.atomNames.size(), -1);
  const auto atomOf = [&](const InitialLiteral& literal) {
    return findAtom(describeAtom(contingent_.domain, contingent_.problem, literal.atom.predicate,
                                 literal.atom.args));
  };
  std::vector<GroundAtom> knownAtoms = contingent_.problem.init;
  for (const GroundAtom& atom : initialValueKnowledge(contingent_)) knownAtoms.push_back(atom);
  for (const GroundAtom& atom : knownAtoms) {
    const AtomId id =
        findAtom(describeAtom(contingent_.domain, contingent_.problem, atom.predicate, atom.args));
    if (id >= 0) fixed[id] = 1;
  }
  struct Clause {
    bool exactlyOne = false;
    std::vector<std::pair<AtomId, bool>> literals;
  };
  std::vector<Clause> clauses;
  std::vector<AtomId> variables;
  std::vector<char> isVariable(task_.atomNames.size(), 0);
  for (const KnowledgeConstraint& constraint : contingent_.constraints) {
    if (constraint.kind == KnowledgeConstraint::Kind::KnownFalse) {
      const InitialLiteral& literal = constraint.literals[0];
      const AtomId id = atomOf(literal);
      if (id < 0) continue;
      if (fixed[id] == 1) {
        throw InputError(locate(file,
                                "contradictory initial knowledge: " + task_.atomNames[id] +
                                    " is both known true and known false",
                                literal.pos.line, literal.pos.column));
      }
      fixed[id] = 0;
      continue;
    }
    Clause clause;
    clause.exactlyOne = constraint.kind == KnowledgeConstraint::Kind::OneOf;
    for (const InitialLiteral& literal : constraint.literals) {
      const AtomId id = atomOf(literal);
      if (id < 0) continue;
      clause.literals.push_back({id, literal.positive});
      if (!isVariable[id]) {
        isVariable[id] = 1;
        variables.push_back(id);
      }
    }
    if (constraint.kind != KnowledgeConstraint::Kind::Unknown) clauses.push_back(clause);
  }
  std::vector<std::vector<int>> clausesOf(task_.atomNames.size());
  for (std::size_t c = 0; c < clauses.size(); ++c) {
    for (const auto& [atom, positive] : clauses[c].literals) {
      clausesOf[atom].push_back(static_cast<int>(c));
    }
  }
  std::vector<std::int8_t> value(task_.atomNames.size(), -1);
  const auto violated = [&](const Clause& clause) {
    int trueCount = 0;
    int open = 0;
    for (const auto& [atom, positive] : clause.literals) {
      if (value[atom] < 0) {
        ++open;
      } else if ((value[atom] == 1) == positive) {
        ++trueCount;
      }
    }
    return (clause.exactlyOne && trueCount > 1) || (trueCount == 0 && open == 0);
  };
  std::vector<std::uint64_t> world(base.size());
  const std::function<void(std::size_t)> assign = [&](std::size_t index) {
    if (index == variables.size()) {
      std::copy(base.begin(), base.end(), world.begin());
      for (std::size_t a = 0; a < fixed.size(); ++a) {
        if (fixed[a] == 1) setBit(world, static_cast<AtomId>(a), true);
      }
      for (const AtomId atom : variables) setBit(world, atom, value[atom] == 1);
      initial_.push_back(store(world));
      if (initial_.size() > maxWorlds) {
        throw InputError(locate(file,
                                "the initial knowledge admits more than " +
                                    std::to_string(maxWorlds) + " possible worlds",
                                contingent_.initPos.line, contingent_.initPos.column));
      }
      return;
    }
    const AtomId atom = variables[index];
    for (const std::int8_t candidate : {std::int8_t{0}, std::int8_t{1}}) {
      if (fixed[atom] >= 0 && fixed[atom] != candidate) continue;
      value[atom] = candidate;
      bool ok = true;
      for (const int c : clausesOf[atom]) ok = ok && !violated(clauses[c]);
      if (ok) assign(index + 1);
    }
    value[atom] = -1;
  };
  assign(0);
  if (initial_.empty()) {
    throw InputError(locate(file,
                            "contradictory initial knowledge: no world satisfies the 'oneof', "
                            "'or' and known atoms of :init",
                            contingent_.initPos.line, contingent_.initPos.column));
  }
  std::sort(initial_.begin(), initial_.end());
  initial_.erase(std::unique(initial_.begin(), initial_.end()), initial_.end());
  canonicalize(initial_);
}

// A goal atom that is unknown initially, that no operator changes and that no operator observes
// can never become known: reject the problem instead of searching forever.
void KnowledgeTask::checkGoalKnowable() {
  if (task_.goal.size() != 1) return;
  std::vector<char> touched(task_.atomNames.size(), 0);
  const auto mark = [&](const EffectList& effect) {
    for (const AtomId a : effect.adds) {
      touched[a] = 1;
      if (kwBase_[a] >= 0) touched[kwBase_[a]] = 1;
    }
    for (const AtomId a : effect.deletes) touched[a] = 1;
  };
  for (const Operator& op : task_.operators) {
    mark(op.effect);
    for (const ConditionalEffect& c : op.conditional) mark(c.effect);
  }
  const Condition& goal = task_.goal[0];
  for (const std::vector<AtomId>* atoms : {&goal.positive, &goal.negative}) {
    for (const AtomId atom : *atoms) {
      bool value = false;
      if (touched[atom] || kQuery_[atom].base != kNotKnowledge || kwBase_[atom] != kNotKnowledge ||
          kvBase_[atom] != kNotKnowledge || known(atom, initial_, value)) {
        continue;
      }
      const SourcePos pos = contingent_.problem.goal.pos;
      throw InputError(locate(contingent_.problem.file,
                              "goal atom " + task_.atomNames[atom] +
                                  " is unknown initially and no action changes or observes "
                                  "it: it can never become known",
                              pos.line, pos.column));
    }
  }
}

AtomId KnowledgeTask::findAtom(const std::string& name) const {
  const auto it = atomIds_.find(name);
  return it == atomIds_.end() ? -1 : it->second;
}

FluentId KnowledgeTask::findFluent(const std::string& name) const {
  const auto it = fluentIds_.find(name);
  return it == fluentIds_.end() ? -1 : it->second;
}

int KnowledgeTask::findOperator(const std::string& name) const {
  const auto it = operatorIds_.find(name);
  return it == operatorIds_.end() ? -1 : it->second.front();
}

const std::vector<int>& KnowledgeTask::variants(int op) const {
  return operatorIds_.at("(" + task_.operators[op].name + ")");
}

bool KnowledgeTask::known(AtomId atom, const Belief& belief, bool& value) {
  summarize(belief);
  value = (allWorlds_[atom >> 6] >> (atom & 63)) & 1u;
  return value || !((anyWorld_[atom >> 6] >> (atom & 63)) & 1u);
}

bool KnowledgeTask::kwHolds(AtomId atom, const Belief& belief) {
  bool value = false;
  if (known(atom, belief, value) && value) return true;
  const AtomId base = kwBase_[atom];
  return base == kNoBase || known(base, belief, value);
}

// K(p) for (k.p …), K(¬p) for (k-not.p …); an atom the grounder never reaches is known false.
bool KnowledgeTask::kQueryHolds(AtomId atom, const Belief& belief) {
  const Auxiliary& query = kQuery_[atom];
  bool value = false;
  if (query.base == kNoBase) return query.negated;
  return known(query.base, belief, value) && value != query.negated;
}

bool KnowledgeTask::kvHolds(AtomId atom, const Belief& belief) {
  bool value = false;
  if (known(atom, belief, value) && value) return true;
  return kvBase_[atom] != kNoBase && fluentKnown(kvBase_[atom], belief);
}

bool sameValue(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}

bool KnowledgeTask::pendingValue(const Belief& belief, FluentId& fluent, double& value) {
  summarize(belief);
  for (const AtomId k : knowledgeAtoms_) {
    const FluentId sensed = kvBase_[k];
    if (sensed < 0 || !bit(allWorlds_, k)) continue;
    const double first = world(belief.front()).fluent(sensed);
    const bool differs = std::any_of(belief.begin(), belief.end(), [&](std::uint32_t w) {
      return !sameValue(world(w).fluent(sensed), first);
    });
    if (!differs) continue;
    fluent = sensed;
    value = first;
    return true;
  }
  return false;
}

bool KnowledgeTask::knowsValue(FluentId fluent, const Belief& belief) {
  if (fluentKnown(fluent, belief)) return true;
  summarize(belief);
  return std::any_of(knowledgeAtoms_.begin(), knowledgeAtoms_.end(),
                     [&](AtomId k) { return kvBase_[k] == fluent && bit(allWorlds_, k); });
}

void KnowledgeTask::splitValue(FluentId fluent, double value, const Belief& belief, Belief& equal,
                               Belief& other) {
  equal.clear();
  other.clear();
  for (const std::uint32_t w : belief) {
    (sameValue(world(w).fluent(fluent), value) ? equal : other).push_back(w);
  }
  if (!equal.empty()) canonicalize(equal);
  if (!other.empty()) canonicalize(other);
}

bool KnowledgeTask::fluentKnown(FluentId fluent, const Belief& belief) {
  const double first = world(belief.front()).fluent(fluent);
  if (std::isnan(first)) return false;
  return std::all_of(belief.begin(), belief.end(),
                     [&](std::uint32_t w) { return world(w).fluent(fluent) == first; });
}

bool KnowledgeTask::knowsWhether(AtomId atom, const Belief& belief) {
  bool value = false;
  if (known(atom, belief, value)) return true;
  for (const AtomId k : knowledgeAtoms_) {
    if (kwBase_[k] == atom) return known(k, belief, value) && value;
  }
  return false;
}

bool KnowledgeTask::allWorlds(const Condition& tests, const Belief& belief) {
  if (tests.fluentTests.empty() && tests.numericTests.empty() && tests.moduleChecks.empty()) {
    return true;
  }
  return std::all_of(belief.begin(), belief.end(),
                     [&](std::uint32_t w) { return evaluator_.holds(tests, world(w)); });
}

bool KnowledgeTask::holds(const Condition& condition, const Belief& belief) {
  return holdsAtoms(condition, belief) &&
         std::all_of(belief.begin(), belief.end(),
                     [&](std::uint32_t w) { return evaluator_.holds(condition, world(w)); });
}

bool KnowledgeTask::applicable(int op, const Belief& belief) {
  return holdsAtoms(task_.operators[op].precondition, belief) &&
         allWorlds(preconditionTests_[op], belief);
}

bool KnowledgeTask::holdsAtoms(const Condition& condition, const Belief& belief) {
  bool value = false;
  for (const AtomId atom : condition.positive) {
    if (kQuery_[atom].base != kNotKnowledge) {
      if (!kQueryHolds(atom, belief)) return false;
    } else if (kwBase_[atom] != kNotKnowledge) {
      if (!kwHolds(atom, belief)) return false;
    } else if (kvBase_[atom] != kNotKnowledge) {
      if (!kvHolds(atom, belief)) return false;
    } else if (!known(atom, belief, value) || !value) {
      return false;
    }
  }
  for (const AtomId atom : condition.negative) {
    if (kQuery_[atom].base != kNotKnowledge) {
      if (kQueryHolds(atom, belief)) return false;
    } else if (kwBase_[atom] != kNotKnowledge) {
      if (kwHolds(atom, belief)) return false;
    } else if (kvBase_[atom] != kNotKnowledge) {
      if (kvHolds(atom, belief)) return false;
    } else if (!known(atom, belief, value) || value) {
      return false;
    }
  }
  return true;
}

bool KnowledgeTask::isGoal(const Belief& belief) {
  if (task_.goal.empty()) return false;
  if (task_.goal.size() == 1) {
    return holdsAtoms(task_.goal[0], belief) && allWorlds(goalTests_, belief);
  }
  // A disjunctive goal must hold in every world, not necessarily by the same disjunct.
  return std::all_of(belief.begin(), belief.end(),
                     [&](std::uint32_t w) { return evaluator_.isGoal(world(w)); });
}

bool KnowledgeTask::apply(int op, const Belief& belief, Belief& out, std::uint32_t sample) {
  attachments_->setSample(sample);
  const bool feasible = applyInWorlds(op, belief, out, true);
  attachments_->setSample(0);
  return feasible;
}

void KnowledgeTask::preview(int op, const Belief& belief, Belief& out) {
  applyInWorlds(op, belief, out, false);
}

bool KnowledgeTask::callsEffectApplicator(int op) const {
  const Operator& o = task_.operators[op];
  return !o.effect.moduleCalls.empty() ||
         std::any_of(o.conditional.begin(), o.conditional.end(),
                     [](const ConditionalEffect& c) { return !c.effect.moduleCalls.empty(); });
}

bool KnowledgeTask::applyInWorlds(int op, const Belief& belief, Belief& out,
                                  bool effectApplicators) {
  out.clear();
  for (const std::uint32_t w : belief) {
    if (!evaluator_.apply(task_.operators[op], world(w), scratch_, effectApplicators)) {
      return false;
    }
    storeForgetting(out);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  canonicalize(out);
  return true;
}

// Atoms true in some world (`anyWorld_`) and in every world (`allWorlds_`) of `belief`; kept
// until asked about another knowledge state.
void KnowledgeTask::summarize(const Belief& belief) {
  if (summarized_ == belief && !anyWorld_.empty()) return;
  summarized_ = belief;
  const std::size_t words = evaluator_.layout().atomBitset(1);
  anyWorld_.assign(words, 0);
  allWorlds_.assign(words, ~std::uint64_t{0});
  for (const std::uint32_t w : belief) {
    const std::uint64_t* bits = world(w).words();
    for (std::size_t i = 0; i < words; ++i) {
      anyWorld_[i] |= bits[i];
      allWorlds_[i] &= bits[i];
    }
  }
}

// Drops Kw/Kv atoms whose subject is known anyway, so equal knowledge has one representation.
void KnowledgeTask::canonicalize(Belief& belief) {
  summarize(belief);
  bool changed = false;
  for (const AtomId k : knowledgeAtoms_) {
    if (!bit(anyWorld_, k)) continue;
    const AtomId base = kwBase_[k];
    const bool subjectKnown =
        base != kNotKnowledge ? base == kNoBase || bit(allWorlds_, base) || !bit(anyWorld_, base)
                              : kvBase_[k] != kNoBase && fluentKnown(kvBase_[k], belief);
    if (!subjectKnown) continue;
    for (std::uint32_t& w : belief) {
      const StateView view = world(w);
      if (!view.atom(k)) continue;
      std::copy_n(view.words(), scratch_.size(), scratch_.begin());
      setBit(scratch_, k, false);
      w = store(scratch_);
    }
    changed = true;
  }
  if (changed) {
    std::sort(belief.begin(), belief.end());
    belief.erase(std::unique(belief.begin(), belief.end()), belief.end());
  }
}

AtomId KnowledgeTask::pendingObservation(const Belief& belief) {
  summarize(belief);
  for (const AtomId k : knowledgeAtoms_) {
    const AtomId base = kwBase_[k];
    if (base < 0 || !bit(allWorlds_, k)) continue;
    if (bit(anyWorld_, base) && !bit(allWorlds_, base)) return base;
  }
  return -1;
}

// del(Kf, p) (thesis §3.3.1): the successor world in `scratch_` is stored without its (kf-del.…)
// markers, and for each marker every world stored for it so far where p is true (false for
// kf-del-not) gains a twin where p is false (true), so K(p) (K(¬p)) no longer holds. A
// non-deterministic effect's marker (nondet-del.… / nondet-add.…) adds the same twins: the twin
// is the world where the effect took place.
void KnowledgeTask::storeForgetting(Belief& out) {
  forgotten_.clear();
  for (const AtomId marker : forgetAtoms_) {
    if (!bit(scratch_, marker)) continue;
    setBit(scratch_, marker, false);
    forgotten_.push_back(marker);
  }
  const std::size_t first = out.size();
  out.push_back(store(scratch_));
  for (const AtomId marker : forgotten_) {
    const Auxiliary& forget = forget_[marker];
    if (forget.base < 0) continue;
    const std::size_t end = out.size();
    for (std::size_t i = first; i < end; ++i) {
      std::copy_n(world(out[i]).words(), scratch_.size(), scratch_.begin());
      if (bit(scratch_, forget.base) == forget.negated) continue;
      setBit(scratch_, forget.base, forget.negated);
      out.push_back(store(scratch_));
    }
  }
}

void KnowledgeTask::split(AtomId atom, const Belief& belief, Belief& onTrue, Belief& onFalse) {
  onTrue.clear();
  onFalse.clear();
  for (const std::uint32_t w : belief) (world(w).atom(atom) ? onTrue : onFalse).push_back(w);
  if (!onTrue.empty()) canonicalize(onTrue);
  if (!onFalse.empty()) canonicalize(onFalse);
}

std::uint32_t KnowledgeTask::hiddenWorld(const HiddenState& hidden, const std::string& file) {
  std::fill(scratch_.begin(), scratch_.end(), 0);
  std::copy_n(world(initial_.front()).words(), scratch_.size(), scratch_.begin());
  // Atoms that differ between initial worlds are the uncertain ones: start them all false.
  for (std::size_t a = 0; a < task_.atomNames.size(); ++a) {
    bool value = false;
    if (!known(static_cast<AtomId>(a), initial_, value)) {
      setBit(scratch_, static_cast<AtomId>(a), false);
    }
  }
  for (const GroundAtom& atom : hidden.atoms) {
    const AtomId id =
        findAtom(describeAtom(contingent_.domain, contingent_.problem, atom.predicate, atom.args));
    if (id < 0) {
      throw InputError(locate(
          file,
          "hidden state is not one of the initial worlds the knowledge admits: " +
              describeAtom(contingent_.domain, contingent_.problem, atom.predicate, atom.args) +
              " can never be true",
          hidden.pos.line, hidden.pos.column));
    }
    setBit(scratch_, id, true);
  }
  const std::uint32_t id = worlds_.find(scratch_);
  if (id == PackedSet::kMissing || !std::binary_search(initial_.begin(), initial_.end(), id)) {
    throw InputError(locate(file,
                            "hidden state is not one of the initial worlds the knowledge admits",
                            hidden.pos.line, hidden.pos.column));
  }
  return id;
}

bool KnowledgeTask::holdsIn(const Condition& condition, std::uint32_t w) {
  return evaluator_.holds(condition, world(w));
}

bool KnowledgeTask::isGoalIn(std::uint32_t w) {
  return evaluator_.isGoal(world(w));
}

std::uint32_t KnowledgeTask::applyIn(int op, std::uint32_t w, std::uint32_t sample) {
  attachments_->setSample(sample);
  const bool feasible = evaluator_.apply(task_.operators[op], world(w), scratch_);
  attachments_->setSample(0);
  if (!feasible) return PackedSet::kMissing;
  // Forgetting changes what the agent knows, not the true world; a non-deterministic effect
  // takes place in it or not, as nature (the seeded generator) chooses.
  for (const AtomId marker : forgetAtoms_) {
    if (!bit(scratch_, marker)) continue;
    setBit(scratch_, marker, false);
    const Auxiliary& effect = forget_[marker];
    if (effect.nondeterministic && effect.base >= 0 && (outcomes_() & 1) != 0) {
      setBit(scratch_, effect.base, effect.negated);
    }
  }
  return store(scratch_);
}

std::uint64_t KnowledgeTask::symbolicKey(const Belief& belief) {
  if (attachmentWritten_.empty()) {
    attachmentWritten_.assign(task_.fluentNames.size() + 1, false);  // +1: never empty again
    for (const GroundModuleCall& call : task_.moduleCalls) {
      for (const FluentId f : call.writes) attachmentWritten_[static_cast<std::size_t>(f)] = true;
    }
  }
  if (symbolicHash_.size() < worlds_.size()) symbolicHash_.resize(worlds_.size(), 0);
  const std::size_t fluentOffset = evaluator_.layout().fluentOffset();
  std::uint64_t key = 0;
  for (const std::uint32_t w : belief) {
    std::uint64_t& term = symbolicHash_[w];
    if (term == 0) {
      const std::span<const std::uint64_t> words = worlds_.get(w);
      std::uint64_t h = 1469598103934665603ull;
      for (std::size_t i = 0; i < words.size(); ++i) {
        if (i >= fluentOffset && attachmentWritten_[i - fluentOffset]) continue;
        h = (h ^ words[i]) * 1099511628211ull;
      }
      // splitmix64's finaliser, so that the sum over worlds mixes well; never 0.
      h ^= h >> 30;
      h *= 0xbf58476d1ce4e5b9ull;
      h ^= h >> 27;
      h *= 0x94d049bb133111ebull;
      h ^= h >> 31;
      term = h | 1u;
    }
    key += term;
  }
  return key;
}

}  // namespace kaboum::symbolic
