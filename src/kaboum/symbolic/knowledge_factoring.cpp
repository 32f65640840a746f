#include "kaboum/symbolic/knowledge_factoring.hpp"

#include <algorithm>
#include <numeric>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {
namespace {

struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Condition checkers stay: without fluents they read nothing but their arguments, so they answer
// the same in every world.
bool hasTests(const Condition& c) {
  return !c.fluentTests.empty() || !c.numericTests.empty();
}

bool callsEffectApplicators(const Operator& op) {
  return !op.effect.moduleCalls.empty() ||
         std::any_of(op.conditional.begin(), op.conditional.end(),
                     [](const ConditionalEffect& c) { return !c.effect.moduleCalls.empty(); });
}

std::string inexactReason(const GroundTask& task) {
  if (!task.fluentNames.empty()) return "the task has fluents, whose values differ per world";
  if (hasTests(task.goal.conjunction)) return "the goal has numeric tests";
  for (const std::vector<Condition>& clause : task.goal.clauses) {
    if (std::any_of(clause.begin(), clause.end(), hasTests)) return "the goal has numeric tests";
  }
  for (const Operator& op : task.operators) {
    if (callsEffectApplicators(op)) return "action (" + op.name + ") calls effect applicators";
    if (hasTests(op.precondition)) return "action (" + op.name + ") has numeric tests";
    for (const ConditionalEffect& effect : op.conditional) {
      for (const Condition& c : effect.disjuncts) {
        if (hasTests(c)) return "a conditional effect of (" + op.name + ") has numeric tests";
      }
    }
  }
  return "";
}

}  // namespace

KnowledgeRepresentation parseKnowledgeRepresentation(const std::string& name) {
  if (name == "auto") return KnowledgeRepresentation::Automatic;
  if (name == "explicit") return KnowledgeRepresentation::Explicit;
  if (name == "factored") return KnowledgeRepresentation::Factored;
  throw InputError("unknown knowledge representation '" + name +
                   "' (expected auto, explicit or factored)");
}

KnowledgeFactoring factorKnowledge(const GroundTask& task,
                                   std::span<const std::vector<AtomId>> correlated,
                                   std::span<const AtomId> forgetBase) {
  KnowledgeFactoring out;
  const std::size_t atoms = task.atomNames.size();
  out.componentOf.assign(atoms, -1);
  out.inexact = inexactReason(task);
  if (!out.inexact.empty()) return out;
  std::vector<char> uncertain(atoms, 0);
  DisjointSets sets(atoms);
  for (const std::vector<AtomId>& group : correlated) {
    for (const AtomId a : group) {
      uncertain[a] = 1;
      sets.join(a, group.front());
    }
  }
  for (const AtomId base : forgetBase) {
    if (base >= 0) uncertain[base] = 1;
  }
  // What an effect list changes: its atoms and the subjects its forgetting markers make unknown.
  const auto forEachChanged = [&](const EffectList& effect, const auto& visit) {
    for (const std::vector<AtomId>* list : {&effect.adds, &effect.deletes}) {
      for (const AtomId a : *list) {
        visit(a);
        if (forgetBase[a] >= 0) visit(forgetBase[a]);
      }
    }
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (const Operator& op : task.operators) {
      for (const ConditionalEffect& effect : op.conditional) {
        AtomId reader = -1;
        for (const Condition& c : effect.disjuncts) {
          for (const std::vector<AtomId>* list : {&c.positive, &c.negative}) {
            for (const AtomId a : *list) {
              if (!uncertain[a]) continue;
              if (reader >= 0) sets.join(a, reader);
              reader = a;
            }
          }
        }
        if (reader < 0) continue;
        forEachChanged(effect.effect, [&](AtomId a) {
          if (!uncertain[a]) changed = true;
          uncertain[a] = 1;
          if (sets.find(a) != sets.find(reader)) changed = true;
          sets.join(a, reader);
        });
      }
    }
  }
  // A goal clause holds in every world when it holds in every world of the one component it reads
  // (with the known core), so it joins the components of its uncertain atoms.
  for (const std::vector<Condition>& clause : task.goal.clauses) {
    AtomId reader = -1;
    for (const Condition& c : clause) {
      for (const std::vector<AtomId>* list : {&c.positive, &c.negative}) {
        for (const AtomId a : *list) {
          if (!uncertain[a]) continue;
          if (reader >= 0) sets.join(a, reader);
          reader = a;
        }
      }
    }
    out.clauseComponent.push_back(reader);  // an atom for now, its component below
  }
  std::vector<int> index(atoms, -1);
  for (std::size_t a = 0; a < atoms; ++a) {
    if (!uncertain[a]) continue;
    int& component = index[sets.find(static_cast<int>(a))];
    if (component < 0) component = out.components++;
    out.componentOf[a] = component;
  }
  for (int& reader : out.clauseComponent) {
    if (reader >= 0) reader = out.componentOf[reader];
  }
  return out;
}

}  // namespace kaboum::symbolic
