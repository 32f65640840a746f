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
                             const ProcedureRegistry& procedures, std::size_t maxWorlds,
                             KnowledgeRepresentation representation)
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
  goalTests_ = testsOnly(task_.goal.conjunction);
  scratch_.resize(evaluator_.layout().words());
  composed_.resize(scratch_.size());
  setUpFactoring(representation);
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
  for (std::size_t a = 0; a < fixed.size(); ++a) {
    if (fixed[a] == 1) setBit(base, static_cast<AtomId>(a), true);
  }
  // Every assignment to `atoms` that no clause forbids, on top of `base` restricted to `mask`
  // (none: the whole world), into `out`.
  std::vector<std::uint64_t> world(base.size());
  const auto enumerate = [&](std::span<const AtomId> atoms, std::span<const std::uint64_t> mask,
                             Belief& out) {
    const std::function<void(std::size_t)> assign = [&](std::size_t index) {
      if (index == atoms.size()) {
        for (std::size_t i = 0; i < world.size(); ++i) {
          world[i] = mask.empty() ? base[i] : base[i] & mask[i];
        }
        for (const AtomId atom : atoms) setBit(world, atom, value[atom] == 1);
        out.push_back(store(world));
        if (out.size() > maxWorlds) {
          throw InputError(locate(file,
                                  "the initial knowledge admits more than " +
                                      std::to_string(maxWorlds) + " possible worlds" +
                                      (mask.empty() ? "" : " in one independent component"),
                                  contingent_.initPos.line, contingent_.initPos.column));
        }
        return;
      }
      const AtomId atom = atoms[index];
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
    if (out.empty()) {
      throw InputError(locate(file,
                              "contradictory initial knowledge: no world satisfies the 'oneof', "
                              "'or' and known atoms of :init",
                              contingent_.initPos.line, contingent_.initPos.column));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  if (!factored_) {
    enumerate(variables, {}, initial_);
    canonicalize(initial_);
    return;
  }
  Belief core;
  enumerate({}, coreMask_, core);
  initial_.push_back(core.front());
  for (int c = 0; c < factoring_.components; ++c) {
    std::vector<AtomId> atoms;
    for (const AtomId atom : variables) {
      if (factoring_.componentOf[atom] == c) atoms.push_back(atom);
    }
    local_.clear();
    enumerate(atoms, componentMask_[c], local_);
    initial_.push_back(internLocal(local_));
  }
  canonicalize(initial_);
}

// Chooses the representation and, when factored, the atoms of the core and of each component and
// the components each operator changes.
void KnowledgeTask::setUpFactoring(KnowledgeRepresentation representation) {
  if (representation == KnowledgeRepresentation::Explicit) return;
  std::vector<std::vector<AtomId>> correlated;
  for (const KnowledgeConstraint& constraint : contingent_.constraints) {
    if (constraint.kind == KnowledgeConstraint::Kind::KnownFalse) continue;
    std::vector<AtomId> group;
    for (const InitialLiteral& literal : constraint.literals) {
      const AtomId id = findAtom(describeAtom(contingent_.domain, contingent_.problem,
                                              literal.atom.predicate, literal.atom.args));
      if (id >= 0) group.push_back(id);
    }
    if (!group.empty()) correlated.push_back(std::move(group));
  }
  std::vector<AtomId> forgetBase(task_.atomNames.size(), -1);
  for (const AtomId marker : forgetAtoms_) forgetBase[marker] = forget_[marker].base;
  factoring_ = factorKnowledge(task_, correlated, forgetBase);
  if (representation == KnowledgeRepresentation::Factored && !factoring_.inexact.empty()) {
    throw InputError(
        locate(contingent_.problem.file, "factored knowledge is not exact for this problem: " +
                                             factoring_.inexact + " (use explicit)"));
  }
  factored_ = factoring_.inexact.empty() &&
              (representation == KnowledgeRepresentation::Factored || factoring_.components >= 2);
  if (!factored_) return;
  const std::size_t words = evaluator_.layout().words();
  coreMask_.assign(words, ~std::uint64_t{0});
  componentMask_.assign(static_cast<std::size_t>(factoring_.components),
                        std::vector<std::uint64_t>(words, 0));
  for (std::size_t a = 0; a < task_.atomNames.size(); ++a) {
    const int c = factoring_.componentOf[a];
    if (c < 0) continue;
    setBit(coreMask_, static_cast<AtomId>(a), false);
    setBit(componentMask_[c], static_cast<AtomId>(a), true);
  }
  touched_.resize(task_.operators.size());
  for (std::size_t o = 0; o < task_.operators.size(); ++o) {
    std::vector<int>& touched = touched_[o];
    const auto mark = [&](const EffectList& effect) {
      for (const std::vector<AtomId>* list : {&effect.adds, &effect.deletes}) {
        for (const AtomId a : *list) {
          for (const AtomId changed : {a, forgetBase[a]}) {
            if (changed >= 0 && factoring_.componentOf[changed] >= 0) {
              touched.push_back(factoring_.componentOf[changed]);
            }
          }
        }
      }
    };
    mark(task_.operators[o].effect);
    for (const ConditionalEffect& c : task_.operators[o].conditional) mark(c.effect);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  }
  setUpSettling();
}

// A goal atom that is unknown initially, that no operator changes and that no operator observes
// can never become known: reject the problem instead of searching forever.
void KnowledgeTask::checkGoalKnowable() {
  if (!task_.goal.reachable) return;
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
  const Condition& goal = task_.goal.conjunction;
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
  if (factored_ && !belief.empty()) {
    // Factored tests are condition checkers, which answer the same in every world: ask one.
    compose(belief, -1, 0);
    return evaluator_.holds(tests, evaluator_.view(composed_));
  }
  return std::all_of(belief.begin(), belief.end(),
                     [&](std::uint32_t w) { return evaluator_.holds(tests, world(w)); });
}

bool KnowledgeTask::holds(const Condition& condition, const Belief& belief) {
  if (factored_) return holdsAtoms(condition, belief) && allWorlds(condition, belief);
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
  const Goal& goal = task_.goal;
  if (!goal.reachable || !holdsAtoms(goal.conjunction, belief) || !allWorlds(goalTests_, belief)) {
    return false;
  }
  for (std::size_t k = 0; k < goal.clauses.size(); ++k) {
    if (!clauseHolds(k, belief)) return false;
  }
  return true;
}

// A goal clause must hold in every world, not necessarily by the same condition. Factored, the
// worlds that differ in the clause's atoms are the local worlds of the one component it reads.
bool KnowledgeTask::clauseHolds(std::size_t clause, const Belief& belief) {
  const std::vector<Condition>& conditions = task_.goal.clauses[clause];
  if (!factored_ || belief.empty()) {
    return std::all_of(belief.begin(), belief.end(),
                       [&](std::uint32_t w) { return evaluator_.holdsAny(conditions, world(w)); });
  }
  const int c = factoring_.clauseComponent[clause];
  if (c < 0) {
    compose(belief, -1, 0);
    return evaluator_.holdsAny(conditions, evaluator_.view(composed_));
  }
  for (const std::uint32_t w : localWorlds_[belief[static_cast<std::size_t>(c) + 1]]) {
    compose(belief, c, w);
    if (!evaluator_.holdsAny(conditions, evaluator_.view(composed_))) return false;
  }
  return true;
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
  if (factored_ && !belief.empty()) {
    applyFactored(op, belief, out, effectApplicators);
    return true;  // a factored task calls no effect applicators, so nothing is infeasible
  }
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
  if (factored_ && !belief.empty()) {
    // Components have disjoint atoms, zero in the core: unions and intersections per component.
    const std::uint64_t* core = world(belief.front()).words();
    anyWorld_.assign(core, core + words);
    allWorlds_.assign(core, core + words);
    for (int c = 0; c < factoring_.components; ++c) {
      const Belief& locals = localWorlds_[belief[static_cast<std::size_t>(c) + 1]];
      for (std::size_t i = 0; i < words; ++i) {
        std::uint64_t any = 0;
        std::uint64_t all = componentMask_[c][i];
        for (const std::uint32_t w : locals) {
          any |= world(w).words()[i];
          all &= world(w).words()[i];
        }
        anyWorld_[i] |= any;
        allWorlds_[i] |= all;
      }
    }
    return;
  }
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
  if (factored_ && !belief.empty()) {
    canonicalizeFactored(belief);
    return;
  }
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
// With a `mask`, the world is stored restricted to it and only subjects inside it are forgotten.
void KnowledgeTask::storeForgetting(Belief& out, std::span<const std::uint64_t> mask) {
  forgotten_.clear();
  for (const AtomId marker : forgetAtoms_) {
    if (!bit(scratch_, marker)) continue;
    setBit(scratch_, marker, false);
    const AtomId base = forget_[marker].base;
    if (mask.empty() || (base >= 0 && bit(mask, base))) forgotten_.push_back(marker);
  }
  if (!mask.empty()) {
    for (std::size_t i = 0; i < scratch_.size(); ++i) scratch_[i] &= mask[i];
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
  if (factored_ && !belief.empty()) {
    splitFactored(atom, belief, onTrue, onFalse);
    return;
  }
  onTrue.clear();
  onFalse.clear();
  for (const std::uint32_t w : belief) (world(w).atom(atom) ? onTrue : onFalse).push_back(w);
  if (!onTrue.empty()) canonicalize(onTrue);
  if (!onFalse.empty()) canonicalize(onFalse);
}

std::uint32_t KnowledgeTask::hiddenWorld(const HiddenState& hidden, const std::string& file) {
  if (factored_) return hiddenWorldFactored(hidden, file);
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
  if (factored_) {  // no effect applicators: the ids are the knowledge
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint32_t id : belief) h = (h ^ id) * 1099511628211ull;
    return h;
  }
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

// Factored knowledge states -----------------------------------------------------------------

double KnowledgeTask::possibleWorlds(const Belief& belief) const {
  if (!factored_ || belief.empty()) return static_cast<double>(belief.size());
  double product = 1.0;
  for (std::size_t c = 1; c < belief.size(); ++c) {
    product *= static_cast<double>(localWorlds_[belief[c]].size());
  }
  return product;
}

std::uint32_t KnowledgeTask::internLocal(Belief& localWorlds) {
  std::uint64_t h = 1469598103934665603ull;
  for (const std::uint32_t w : localWorlds) h = (h ^ w) * 1099511628211ull;
  std::vector<std::uint32_t>& bucket = localIds_[h];
  for (const std::uint32_t id : bucket) {
    if (localWorlds_[id] == localWorlds) return id;
  }
  const auto id = static_cast<std::uint32_t>(localWorlds_.size());
  localWorlds_.push_back(localWorlds);
  bucket.push_back(id);
  return id;
}

// `composed_` := the core of `belief` with local world `local` of `component` (none if -1) and the
// first local world of each other component when `component` is -1 or for heuristicWorlds.
void KnowledgeTask::compose(const Belief& belief, int component, std::uint32_t local) {
  const std::uint64_t* core = world(belief.front()).words();
  std::copy_n(core, composed_.size(), composed_.begin());
  const auto add = [&](std::uint32_t w) {
    const std::uint64_t* words = world(w).words();
    for (std::size_t i = 0; i < composed_.size(); ++i) composed_[i] |= words[i];
  };
  for (int c = 0; c < factoring_.components; ++c) {
    add(c == component ? local : localWorlds_[belief[static_cast<std::size_t>(c) + 1]].front());
  }
}

const Belief& KnowledgeTask::heuristicWorlds(const Belief& belief) {
  if (!factored_ || belief.empty()) return belief;
  sample_.clear();
  for (int c = 0; c < factoring_.components; ++c) {
    const Belief& locals = localWorlds_[belief[static_cast<std::size_t>(c) + 1]];
    for (std::size_t j = c == 0 ? 0 : 1; j < locals.size(); ++j) {
      compose(belief, c, locals[j]);
      sample_.push_back(store(composed_));
    }
  }
  return sample_;
}

// An operator's effect on a component depends only on the core and that component's atoms
// (knowledge_factoring.hpp), so it is applied to each local world once, with the core; the core's
// successor is the same in every world.
void KnowledgeTask::applyFactored(int op, const Belief& belief, Belief& out,
                                  bool effectApplicators) {
  const Operator& o = task_.operators[op];
  out.assign(belief.begin(), belief.end());
  compose(belief, -1, 0);
  evaluator_.apply(o, evaluator_.view(composed_), scratch_, effectApplicators);
  local_.clear();
  storeForgetting(local_, coreMask_);
  out.front() = local_.front();
  Belief& next = splitWorlds_[0];
  for (const int c : touched_[op]) {
    next.clear();
    for (const std::uint32_t w : localWorlds_[belief[static_cast<std::size_t>(c) + 1]]) {
      compose(belief, c, w);
      evaluator_.apply(o, evaluator_.view(composed_), scratch_, effectApplicators);
      storeForgetting(next, componentMask_[c]);
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    out[static_cast<std::size_t>(c) + 1] = internLocal(next);
  }
  canonicalize(out);
}

// As canonicalize: Kw atoms whose subject is known are cleared, in the core or in the local
// worlds of their component.
void KnowledgeTask::canonicalizeFactored(Belief& belief) {
  summarize(belief);
  for (const AtomId k : knowledgeAtoms_) {
    if (!bit(anyWorld_, k)) continue;
    const AtomId base = kwBase_[k];
    if (base == kNotKnowledge) continue;  // Kv: a factored task has no fluents
    if (base != kNoBase && !bit(allWorlds_, base) && bit(anyWorld_, base)) continue;
    const int c = factoring_.componentOf[k];
    if (c < 0) {
      std::copy_n(world(belief.front()).words(), scratch_.size(), scratch_.begin());
      setBit(scratch_, k, false);
      belief.front() = store(scratch_);
      continue;
    }
    local_.clear();
    for (const std::uint32_t w : localWorlds_[belief[static_cast<std::size_t>(c) + 1]]) {
      std::copy_n(world(w).words(), scratch_.size(), scratch_.begin());
      setBit(scratch_, k, false);
      local_.push_back(store(scratch_));
    }
    std::sort(local_.begin(), local_.end());
    local_.erase(std::unique(local_.begin(), local_.end()), local_.end());
    belief[static_cast<std::size_t>(c) + 1] = internLocal(local_);
  }
}

// Only the atom's component splits; an atom of the core is known, so one side is empty.
void KnowledgeTask::splitFactored(AtomId atom, const Belief& belief, Belief& onTrue,
                                  Belief& onFalse) {
  onTrue.clear();
  onFalse.clear();
  const int c = factoring_.componentOf[atom];
  if (c < 0) {
    (world(belief.front()).atom(atom) ? onTrue : onFalse) = belief;
    return;
  }
  Belief& trueWorlds = splitWorlds_[0];
  Belief& falseWorlds = splitWorlds_[1];
  trueWorlds.clear();
  falseWorlds.clear();
  for (const std::uint32_t w : localWorlds_[belief[static_cast<std::size_t>(c) + 1]]) {
    (world(w).atom(atom) ? trueWorlds : falseWorlds).push_back(w);
  }
  for (auto [side, worlds] : {std::pair{&onTrue, &trueWorlds}, {&onFalse, &falseWorlds}}) {
    if (worlds->empty()) continue;
    *side = belief;
    (*side)[static_cast<std::size_t>(c) + 1] = internLocal(*worlds);
    canonicalize(*side);
  }
}

// The hidden state must agree with the known core and give each component one of its initial
// local worlds; the atoms it leaves out keep their known values.
std::uint32_t KnowledgeTask::hiddenWorldFactored(const HiddenState& hidden,
                                                 const std::string& file) {
  summarize(initial_);
  std::copy_n(world(initial_.front()).words(), scratch_.size(), scratch_.begin());
  std::copy(allWorlds_.begin(), allWorlds_.end(), scratch_.begin());
  const auto reject = [&](const std::string& why) {
    return InputError(
        locate(file, "hidden state is not one of the initial worlds the knowledge admits" + why,
               hidden.pos.line, hidden.pos.column));
  };
  for (const GroundAtom& atom : hidden.atoms) {
    const std::string name =
        describeAtom(contingent_.domain, contingent_.problem, atom.predicate, atom.args);
    const AtomId id = findAtom(name);
    if (id < 0) throw reject(": " + name + " can never be true");
    setBit(scratch_, id, true);
  }
  const std::vector<std::uint64_t> whole = scratch_;
  const std::uint64_t* core = world(initial_.front()).words();
  for (std::size_t i = 0; i < whole.size(); ++i) {
    if ((whole[i] & coreMask_[i]) != core[i]) throw reject("");
  }
  for (int c = 0; c < factoring_.components; ++c) {
    for (std::size_t i = 0; i < whole.size(); ++i) scratch_[i] = whole[i] & componentMask_[c][i];
    const Belief& locals = localWorlds_[initial_[static_cast<std::size_t>(c) + 1]];
    const std::uint32_t id = worlds_.find(scratch_);
    if (id == PackedSet::kMissing || !std::binary_search(locals.begin(), locals.end(), id)) {
      throw reject("");
    }
  }
  return store(whole);
}

// Which component each atom's value or knowledge belongs to, which components each operator reads
// (precondition) or writes, and the index of the relaxed reachability of sharingKey: operators by
// the plain literal they wait for, and their knowledge literals.
void KnowledgeTask::setUpSettling() {
  ownerOf_ = factoring_.componentOf;
  for (std::size_t a = 0; a < ownerOf_.size(); ++a) {
    for (const AtomId base : {kwBase_[a], kQuery_[a].base, forget_[a].base}) {
      if (base >= 0 && factoring_.componentOf[base] >= 0) {
        ownerOf_[a] = factoring_.componentOf[base];
      }
    }
  }
  const std::size_t atoms = task_.atomNames.size();
  const std::size_t operators = task_.operators.size();
  opReadsOrWrites_.resize(operators);
  waitingFor_.assign(2 * atoms, {});
  knowledgeLiterals_.resize(operators);
  for (std::size_t o = 0; o < operators; ++o) {
    const Operator& op = task_.operators[o];
    std::vector<int>& components = opReadsOrWrites_[o];
    const auto add = [&](const std::vector<AtomId>& list) {
      for (const AtomId a : list) {
        if (ownerOf_[a] >= 0) components.push_back(ownerOf_[a]);
      }
    };
    add(op.effect.adds);
    add(op.effect.deletes);
    add(op.precondition.positive);
    add(op.precondition.negative);
    for (const ConditionalEffect& c : op.conditional) {
      add(c.effect.adds);
      add(c.effect.deletes);
      for (const Condition& d : c.disjuncts) {
        add(d.positive);
        add(d.negative);
      }
    }
    std::sort(components.begin(), components.end());
    components.erase(std::unique(components.begin(), components.end()), components.end());
    for (const bool positive : {true, false}) {
      for (const AtomId a : positive ? op.precondition.positive : op.precondition.negative) {
        const bool knowledge = kQuery_[a].base != kNotKnowledge || kwBase_[a] != kNotKnowledge ||
                               kvBase_[a] != kNotKnowledge;
        if (knowledge) {
          knowledgeLiterals_[o].push_back({a, positive});
        } else {
          waitingFor_[2 * static_cast<std::size_t>(a) + (positive ? 0 : 1)].push_back(
              static_cast<int>(o));
        }
      }
    }
  }
}

// The current truth of a knowledge atom (K, Kw or Kv query) as holdsAtoms reads it.
bool KnowledgeTask::knowledgeLiteralHolds(AtomId atom, const Belief& belief) {
  if (kQuery_[atom].base != kNotKnowledge) return kQueryHolds(atom, belief);
  if (kwBase_[atom] != kNotKnowledge) return kwHolds(atom, belief);
  return kvHolds(atom, belief);
}

// A delete relaxation from `belief` (an atom may become true if it is true in some world or a
// reached action adds it; false likewise) in which the components not yet unsettled keep their
// knowledge: their knowledge literals are read as they are now, the others may go either way.
// Reaching an action unsettles the components it touches, which only widens the relaxation, so
// one monotone pass over a worklist finds the fixpoint (a greatest fixpoint of the settled set:
// an action that would first touch a settled component would have been reached).
void KnowledgeTask::sharingKey(const Belief& belief, Belief& key) {
  key = belief;
  if (!factored_ || belief.empty()) return;
  summarize(belief);
  unsettled_.assign(static_cast<std::size_t>(factoring_.components), 0);
  const auto unsettleOwner = [&](AtomId a) {
    if (ownerOf_[a] >= 0) unsettled_[ownerOf_[a]] = 1;
  };
  const auto unsettleReadBy = [&](const Condition& c) {
    for (const AtomId a : c.positive) unsettleOwner(a);
    for (const AtomId a : c.negative) unsettleOwner(a);
  };
  unsettleReadBy(task_.goal.conjunction);
  for (const std::vector<Condition>& clause : task_.goal.clauses) {
    for (const Condition& c : clause) unsettleReadBy(c);
  }
  for (const AtomId k : knowledgeAtoms_) {  // a pending observation is still to be branched on
    const AtomId base = kwBase_[k];
    if (base >= 0 && bit(allWorlds_, k) && bit(anyWorld_, base) && !bit(allWorlds_, base)) {
      unsettleOwner(base);
    }
  }
  int open = static_cast<int>(std::count(unsettled_.begin(), unsettled_.end(), 0));
  if (open == 0) return;
  const std::size_t atoms = task_.atomNames.size();
  const std::size_t operators = task_.operators.size();
  reachable_.resize(2 * atoms);
  for (std::size_t a = 0; a < atoms; ++a) {
    reachable_[2 * a] = bit(anyWorld_, static_cast<AtomId>(a));
    reachable_[2 * a + 1] = !bit(allWorlds_, static_cast<AtomId>(a));
  }
  // Per operator: plain literals not yet reachable plus knowledge literals of settled components
  // that fail now; ready at 0.
  missing_.assign(operators, 0);
  blockedBy_.resize(static_cast<std::size_t>(factoring_.components));
  for (std::vector<int>& ops : blockedBy_) ops.clear();
  for (std::size_t fact = 0; fact < 2 * atoms; ++fact) {
    if (reachable_[fact]) continue;
    for (const int o : waitingFor_[fact]) ++missing_[o];
  }
  for (std::size_t o = 0; o < operators; ++o) {
    for (const auto& [a, positive] : knowledgeLiterals_[o]) {
      const int c = ownerOf_[a];
      if (c < 0 || unsettled_[c] || knowledgeLiteralHolds(a, belief) == positive) continue;
      ++missing_[o];
      blockedBy_[c].push_back(static_cast<int>(o));
    }
  }
  worklist_.clear();
  for (std::size_t o = 0; o < operators; ++o) {
    if (missing_[o] == 0) worklist_.push_back(static_cast<int>(o));
  }
  const auto ready = [&](int o) {
    if (--missing_[o] == 0) worklist_.push_back(o);
  };
  const auto reach = [&](std::size_t fact) {
    if (reachable_[fact]) return;
    reachable_[fact] = 1;
    for (const int o : waitingFor_[fact]) ready(o);
  };
  const auto reachEffects = [&](const EffectList& effect) {
    for (const AtomId a : effect.adds) {
      reach(2 * static_cast<std::size_t>(a));
      const AtomId subject = forget_[a].base;
      if (subject >= 0) {
        reach(2 * static_cast<std::size_t>(subject));
        reach(2 * static_cast<std::size_t>(subject) + 1);
      }
    }
    for (const AtomId a : effect.deletes) reach(2 * static_cast<std::size_t>(a) + 1);
  };
  while (!worklist_.empty() && open > 0) {
    const int o = worklist_.back();
    worklist_.pop_back();
    for (const int c : opReadsOrWrites_[o]) {
      if (unsettled_[c]) continue;
      unsettled_[c] = 1;
      --open;
      for (const int blocked : blockedBy_[c]) ready(blocked);
    }
    const Operator& op = task_.operators[o];
    reachEffects(op.effect);
    for (const ConditionalEffect& c : op.conditional) reachEffects(c.effect);
  }
  for (int c = 0; c < factoring_.components; ++c) {
    if (!unsettled_[c]) key[static_cast<std::size_t>(c) + 1] = kSettled;
  }
}

}  // namespace kaboum::symbolic
