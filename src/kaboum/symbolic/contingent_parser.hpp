// Compiler of the contingent PDDL dialect (thesis §3.3.1, PKS databases Kf/Kw/Kv and primitive
// queries; seed 003 §III-A): the dialect (`unknown`, `oneof`, `or` in :init, `:observe`,
// Contingent-FF's `(nondet l)` effects, PO-PRP's `(:sensor …)` and `(invariant …)`) and explicit
// PKS operators (`(kw φ)`, `(kv f)`, `(k φ)`, ¬K as `(not (k φ))`, database updates
// `(add|del kf|kw|kv φ)`, del(Kf) forgetting) are rewritten onto the core parser and grounder; the
// knowledge constraints of :init are kept for the knowledge level (knowledge.hpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "kaboum/symbolic/pddl.hpp"

namespace kaboum::symbolic {

// A literal of the initial knowledge, with where it was written.
struct InitialLiteral {
  GroundAtom atom;
  bool positive = true;
  SourcePos pos;
};

// One statement of :init beyond plain known atoms: `(unknown p)`, `(oneof l…)` (exactly one holds;
// also PO-PRP's `(invariant l…)`, which the CLG versions of its problems write as `oneof`), `(or
// l…)` (at least one holds) or `(not p)` (p known false).
struct KnowledgeConstraint {
  enum class Kind { Unknown, OneOf, Or, KnownFalse };
  Kind kind = Kind::Unknown;
  std::vector<InitialLiteral> literals;
  SourcePos pos;
};

// A parsed contingent problem. `problem.init` holds the atoms known true; every atom not known true
// and not named by a constraint is known false (the benchmarks' convention; PKS's open world is
// written with `unknown`).
struct ContingentProblem {
  Domain domain;
  Problem problem;
  std::vector<KnowledgeConstraint> constraints;
  std::vector<int> varyingPredicates;  // unknown initially or observed: never folded as static
  SourcePos initPos;
};

// Parses the contingent dialect (also plain PDDL: the closed-world special case). Throws InputError
// "file:line:col: ..." for malformed `oneof`/`or`/`unknown`/`kw`/`kv`, sensing actions that also
// change the atom they observe, and everything the core parser rejects.
ContingentProblem parseContingent(std::string_view domainText, const std::string& domainFile,
                                  std::string_view problemText, const std::string& problemFile);
ContingentProblem loadContingent(const std::string& domainPath, const std::string& problemPath);

// True initial states of a `hidden.pddl` file: one list of atoms (true besides the known ones) per
// `(:hidden …)` section; a problem file's own :hidden sections work the same way.
struct HiddenState {
  std::vector<GroundAtom> atoms;
  SourcePos pos;
};
std::vector<HiddenState> parseHidden(std::string_view text, const std::string& file,
                                     const ContingentProblem& contingent);

// Kv(f) atoms `(kv.f …)` of the function terms :init gives a value: those values are known.
std::vector<GroundAtom> initialValueKnowledge(const ContingentProblem& contingent);

// The classical problem the core grounder grounds: the known atoms, every atom a constraint names
// (it may be true in some world), the initial Kv atoms and every instance of the ¬K query atoms.
Problem groundingProblem(const ContingentProblem& contingent);

}  // namespace kaboum::symbolic
