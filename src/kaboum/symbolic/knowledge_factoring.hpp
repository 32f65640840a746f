// Independent components of a contingent task's uncertain atoms (thesis §3.3.1; docs/contingent.md,
// "Knowledge representations"): knowledge states stored as a product of per-component world sets
// are exact when no action lets the value of one component's atoms decide another's.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

// How a knowledge state stores its possible worlds.
enum class KnowledgeRepresentation {
  Automatic,  // Factored when it is exact and there are at least two components, else Explicit
  Explicit,   // the set of whole worlds
  Factored,   // one known core and a set of local worlds per independent component
};

// Parses "auto", "explicit" or "factored"; throws InputError otherwise.
KnowledgeRepresentation parseKnowledgeRepresentation(const std::string& name);

struct KnowledgeFactoring {
  // Per atom: its component, or -1 for an atom known in every reachable knowledge state.
  std::vector<int> componentOf;
  int components = 0;
  std::vector<int> clauseComponent;  // per goal clause: the component it reads, or -1 (none)
  std::string inexact;  // why a factored representation would not be exact; "" if it is
};

// Uncertain atoms are those of `correlated` (each group: the atoms of one `oneof`/`or` clause, or
// one `unknown` atom) and the subjects of forgetting (`forgetBase`, per atom: the atom a
// del(Kf)/nondet marker makes unknown, -1 otherwise). A conditional effect whose condition reads an
// uncertain atom makes its effect atoms uncertain and joins them to that atom's component, up to a
// fixpoint; a goal clause joins the components it reads, so that it is checked in one component's
// local worlds. Fluents, effect applicators and numeric tests make factoring inexact; condition
// checkers do not (without fluents they read only their arguments, the same in every world).
// Goals are clauses (task.hpp), never a disjunctive normal form, so the clauses of Bartender's
// ⊕ goal, one per bottle, keep the bottles apart.
KnowledgeFactoring factorKnowledge(const GroundTask& task,
                                   std::span<const std::vector<AtomId>> correlated,
                                   std::span<const AtomId> forgetBase);

}  // namespace kaboum::symbolic
