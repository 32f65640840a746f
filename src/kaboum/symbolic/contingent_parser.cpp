#include "kaboum/symbolic/contingent_parser.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <set>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {
namespace {

[[noreturn]] void fail(const std::string& file, const SExpr& where, const std::string& what) {
  throw InputError(locate(file, what, where.pos.line, where.pos.column));
}

SExpr atomNode(const std::string& text, SourcePos pos) {
  SExpr out;
  out.text = text;
  out.original = text;
  out.pos = pos;
  return out;
}

// Rewrites the contingent dialect and PKS operators of one file's tree onto core PDDL.
class Rewriter {
 public:
  explicit Rewriter(const std::string& file) : file_(file) {}

  // (kw (p x)) -> (kw.p x), (kv (f x)) -> (kv.f x), (k φ) -> φ. In a precondition, a positive
  // Kw query becomes (or (kw.p x) (p x) (not (p x))): sensed, known true or known false.
  enum class Context { Effect, Precondition, Goal };
  void queries(SExpr& expr, Context context, bool positive = true) {
    if (!expr.isList() || expr.items.empty()) return;
    if (context == Context::Effect && (databaseUpdate(expr) || nondeterministicEffect(expr))) {
      queries(expr, context, positive);
      return;
    }
    const bool knowledge = expr.startsWith("kw") || expr.startsWith("kv") || expr.startsWith("k");
    if (knowledge && expr.items.size() == 2 && expr.items[1].isList()) {
      const std::string head = expr.items[0].text;
      SExpr inner = expr.items[1];
      if (head == "k" && !positive) {
        notKnown(expr, std::move(inner));
        return;
      }
      if (head == "k") {
        expr = std::move(inner);
        queries(expr, context, positive);
        return;
      }
      if (inner.items.empty() || !inner.items[0].isAtom() || inner.kind != SExpr::Kind::List) {
        fail(file_, inner, "'" + head + "' takes one atom, e.g. (" + head + " (p ?x))");
      }
      const std::string name = inner.items[0].text;
      (head == "kw" ? kwPredicates : kvFunctions).insert({name, inner.pos});
      SExpr sensed = inner;
      sensed.items[0].text = head + "." + name;
      sensed.items[0].original = sensed.items[0].text;
      if (head == "kw" && context == Context::Precondition && positive) {
        SExpr negated;
        negated.kind = SExpr::Kind::List;
        negated.pos = inner.pos;
        negated.items = {atomNode("not", inner.pos), inner};
        expr.items = {atomNode("or", expr.pos), std::move(sensed), std::move(inner),
                      std::move(negated)};
        return;
      }
      expr = std::move(sensed);
      return;
    }
    const bool negation = expr.startsWith("not");
    for (SExpr& item : expr.items) queries(item, context, negation ? !positive : positive);
  }

  std::map<std::string, SourcePos> kwPredicates;
  std::map<std::string, SourcePos> kvFunctions;
  // Auxiliary predicates over a base predicate: {prefix, base name} -> first use. Prefixes:
  // "k." / "k-not." (queries K(p) / K(¬p) under a negation), "kf-del." / "kf-del-not." (forget),
  // "nondet-del." / "nondet-add." (a non-deterministic effect may delete / add p).
  std::map<std::pair<std::string, std::string>, SourcePos> kfPredicates;

 private:
  // Renames `atom` (p args…) to (PREFIX.p args…) and records the auxiliary predicate.
  void auxiliary(SExpr& atom, const std::string& prefix) {
    if (atom.kind != SExpr::Kind::List || atom.items.empty() || !atom.items[0].isAtom() ||
        atom.startsWith("not")) {
      fail(file_, atom, "expected an atom, e.g. (p ?x)");
    }
    kfPredicates.insert({{prefix, atom.items[0].text}, atom.pos});
    atom.items[0].text = prefix + atom.items[0].text;
    atom.items[0].original = atom.items[0].text;
  }

  // ¬K(p) / ¬K(¬p) ("not known true" / "not known false"): (not (k (p x))) -> (not (k.p x)).
  void notKnown(SExpr& expr, SExpr inner) {
    const bool negated = inner.startsWith("not") && inner.items.size() == 2;
    SExpr atom = negated ? inner.items[1] : std::move(inner);
    auxiliary(atom, negated ? "k-not." : "k.");
    expr = std::move(atom);
  }

  // Explicit database updates (thesis §3.3.1): (add kf φ) -> φ, (add kw (p)) -> (kw (p)),
  // (add kv (f)) -> (kv (f)), (del kw (p)) -> (not (kw (p))), (del kv (f)) -> (not (kv (f))),
  // (del kf (p)) -> (kf-del.p), (del kf (not (p))) -> (kf-del-not.p). False if `expr` is not one.
  bool databaseUpdate(SExpr& expr) {
    if (expr.items.size() != 3 || !(expr.startsWith("add") || expr.startsWith("del")) ||
        !expr.items[1].isAtom() || !expr.items[2].isList()) {
      return false;
    }
    const std::string database = expr.items[1].text;
    const bool add = expr.startsWith("add");
    if (database != "kf" && database != "kw" && database != "kv") {
      fail(file_, expr.items[1], "unknown database '" + database + "': expected kf, kw or kv");
    }
    SExpr subject = expr.items[2];
    if (database == "kf") {
      if (add) {
        expr = std::move(subject);
        return true;
      }
      const bool negated = subject.startsWith("not") && subject.items.size() == 2;
      SExpr atom = negated ? subject.items[1] : std::move(subject);
      auxiliary(atom, negated ? "kf-del-not." : "kf-del.");
      expr = std::move(atom);
      return true;
    }
    SExpr query;
    query.kind = SExpr::Kind::List;
    query.pos = expr.pos;
    query.items = {atomNode(database, expr.items[1].pos), std::move(subject)};
    if (add) {
      expr = std::move(query);
    } else {
      expr.items = {atomNode("not", expr.pos), std::move(query)};
    }
    return true;
  }

  // Contingent-FF's non-deterministic effect `(nondet l)`: l may or may not take place, so in
  // each world where it applies the atom keeps its value or takes l's, and knowing it is lost
  // (the thesis's loss of knowledge): (nondet (not (p x))) -> (nondet-del.p x) (like del(Kf, p),
  // and the true world may lose p), (nondet (p x)) -> (nondet-add.p x). False if not one.
  bool nondeterministicEffect(SExpr& expr) {
    if (!expr.startsWith("nondet")) return false;
    const auto isLiteral = [](const SExpr& atom) {
      return atom.kind == SExpr::Kind::List && !atom.items.empty() && atom.items[0].isAtom() &&
             std::none_of(kConnectives.begin(), kConnectives.end(),
                          [&](std::string_view c) { return atom.startsWith(c); });
    };
    SExpr* literal = expr.items.size() == 2 ? &expr.items[1] : nullptr;
    const bool negated =
        literal != nullptr && literal->startsWith("not") && literal->items.size() == 2;
    SExpr* atom = negated ? &literal->items[1] : literal;
    if (atom == nullptr || !isLiteral(*atom)) {
      fail(file_, expr, "'nondet' takes one literal, e.g. (nondet (not (p ?x)))");
    }
    SExpr changed = std::move(*atom);
    auxiliary(changed, negated ? "nondet-del." : "nondet-add.");
    expr = std::move(changed);
    return true;
  }

  static constexpr std::array<std::string_view, 9> kConnectives = {
      "and", "or", "not", "imply", "when", "forall", "exists", "oneof", "nondet"};

  const std::string& file_;
};

// The atom a non-deterministic effect marker `(nondet-del.p …)` / `(nondet-add.p …)` may change,
// as its predicate name; other atoms name themselves.
std::string_view changedPredicate(const SExpr& atom) {
  std::string_view name = atom.items[0].text;
  for (const std::string_view prefix : {"nondet-del.", "nondet-add."}) {
    if (name.starts_with(prefix)) name.remove_prefix(prefix.size());
  }
  return name;
}

bool sameAtom(const SExpr& a, const SExpr& b) {
  if (a.items.size() != b.items.size() || !a.items[0].isAtom() || !b.items[0].isAtom() ||
      changedPredicate(a) != changedPredicate(b)) {
    return false;
  }
  for (std::size_t i = 1; i < a.items.size(); ++i) {
    if (!a.items[i].isAtom() || !b.items[i].isAtom() || a.items[i].text != b.items[i].text) {
      return false;
    }
  }
  return true;
}

// Finds an add, delete or non-deterministic change of `observed` in a rewritten effect tree.
const SExpr* findChange(const SExpr& effect, const SExpr& observed) {
  if (!effect.isList() || effect.items.empty()) return nullptr;
  if (sameAtom(effect, observed)) return &effect;
  for (std::size_t i = effect.startsWith("when") ? 2 : 1; i < effect.items.size(); ++i) {
    if (const SExpr* hit = findChange(effect.items[i], observed)) return hit;
  }
  return nullptr;
}

void rewriteAction(SExpr& action, Rewriter& rewriter, const std::string& file) {
  std::vector<SExpr> kept;
  std::vector<SExpr> observed;
  SExpr* effect = nullptr;
  std::size_t effectIndex = 0;
  for (std::size_t i = 0; i < action.items.size(); ++i) {
    SExpr& item = action.items[i];
    if (i >= 2 && item.isAtom(":observe") && i + 1 < action.items.size()) {
      SExpr& value = action.items[++i];
      if (!value.isList() || value.items.empty()) fail(file, value, "expected an atom to observe");
      if (value.startsWith("and")) {
        observed.insert(observed.end(), value.items.begin() + 1, value.items.end());
      } else {
        observed.push_back(value);
      }
      continue;
    }
    if (i >= 2 && (item.isAtom(":precondition") || item.isAtom(":effect")) &&
        i + 1 < action.items.size()) {
      rewriter.queries(action.items[i + 1], item.isAtom(":effect")
                                                ? Rewriter::Context::Effect
                                                : Rewriter::Context::Precondition);
      if (item.isAtom(":effect")) effectIndex = kept.size() + 1;
    }
    kept.push_back(std::move(item));
  }
  if (effectIndex > 0) effect = &kept[effectIndex];
  if (observed.empty()) {
    action.items = std::move(kept);
    return;
  }
  SExpr conjunction;
  conjunction.kind = SExpr::Kind::List;
  conjunction.pos = observed.front().pos;
  conjunction.items.push_back(atomNode("and", conjunction.pos));
  for (SExpr& atom : observed) {
    if (atom.kind != SExpr::Kind::List || atom.items.empty() || !atom.items[0].isAtom() ||
        atom.startsWith("not")) {
      fail(file, atom, "':observe' takes atoms, e.g. (p ?x)");
    }
    if (effect != nullptr) {
      if (const SExpr* change = findChange(*effect, atom)) {
        fail(file, *change,
             "sensing action changes the atom it observes " + toString(atom) +
                 "; observe in one action and change it in another");
      }
    }
    rewriter.kwPredicates.insert({atom.items[0].text, atom.pos});
    atom.items[0].text = "kw." + atom.items[0].text;
    atom.items[0].original = atom.items[0].text;
    conjunction.items.push_back(std::move(atom));
  }
  if (effect != nullptr) {
    conjunction.items.push_back(std::move(*effect));
    *effect = std::move(conjunction);
  } else {
    kept.push_back(atomNode(":effect", conjunction.pos));
    kept.push_back(std::move(conjunction));
  }
  action.items = std::move(kept);
}

SExpr* section(SExpr& define, std::string_view key) {
  for (std::size_t i = 2; i < define.items.size(); ++i) {
    if (define.items[i].startsWith(key)) return &define.items[i];
  }
  return nullptr;
}

// Declares (kw.p …) for observed/queried predicates, (kv.f …) for queried functions and the
// auxiliary predicates of ¬K queries and Kf deletions (those of the goal's rewriter too).
void declareKnowledgePredicates(SExpr& define, const Rewriter& rewriter, const std::string& file,
                                const Rewriter& goalRewriter, const std::string& problemFile) {
  SExpr* predicates = section(define, ":predicates");
  SExpr* functions = section(define, ":functions");
  std::vector<SExpr> added;
  const auto copyDeclaration = [&](SExpr* from, const std::string& name, const std::string& prefix,
                                   SourcePos use, const char* what, const std::string& where) {
    if (from != nullptr) {
      for (std::size_t i = 1; i < from->items.size(); ++i) {
        const SExpr& declaration = from->items[i];
        if (declaration.startsWith(name)) {
          SExpr copy = declaration;
          copy.items[0].text = prefix + name;
          copy.items[0].original = copy.items[0].text;
          added.push_back(std::move(copy));
          return;
        }
      }
    }
    throw InputError(
        locate(where, std::string("undefined ") + what + " '" + name + "'", use.line, use.column));
  };
  for (const auto& [name, pos] : rewriter.kwPredicates) {
    copyDeclaration(predicates, name, "kw.", pos, "predicate", file);
  }
  for (const auto& [name, pos] : rewriter.kvFunctions) {
    copyDeclaration(functions, name, "kv.", pos, "function", file);
  }
  std::set<std::string> auxiliaries;
  for (const auto& [from, where] :
       {std::pair{&rewriter, &file}, std::pair{&goalRewriter, &problemFile}}) {
    for (const auto& [key, pos] : from->kfPredicates) {
      if (auxiliaries.insert(key.first + key.second).second) {
        copyDeclaration(predicates, key.second, key.first, pos, "predicate", *where);
      }
    }
  }
  if (added.empty()) return;
  if (predicates == nullptr) {
    SExpr fresh;
    fresh.kind = SExpr::Kind::List;
    fresh.items.push_back(atomNode(":predicates", define.pos));
    define.items.push_back(std::move(fresh));
    predicates = &define.items.back();
  }
  predicates->items.insert(predicates->items.end(), added.begin(), added.end());
}

GroundAtom resolveAtom(const SExpr& expr, const std::string& file, const Domain& domain,
                       const Problem& problem) {
  if (expr.kind != SExpr::Kind::List || expr.items.empty() || !expr.items[0].isAtom()) {
    fail(file, expr, "expected an atom, e.g. (p a b)");
  }
  const std::string& head = expr.items[0].text;
  const int predicate = domain.findPredicate(head);
  if (predicate < 0) fail(file, expr.items[0], "undefined predicate '" + head + "'");
  const std::size_t arity = domain.predicates[predicate].paramTypes.size();
  if (expr.items.size() - 1 != arity) {
    fail(file, expr,
         "predicate '" + head + "' takes " + std::to_string(arity) + " argument(s), " +
             std::to_string(expr.items.size() - 1) + " given");
  }
  GroundAtom out{predicate, {}};
  for (std::size_t i = 1; i < expr.items.size(); ++i) {
    const SExpr& arg = expr.items[i];
    if (!arg.isAtom()) fail(file, arg, "expected an object name");
    const ObjectId id = problem.findObject(arg.text);
    if (id < 0) fail(file, arg, "undefined object '" + arg.text + "'");
    out.args.push_back(id);
  }
  return out;
}

InitialLiteral resolveLiteral(const SExpr& expr, const std::string& file, const Domain& domain,
                              const Problem& problem) {
  if (expr.startsWith("not")) {
    if (expr.items.size() != 2) fail(file, expr, "'not' takes one atom");
    return {resolveAtom(expr.items[1], file, domain, problem), false, expr.pos};
  }
  return {resolveAtom(expr, file, domain, problem), true, expr.pos};
}

// PO-PRP's sensor `(:sensor NAME :parameters (…) :condition φ :sense (p …))` as the sensing action
// `(:action NAME :parameters (…) :precondition φ :observe (p …))`: an observation the planner may
// make whenever φ holds (PO-PRP makes it then anyway; what it tells is the same).
void sensorAsAction(SExpr& sensor) {
  sensor.items[0].text = ":action";
  for (std::size_t i = 2; i < sensor.items.size(); i += 2) {
    SExpr& key = sensor.items[i];
    if (key.isAtom(":condition")) key.text = ":precondition";
    if (key.isAtom(":sense")) key.text = ":observe";
  }
}

// Moves the knowledge constraints of :init out of it, leaving the plain facts in place.
std::vector<SExpr> extractConstraints(SExpr& init) {
  std::vector<SExpr> facts;
  std::vector<SExpr> constraints;
  const std::function<void(SExpr&)> visit = [&](SExpr& item) {
    if (item.startsWith("and")) {
      for (std::size_t i = 1; i < item.items.size(); ++i) visit(item.items[i]);
    } else if (item.startsWith("unknown") || item.startsWith("oneof") || item.startsWith("or") ||
               item.startsWith("not") || item.startsWith("invariant")) {
      constraints.push_back(std::move(item));
    } else {
      facts.push_back(std::move(item));
    }
  };
  for (std::size_t i = 1; i < init.items.size(); ++i) visit(init.items[i]);
  init.items.resize(1);
  init.items.insert(init.items.end(), facts.begin(), facts.end());
  return constraints;
}

}  // namespace

ContingentProblem parseContingent(std::string_view domainText, const std::string& domainFile,
                                  std::string_view problemText, const std::string& problemFile) {
  ContingentProblem out;
  std::vector<SExpr> problemTop = readSExprs(problemText, problemFile);
  std::vector<SExpr> constraintExprs;
  Rewriter goalRewriter(problemFile);
  if (problemTop.size() == 1 && problemTop[0].startsWith("define")) {
    SExpr& define = problemTop[0];
    std::erase_if(define.items, [](const SExpr& s) { return s.startsWith(":hidden"); });
    for (std::size_t i = 2; i < define.items.size(); ++i) {
      SExpr& part = define.items[i];
      if (part.startsWith(":init")) {
        out.initPos = part.pos;
        constraintExprs = extractConstraints(part);
      }
      if (part.startsWith(":goal")) goalRewriter.queries(part, Rewriter::Context::Goal);
    }
  }
  std::vector<SExpr> domainTop = readSExprs(domainText, domainFile);
  Rewriter rewriter(domainFile);
  if (domainTop.size() == 1 && domainTop[0].startsWith("define") && domainTop[0].items.size() > 2) {
    SExpr& define = domainTop[0];
    for (std::size_t i = 2; i < define.items.size(); ++i) {
      SExpr& part = define.items[i];
      if (part.startsWith(":sensor")) sensorAsAction(part);
      if (part.startsWith(":action")) rewriteAction(part, rewriter, domainFile);
      if (part.startsWith(":requirements")) {
        std::erase_if(part.items, [](const SExpr& r) { return r.isAtom(":contingent"); });
      }
    }
    declareKnowledgePredicates(define, rewriter, domainFile, goalRewriter, problemFile);
  }
  out.domain = parseDomain(domainTop, domainFile);
  for (const auto& [name, pos] : goalRewriter.kwPredicates) {
    if (out.domain.findPredicate("kw." + name) < 0) {
      throw InputError(locate(problemFile,
                              "goal queries Kw of '" + name + "', which no action observes",
                              pos.line, pos.column));
    }
  }
  for (const auto& [name, pos] : goalRewriter.kvFunctions) {
    if (out.domain.findPredicate("kv." + name) < 0) {
      throw InputError(locate(problemFile,
                              "goal queries Kv of '" + name + "', which no action senses", pos.line,
                              pos.column));
    }
  }
  out.problem = parseProblem(problemTop, problemFile, out.domain);

  std::set<int> varying;
  for (const SExpr& expr : constraintExprs) {
    KnowledgeConstraint constraint;
    constraint.pos = expr.pos;
    const std::string& head = expr.items[0].text;
    if (head == "not") {
      constraint.kind = KnowledgeConstraint::Kind::KnownFalse;
      constraint.literals.push_back(resolveLiteral(expr, problemFile, out.domain, out.problem));
    } else if (head == "unknown") {
      if (expr.items.size() != 2) fail(problemFile, expr, "'unknown' takes one atom");
      constraint.kind = KnowledgeConstraint::Kind::Unknown;
      constraint.literals.push_back(
          {resolveAtom(expr.items[1], problemFile, out.domain, out.problem), true, expr.pos});
    } else {
      constraint.kind =
          head == "or" ? KnowledgeConstraint::Kind::Or : KnowledgeConstraint::Kind::OneOf;
      if (expr.items.size() < 2) fail(problemFile, expr, "'" + head + "' needs at least one atom");
      for (std::size_t i = 1; i < expr.items.size(); ++i) {
        const SExpr& item = expr.items[i];
        if (item.startsWith("and") || item.startsWith("oneof") || item.startsWith("or")) {
          fail(problemFile, item,
               "malformed '" + head + "': expected atoms or (not atom), found " + toString(item));
        }
        constraint.literals.push_back(resolveLiteral(item, problemFile, out.domain, out.problem));
      }
    }
    for (const InitialLiteral& literal : constraint.literals) {
      if (constraint.kind != KnowledgeConstraint::Kind::KnownFalse) {
        varying.insert(literal.atom.predicate);
        continue;
      }
      for (const GroundAtom& known : out.problem.init) {
        if (known.predicate == literal.atom.predicate && known.args == literal.atom.args) {
          throw InputError(
              locate(problemFile,
                     "contradictory initial knowledge: " +
                         describeAtom(out.domain, out.problem, known.predicate, known.args) +
                         " is both known true and known false",
                     literal.pos.line, literal.pos.column));
        }
      }
    }
    out.constraints.push_back(std::move(constraint));
  }
  for (std::size_t p = 0; p < out.domain.predicates.size(); ++p) {
    const std::string& name = out.domain.predicates[p].name;
    if (name.starts_with("kw.")) varying.insert(out.domain.findPredicate(name.substr(3)));
  }
  for (const auto* from : {&rewriter, &goalRewriter}) {
    for (const auto& [key, pos] : from->kfPredicates) {
      varying.insert(out.domain.findPredicate(key.second));
      varying.insert(out.domain.findPredicate(key.first + key.second));
    }
  }
  out.varyingPredicates.assign(varying.begin(), varying.end());
  return out;
}

ContingentProblem loadContingent(const std::string& domainPath, const std::string& problemPath) {
  return parseContingent(readTextFile(domainPath), domainPath, readTextFile(problemPath),
                         problemPath);
}

std::vector<HiddenState> parseHidden(std::string_view text, const std::string& file,
                                     const ContingentProblem& contingent) {
  std::vector<HiddenState> out;
  const std::vector<SExpr> top = readSExprs(text, file);
  const std::function<void(const SExpr&)> visit = [&](const SExpr& expr) {
    if (!expr.isList()) return;
    if (expr.startsWith(":hidden")) {
      HiddenState state;
      state.pos = expr.pos;
      for (std::size_t i = 1; i < expr.items.size(); ++i) {
        const SExpr& item = expr.items[i];
        if (item.startsWith("and")) {
          for (std::size_t k = 1; k < item.items.size(); ++k) {
            state.atoms.push_back(
                resolveAtom(item.items[k], file, contingent.domain, contingent.problem));
          }
        } else if (!item.startsWith("not")) {
          state.atoms.push_back(resolveAtom(item, file, contingent.domain, contingent.problem));
        }
      }
      out.push_back(std::move(state));
      return;
    }
    for (const SExpr& item : expr.items) visit(item);
  };
  for (const SExpr& expr : top) visit(expr);
  if (out.empty()) throw InputError(locate(file, "no '(:hidden …)' section"));
  return out;
}

std::vector<GroundAtom> initialValueKnowledge(const ContingentProblem& contingent) {
  std::vector<GroundAtom> out;
  for (const InitialFluent& value : contingent.problem.initFluents) {
    const int predicate =
        contingent.domain.findPredicate("kv." + contingent.domain.functions[value.function].name);
    if (predicate >= 0) out.push_back({predicate, value.args});
  }
  return out;
}

Problem groundingProblem(const ContingentProblem& contingent) {
  Problem problem = contingent.problem;
  for (const GroundAtom& atom : initialValueKnowledge(contingent)) problem.init.push_back(atom);
  for (const KnowledgeConstraint& constraint : contingent.constraints) {
    if (constraint.kind == KnowledgeConstraint::Kind::KnownFalse) continue;
    // Negative literals too: an atom a constraint names may be true in some world.
    for (const InitialLiteral& literal : constraint.literals) problem.init.push_back(literal.atom);
  }
  // ¬K query atoms (k.p …) are never true in a world: make every typed instance reachable so the
  // grounder keeps them as atoms (the worlds are rebuilt from the known atoms without them).
  const Domain& domain = contingent.domain;
  for (std::size_t p = 0; p < domain.predicates.size(); ++p) {
    const std::string& name = domain.predicates[p].name;
    if (!name.starts_with("k.") && !name.starts_with("k-not.")) continue;
    const std::vector<int>& types = domain.predicates[p].paramTypes;
    std::vector<std::vector<ObjectId>> choices;
    for (const int type : types) choices.push_back(problem.objectsOfType(domain, type));
    std::vector<ObjectId> args(types.size());
    const std::function<void(std::size_t)> enumerate = [&](std::size_t i) {
      if (i == types.size()) {
        problem.init.push_back({static_cast<int>(p), args});
        return;
      }
      for (const ObjectId object : choices[i]) {
        args[i] = object;
        enumerate(i + 1);
      }
    };
    enumerate(0);
  }
  return problem;
}

}  // namespace kaboum::symbolic
