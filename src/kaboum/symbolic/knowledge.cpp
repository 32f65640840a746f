#include "kaboum/symbolic/knowledge.hpp"

#include <algorithm>
#include <cmath>
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
    if (context == Context::Effect && databaseUpdate(expr)) {
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
  // "k." / "k-not." (queries K(p) / K(¬p) under a negation), "kf-del." / "kf-del-not." (forget).
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

  const std::string& file_;
};

bool sameAtom(const SExpr& a, const SExpr& b) {
  if (a.items.size() != b.items.size()) return false;
  for (std::size_t i = 0; i < a.items.size(); ++i) {
    if (!a.items[i].isAtom() || !b.items[i].isAtom() || a.items[i].text != b.items[i].text) {
      return false;
    }
  }
  return true;
}

// Finds an add or delete of `observed` in an effect tree.
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

// Moves the knowledge constraints of :init out of it, leaving the plain facts in place.
std::vector<SExpr> extractConstraints(SExpr& init) {
  std::vector<SExpr> facts;
  std::vector<SExpr> constraints;
  const std::function<void(SExpr&)> visit = [&](SExpr& item) {
    if (item.startsWith("and")) {
      for (std::size_t i = 1; i < item.items.size(); ++i) visit(item.items[i]);
    } else if (item.startsWith("unknown") || item.startsWith("oneof") || item.startsWith("or") ||
               item.startsWith("not")) {
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
      if (part.startsWith(":action")) rewriteAction(part, rewriter, domainFile);
      if (part.startsWith(":requirements")) {
        std::erase_if(part.items, [](const SExpr& r) { return r.isAtom(":contingent"); });
      }
    }
    declareKnowledgePredicates(define, rewriter, domainFile, goalRewriter, problemFile);
    // Some benchmark domains declare constants before their types: declare types first.
    std::stable_partition(define.items.begin() + 2, define.items.end(), [](const SExpr& part) {
      return part.startsWith(":requirements") || part.startsWith(":types");
    });
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
          head == "oneof" ? KnowledgeConstraint::Kind::OneOf : KnowledgeConstraint::Kind::Or;
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

// --- KnowledgeTask -------------------------------------------------------------------------

namespace {

// Kv(f) holds initially for every function term :init gives a value.
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
                                          {"(kf-del-not.", true}}) {
      const std::string_view head(prefix);
      if (!name.starts_with(head)) continue;
      const auto it = atomIds_.find("(" + name.substr(head.size()));
      const bool query = head.starts_with("(k.") || head.starts_with("(k-not.");
      Auxiliary& target = query ? kQuery_[a] : forget_[a];
      target.base = it == atomIds_.end() ? kNoBase : it->second;
      target.negated = negated;
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

namespace {
bool sameValue(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}
}  // namespace

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

bool KnowledgeTask::apply(int op, const Belief& belief, Belief& out) {
  out.clear();
  for (const std::uint32_t w : belief) {
    if (!evaluator_.apply(task_.operators[op], world(w), scratch_)) return false;
    storeForgetting(out);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  canonicalize(out);
  return true;
}

// Drops Kw/Kv atoms whose subject is known anyway, so equal knowledge has one representation.
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
// kf-del-not) gains a twin where p is false (true), so K(p) (K(¬p)) no longer holds.
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

std::uint32_t KnowledgeTask::applyIn(int op, std::uint32_t w) {
  if (!evaluator_.apply(task_.operators[op], world(w), scratch_)) return PackedSet::kMissing;
  // Forgetting changes what the agent knows, not the true world.
  for (const AtomId marker : forgetAtoms_) setBit(scratch_, marker, false);
  return store(scratch_);
}

}  // namespace kaboum::symbolic
