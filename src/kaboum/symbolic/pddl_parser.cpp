// Parser from S-expressions to the lifted Domain/Problem of pddl.hpp, with name resolution and
// file:line:col errors.
#include <algorithm>
#include <array>
#include <charconv>
#include <functional>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/pddl.hpp"

namespace kaboum::symbolic {
namespace {

constexpr std::array kSupportedRequirements = {":strips",
                                               ":typing",
                                               ":negative-preconditions",
                                               ":equality",
                                               ":disjunctive-preconditions",
                                               ":existential-preconditions",
                                               ":universal-preconditions",
                                               ":quantified-preconditions",
                                               ":conditional-effects",
                                               ":adl",
                                               ":fluents",
                                               ":numeric-fluents",
                                               ":object-fluents",
                                               ":action-costs",
                                               ":semantic-attachments"};

int findByName(const auto& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

bool parseNumber(const std::string& text, double& out) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, out);
  return result.ec == std::errc() && result.ptr == end;
}

class Parser {
 public:
  Parser(const std::string& file) : file_(file) {}

  [[noreturn]] void fail(const SExpr& where, const std::string& what) const {
    throw InputError(locate(file_, what, where.pos.line, where.pos.column));
  }

  const SExpr& expectList(const SExpr& expr, const std::string& what) const {
    if (!expr.isList()) fail(expr, "expected " + what + ", found '" + expr.text + "'");
    return expr;
  }

  const std::string& expectName(const SExpr& expr, const std::string& what) const {
    if (!expr.isAtom() || expr.text.empty()) fail(expr, "expected " + what);
    return expr.text;
  }

  // The single top-level form "(define (KIND NAME) ...)"; returns it after checking its shape.
  const SExpr& expectDefine(const std::vector<SExpr>& top, const std::string& kind) const {
    const std::string shape = "expected '(define (" + kind + " NAME) ...)'";
    if (top.empty()) throw InputError(locate(file_, shape));
    if (top.size() > 1) fail(top[1], "expected end of file after the " + kind + " definition");
    const SExpr& define = top[0];
    if (!define.startsWith("define") || define.items.size() < 2 ||
        !define.items[1].startsWith(kind) || define.items[1].items.size() != 2) {
      fail(define, shape);
    }
    return define;
  }

  // A typed list "a b - t c": returns (name, type expression) pairs; `variables` demands '?'.
  std::vector<std::pair<const SExpr*, const SExpr*>> typedList(const std::vector<SExpr>& items,
                                                               std::size_t from, bool variables,
                                                               std::size_t to) const {
    std::vector<std::pair<const SExpr*, const SExpr*>> out;
    std::size_t pendingStart = out.size();
    for (std::size_t i = from; i < to; ++i) {
      const SExpr& item = items[i];
      if (item.isAtom("-")) {
        if (i + 1 >= to) fail(item, "expected a type name after '-'");
        const SExpr& type = items[i + 1];
        for (std::size_t k = pendingStart; k < out.size(); ++k) out[k].second = &type;
        pendingStart = out.size();
        ++i;
        continue;
      }
      if (!item.isAtom()) fail(item, variables ? "expected a variable" : "expected a name");
      if (variables && item.text.front() != '?') {
        fail(item, "expected a variable starting with '?', found '" + item.text + "'");
      }
      if (!variables && item.text.front() == '?') fail(item, "expected a name, found a variable");
      out.push_back({&item, nullptr});
    }
    return out;
  }

  // Type named by `type` (nullptr: object); 'either' and undefined types are errors.
  int typeId(const Domain& domain, const SExpr* type) const {
    if (type == nullptr) return 0;
    if (type->startsWith("either")) fail(*type, "unsupported: 'either' types");
    const int id = domain.findType(expectName(*type, "a type name"));
    if (id < 0) fail(*type, "undefined type '" + type->text + "'");
    return id;
  }

 protected:
  const std::string& file_;
};

// Resolves formulas, terms and effects for one scope (an action, a module or the goal).
class ScopeParser : public Parser {
 public:
  using ObjectLookup = std::function<int(const SExpr&)>;

  ScopeParser(const std::string& file, const Domain& domain, ObjectLookup lookupObject,
              std::vector<int>& slotTypes, std::vector<std::string>& slotNames)
      : Parser(file),
        domain_(domain),
        lookupObject_(std::move(lookupObject)),
        slotTypes_(slotTypes),
        slotNames_(slotNames) {}

  int resolveType(const SExpr* type) const { return typeId(domain_, type); }

  // Declares the variables of a typed list as new slots in scope; returns their slots.
  std::vector<int> declareVariables(const std::vector<SExpr>& items, std::size_t from,
                                    std::size_t to) {
    std::vector<int> slots;
    for (const auto& [name, type] : typedList(items, from, true, to)) {
      for (const int slot : slots) {
        if (slotNames_[slot] == name->text) fail(*name, "duplicate variable '" + name->text + "'");
      }
      const int slot = static_cast<int>(slotTypes_.size());
      slotTypes_.push_back(resolveType(type));
      slotNames_.push_back(name->text);
      scope_.push_back(slot);
      slots.push_back(slot);
    }
    return slots;
  }

  void popVariables(std::size_t count) { scope_.resize(scope_.size() - count); }

  Term term(const SExpr& expr) const {
    Term out;
    if (expr.isAtom()) {
      if (expr.text.front() == '?') {
        for (auto it = scope_.rbegin(); it != scope_.rend(); ++it) {
          if (slotNames_[*it] == expr.text) {
            out.kind = Term::Kind::Variable;
            out.index = *it;
            return out;
          }
        }
        fail(expr, "undefined variable '" + expr.text + "'");
      }
      const int object = lookupObject_(expr);
      if (object < 0) fail(expr, "undefined constant or object '" + expr.text + "'");
      out.index = object;
      return out;
    }
    if (expr.kind != SExpr::Kind::List || expr.items.empty()) fail(expr, "expected a term");
    const std::string& name = expectName(expr.items[0], "a function name");
    const int function = domain_.findFunction(name);
    if (function < 0) fail(expr.items[0], "undefined function '" + name + "'");
    out.kind = Term::Kind::Function;
    out.index = function;
    checkArity(expr, domain_.functions[function].paramTypes.size(), "function '" + name + "'");
    for (std::size_t i = 1; i < expr.items.size(); ++i) {
      Term arg = term(expr.items[i]);
      if (arg.kind == Term::Kind::Function)
        fail(expr.items[i], "nested function terms unsupported");
      out.args.push_back(std::move(arg));
    }
    return out;
  }

  void checkArity(const SExpr& call, std::size_t expected, const std::string& what) const {
    const std::size_t given = call.items.size() - 1;
    if (given != expected) {
      fail(call, what + " takes " + std::to_string(expected) + " argument(s), " +
                     std::to_string(given) + " given");
    }
  }

  std::vector<Term> objectArgs(const SExpr& call) const {
    std::vector<Term> args;
    for (std::size_t i = 1; i < call.items.size(); ++i) {
      Term arg = term(call.items[i]);
      if (arg.kind == Term::Kind::Function) {
        fail(call.items[i], "function terms are not allowed as arguments here");
      }
      args.push_back(std::move(arg));
    }
    return args;
  }

  bool isNumericExpr(const SExpr& expr) const {
    double unused = 0.0;
    if (expr.isAtom()) return parseNumber(expr.text, unused);
    if (expr.kind != SExpr::Kind::List || expr.items.empty() || !expr.items[0].isAtom()) {
      return false;
    }
    const std::string& head = expr.items[0].text;
    if (head == "+" || head == "-" || head == "*" || head == "/") return true;
    const int function = domain_.findFunction(head);
    return function >= 0 && domain_.functions[function].isNumeric();
  }

  NumExpr number(const SExpr& expr) const {
    NumExpr out;
    if (expr.isAtom()) {
      if (!parseNumber(expr.text, out.value)) fail(expr, "expected a number or numeric term");
      return out;
    }
    if (expr.kind != SExpr::Kind::List || expr.items.empty()) fail(expr, "expected a number");
    const std::string& head = expectName(expr.items[0], "an operator or function");
    static const std::array<std::pair<const char*, NumExpr::Kind>, 4> kOperators = {
        {{"+", NumExpr::Kind::Add},
         {"-", NumExpr::Kind::Sub},
         {"*", NumExpr::Kind::Mul},
         {"/", NumExpr::Kind::Div}}};
    for (const auto& [symbol, kind] : kOperators) {
      if (head != symbol) continue;
      if (expr.items.size() == 2 && kind == NumExpr::Kind::Sub) {
        out.kind = NumExpr::Kind::Neg;
        out.args.push_back(number(expr.items[1]));
        return out;
      }
      if (expr.items.size() != 3) fail(expr, "'" + head + "' takes two operands");
      out.kind = kind;
      out.args.push_back(number(expr.items[1]));
      out.args.push_back(number(expr.items[2]));
      return out;
    }
    out.kind = NumExpr::Kind::Fluent;
    out.fluent = term(expr);
    if (!domain_.functions[out.fluent.index].isNumeric()) {
      fail(expr, "function '" + head + "' is object-valued, expected a number");
    }
    return out;
  }

  Formula formula(const SExpr& expr) {
    Formula out;
    out.pos = expr.pos;
    if (expr.isAtom()) fail(expr, "expected a formula in parentheses, found '" + expr.text + "'");
    if (expr.items.empty()) return out;  // () is the empty conjunction
    if (expr.kind == SExpr::Kind::BracketList)
      return moduleCall(expr, Module::Kind::ConditionChecker, out);
    const std::string& head = expectName(expr.items[0], "a predicate or connective");
    if (head == "and" || head == "or") {
      out.kind = head == "and" ? Formula::Kind::And : Formula::Kind::Or;
      for (std::size_t i = 1; i < expr.items.size(); ++i) {
        out.children.push_back(formula(expr.items[i]));
      }
      return out;
    }
    if (head == "not") {
      if (expr.items.size() != 2) fail(expr, "'not' takes one formula");
      out.kind = Formula::Kind::Not;
      out.children.push_back(formula(expr.items[1]));
      return out;
    }
    if (head == "imply") {
      if (expr.items.size() != 3) fail(expr, "'imply' takes two formulas");
      out.kind = Formula::Kind::Imply;
      out.children.push_back(formula(expr.items[1]));
      out.children.push_back(formula(expr.items[2]));
      return out;
    }
    if (head == "exists" || head == "forall") {
      if (expr.items.size() != 3) fail(expr, "'" + head + "' takes a variable list and a formula");
      const SExpr& vars = expectList(expr.items[1], "a variable list");
      out.kind = head == "exists" ? Formula::Kind::Exists : Formula::Kind::Forall;
      out.slots = declareVariables(vars.items, 0, vars.items.size());
      out.children.push_back(formula(expr.items[2]));
      popVariables(out.slots.size());
      return out;
    }
    static const std::array<std::pair<const char*, Comparison>, 5> kComparisons = {
        {{"<", Comparison::Less},
         {"<=", Comparison::LessEqual},
         {"=", Comparison::Equal},
         {">=", Comparison::GreaterEqual},
         {">", Comparison::Greater}}};
    for (const auto& [symbol, comparison] : kComparisons) {
      if (head != symbol) continue;
      if (expr.items.size() != 3) fail(expr, "'" + head + "' takes two operands");
      if (comparison == Comparison::Equal && !isNumericExpr(expr.items[1]) &&
          !isNumericExpr(expr.items[2])) {
        out.kind = Formula::Kind::Equal;
        out.args.push_back(term(expr.items[1]));
        out.args.push_back(term(expr.items[2]));
        return out;
      }
      out.kind = Formula::Kind::Compare;
      out.comparison = comparison;
      out.numbers.push_back(number(expr.items[1]));
      out.numbers.push_back(number(expr.items[2]));
      return out;
    }
    if (domain_.findModule(head) >= 0) return moduleCall(expr, Module::Kind::ConditionChecker, out);
    const int predicate = domain_.findPredicate(head);
    if (predicate < 0) fail(expr.items[0], "undefined predicate '" + head + "'");
    checkArity(expr, domain_.predicates[predicate].paramTypes.size(), "predicate '" + head + "'");
    out.kind = Formula::Kind::Atom;
    out.symbol = predicate;
    out.args = objectArgs(expr);
    return out;
  }

  template <typename Node>
  Node moduleCall(const SExpr& expr, Module::Kind kind, Node& out) const {
    if (expr.items.empty()) fail(expr, "expected a module name in '[...]'");
    const std::string& name = expectName(expr.items[0], "a module name");
    const int module = domain_.findModule(name);
    if (module < 0) fail(expr.items[0], "undefined module '" + name + "'");
    const Module& declared = domain_.modules[module];
    if (declared.kind != kind) {
      fail(expr,
           "module '" + name + "' is " +
               (kind == Module::Kind::ConditionChecker ? "an effect applicator, used as a condition"
                                                       : "a condition checker, used as an effect"));
    }
    checkArity(expr, declared.paramTypes.size(), "module '" + name + "'");
    out.kind = Node::Kind::Module;
    out.symbol = module;
    out.args = objectArgs(expr);
    return out;
  }

  Effect effect(const SExpr& expr) {
    Effect out;
    out.pos = expr.pos;
    if (expr.isAtom()) fail(expr, "expected an effect in parentheses, found '" + expr.text + "'");
    if (expr.items.empty()) return out;
    if (expr.kind == SExpr::Kind::BracketList)
      return moduleCall(expr, Module::Kind::EffectApplicator, out);
    const std::string& head = expectName(expr.items[0], "a predicate or effect");
    if (head == "and") {
      for (std::size_t i = 1; i < expr.items.size(); ++i) {
        out.children.push_back(effect(expr.items[i]));
      }
      return out;
    }
    if (head == "not") {
      if (expr.items.size() != 2) fail(expr, "'not' takes one atom");
      out = atomEffect(expr.items[1]);
      out.kind = Effect::Kind::Delete;
      return out;
    }
    if (head == "forall") {
      if (expr.items.size() != 3) fail(expr, "'forall' takes a variable list and an effect");
      const SExpr& vars = expectList(expr.items[1], "a variable list");
      out.kind = Effect::Kind::Forall;
      out.slots = declareVariables(vars.items, 0, vars.items.size());
      out.children.push_back(effect(expr.items[2]));
      popVariables(out.slots.size());
      return out;
    }
    if (domain_.findPredicate(head) < 0) {
      if (head == "nondet") {
        fail(expr.items[0],
             "'nondet' (a non-deterministic effect of Contingent-FF's dialect) needs the "
             "knowledge-level planner: kaboum contingent");
      }
      if (head == "oneof") fail(expr.items[0], "unsupported: non-deterministic 'oneof' effects");
      if (head == "probabilistic") {
        fail(expr.items[0], "unsupported: probabilistic effects ('probabilistic')");
      }
    }
    if (head == "when") {
      if (expr.items.size() != 3) fail(expr, "'when' takes a condition and an effect");
      out.kind = Effect::Kind::When;
      out.condition = formula(expr.items[1]);
      out.children.push_back(effect(expr.items[2]));
      return out;
    }
    static const std::array<std::pair<const char*, Effect::Kind>, 5> kAssignments = {
        {{"assign", Effect::Kind::Assign},
         {"increase", Effect::Kind::Increase},
         {"decrease", Effect::Kind::Decrease},
         {"scale-up", Effect::Kind::ScaleUp},
         {"scale-down", Effect::Kind::ScaleDown}}};
    for (const auto& [symbol, kind] : kAssignments) {
      if (head != symbol) continue;
      if (expr.items.size() != 3) fail(expr, "'" + head + "' takes a function term and a value");
      out.kind = kind;
      out.target = term(expr.items[1]);
      if (out.target.kind != Term::Kind::Function) {
        fail(expr.items[1], "expected a function term to assign");
      }
      const bool numeric = domain_.functions[out.target.index].isNumeric();
      if (!numeric && kind != Effect::Kind::Assign) {
        fail(expr, "'" + head + "' needs a numeric function");
      }
      if (numeric) {
        out.numberValue = number(expr.items[2]);
      } else {
        out.objectValue = term(expr.items[2]);
        if (out.objectValue.kind == Term::Kind::Function) {
          fail(expr.items[2], "assign an object or variable to an object fluent");
        }
      }
      return out;
    }
    if (domain_.findModule(head) >= 0) return moduleCall(expr, Module::Kind::EffectApplicator, out);
    return atomEffect(expr);
  }

  Effect atomEffect(const SExpr& expr) const {
    Effect out;
    out.pos = expr.pos;
    if (expr.kind != SExpr::Kind::List || expr.items.empty()) fail(expr, "expected an atom");
    const std::string& name = expectName(expr.items[0], "a predicate name");
    const int predicate = domain_.findPredicate(name);
    if (predicate < 0) fail(expr.items[0], "undefined predicate '" + name + "'");
    checkArity(expr, domain_.predicates[predicate].paramTypes.size(), "predicate '" + name + "'");
    out.kind = Effect::Kind::Add;
    out.symbol = predicate;
    out.args = objectArgs(expr);
    return out;
  }

 private:
  const Domain& domain_;
  ObjectLookup lookupObject_;
  std::vector<int>& slotTypes_;
  std::vector<std::string>& slotNames_;
  std::vector<int> scope_;
};

class DomainParser : public Parser {
 public:
  using Parser::Parser;

  Domain parse(const std::vector<SExpr>& top) {
    domain_.file = file_;
    domain_.types.push_back({"object", -1});
    const SExpr& define = expectDefine(top, "domain");
    domain_.name = expectName(define.items[1].items[1], "a domain name");
    // Requirements and types first, then the other declarations in any order (as Fast Downward
    // reads them), modules and actions last, so each may use anything declared anywhere.
    std::vector<const SExpr*> declarations;
    std::vector<const SExpr*> actions;
    for (std::size_t i = 2; i < define.items.size(); ++i) {
      const SExpr& section = expectList(define.items[i], "a domain section");
      if (section.items.empty() || !section.items[0].isAtom()) fail(section, "expected a section");
      const std::string& key = section.items[0].text;
      if (key == ":requirements") {
        requirements(section);
      } else if (key == ":types") {
        types(section);
      } else {
        declarations.push_back(&section);
      }
    }
    for (std::size_t i = 2; i < define.items.size(); ++i) {
      const SExpr& section = define.items[i];
      if (!section.startsWith(":types")) undeclaredTypes(section, section.startsWith(":functions"));
    }
    for (const SExpr* declaration : declarations) {
      const SExpr& section = *declaration;
      const std::string& key = section.items[0].text;
      if (key == ":constants") {
        constants(section);
      } else if (key == ":predicates") {
        predicates(section);
      } else if (key == ":functions") {
        functions(section);
      } else if (key == ":modules") {
        pendingModules_.push_back(&section);
      } else if (key == ":action") {
        actions.push_back(&section);
      } else if (key == ":durative-action" || key == ":derived" || key == ":constraints") {
        fail(section.items[0], "unsupported section '" + key + "'");
      } else {
        fail(section.items[0], "unknown domain section '" + key + "'");
      }
    }
    for (const SExpr* section : pendingModules_) modules(*section);
    for (const SExpr* section : actions) action(*section);
    return std::move(domain_);
  }

 private:
  void requirements(const SExpr& section) {
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const std::string& name = expectName(section.items[i], "a requirement");
      if (std::find(kSupportedRequirements.begin(), kSupportedRequirements.end(), name) ==
          kSupportedRequirements.end()) {
        fail(section.items[i], "unsupported requirement '" + name + "'");
      }
      domain_.requirements.push_back(name);
    }
  }

  // Types that a typed list names after '-' but :types does not declare: declared under object,
  // with a warning, as Contingent-FF and CLG read them (CLG's medpks domains type constants so).
  // A '-' heading a list is subtraction; `functionResults`: the :functions section, whose '-
  // number' is no type.
  void undeclaredTypes(const SExpr& expr, bool functionResults = false) {
    if (!expr.isList()) return;
    for (std::size_t i = 1; i + 1 < expr.items.size(); ++i) {
      const SExpr& type = expr.items[i + 1];
      if (!expr.items[i].isAtom("-") || !type.isAtom() || type.text.empty() ||
          type.text.front() == '?' || (functionResults && type.isAtom("number")) ||
          domain_.findType(type.text) >= 0) {
        continue;
      }
      domain_.types.push_back({type.text, 0});
      domain_.warnings.push_back(locate(
          file_, "type '" + type.text + "' is not declared in :types; read as a subtype of object",
          type.pos.line, type.pos.column));
    }
    for (const SExpr& item : expr.items) undeclaredTypes(item);
  }

  int typeOrDeclare(const SExpr& name) {
    if (name.startsWith("either")) fail(name, "unsupported: 'either' types");
    const std::string& text = expectName(name, "a type name");
    int id = domain_.findType(text);
    if (id < 0) {
      id = static_cast<int>(domain_.types.size());
      domain_.types.push_back({text, 0});
    }
    return id;
  }

  void types(const SExpr& section) {
    for (const auto& [name, parent] : typedList(section.items, 1, false, section.items.size())) {
      const int id = typeOrDeclare(*name);
      if (id == 0) continue;
      const int parentId = parent == nullptr ? 0 : typeOrDeclare(*parent);
      if (domain_.isSubtype(parentId, id))
        fail(*name, "cyclic type hierarchy at '" + name->text + "'");
      domain_.types[id].parent = parentId;
    }
  }

  int resolveType(const SExpr* type) const { return typeId(domain_, type); }

  void constants(const SExpr& section) {
    for (const auto& [name, type] : typedList(section.items, 1, false, section.items.size())) {
      if (std::find(domain_.constantNames.begin(), domain_.constantNames.end(), name->text) !=
          domain_.constantNames.end()) {
        fail(*name, "duplicate constant '" + name->text + "'");
      }
      domain_.constantNames.push_back(name->text);
      domain_.constantTypes.push_back(resolveType(type));
    }
  }

  std::vector<int> parameterTypes(const SExpr& head) const {
    std::vector<int> out;
    for (const auto& entry : typedList(head.items, 1, true, head.items.size())) {
      out.push_back(resolveType(entry.second));
    }
    return out;
  }

  void predicates(const SExpr& section) {
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& head = expectList(section.items[i], "a predicate declaration");
      if (head.items.empty()) fail(head, "expected a predicate name");
      const std::string& name = expectName(head.items[0], "a predicate name");
      if (domain_.findPredicate(name) >= 0) fail(head, "duplicate predicate '" + name + "'");
      domain_.predicates.push_back({name, parameterTypes(head)});
    }
  }

  void functions(const SExpr& section) {
    std::size_t pendingStart = domain_.functions.size();
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& item = section.items[i];
      if (item.isAtom("-")) {
        if (i + 1 >= section.items.size()) fail(item, "expected a type after '-'");
        const SExpr& type = section.items[++i];
        const int result = type.isAtom("number") ? kNumberType : resolveType(&type);
        for (std::size_t k = pendingStart; k < domain_.functions.size(); ++k) {
          domain_.functions[k].resultType = result;
        }
        pendingStart = domain_.functions.size();
        continue;
      }
      const SExpr& head = expectList(item, "a function declaration");
      if (head.items.empty()) fail(head, "expected a function name");
      const std::string& name = expectName(head.items[0], "a function name");
      if (domain_.findFunction(name) >= 0) fail(head, "duplicate function '" + name + "'");
      domain_.functions.push_back({name, parameterTypes(head), kNumberType});
    }
  }

  // PDDL/M: (name ?p - t ... [(fluent ...)...] conditionchecker|effect proc[@lib.so]
  //          [:reads ((fluent ...) ...)])
  void modules(const SExpr& section) {
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& decl = expectList(section.items[i], "a module declaration");
      if (decl.items.empty()) fail(decl, "expected a module name");
      Module module;
      module.pos = decl.pos;
      module.name = expectName(decl.items[0], "a module name");
      if (domain_.findModule(module.name) >= 0)
        fail(decl, "duplicate module '" + module.name + "'");
      std::size_t at = 1;
      std::size_t paramEnd = at;
      while (paramEnd < decl.items.size() && decl.items[paramEnd].isAtom() &&
             (decl.items[paramEnd].text.front() == '?' || decl.items[paramEnd].text == "-")) {
        paramEnd += decl.items[paramEnd].text == "-" ? 2 : 1;
      }
      paramEnd = std::min(paramEnd, decl.items.size());
      std::vector<int> slotTypes;
      std::vector<std::string> slotNames;
      ScopeParser scope(
          file_, domain_, [this](const SExpr& n) { return constantId(n); }, slotTypes, slotNames);
      scope.declareVariables(decl.items, at, paramEnd);
      module.paramTypes = slotTypes;
      at = paramEnd;
      std::vector<const SExpr*> writes;
      while (at < decl.items.size() && decl.items[at].isList()) writes.push_back(&decl.items[at++]);
      if (at >= decl.items.size()) fail(decl, "expected 'conditionchecker' or 'effect'");
      const SExpr& kind = decl.items[at++];
      if (kind.isAtom("conditionchecker")) {
        module.kind = Module::Kind::ConditionChecker;
        if (!writes.empty()) fail(*writes.front(), "condition checkers set no fluents");
      } else if (kind.isAtom("effect")) {
        module.kind = Module::Kind::EffectApplicator;
      } else {
        fail(kind, "expected 'conditionchecker' or 'effect'");
      }
      if (at >= decl.items.size())
        fail(kind, "expected the procedure name after '" + kind.text + "'");
      expectName(decl.items[at], "a procedure name");
      const std::string& procedure = decl.items[at++].original;
      const std::size_t split = procedure.find('@');
      module.procedure = procedure.substr(0, split);
      if (split != std::string::npos) module.library = procedure.substr(split + 1);
      if (module.procedure.empty()) fail(decl.items[at - 1], "expected a procedure name");
      if (split != std::string::npos && module.library.empty()) {
        fail(decl.items[at - 1], "expected a library after '@'");
      }
      for (const SExpr* write : writes) {
        module.writes.push_back(numericTerm(scope, *write));
      }
      if (at < decl.items.size()) {
        if (!decl.items[at].isAtom(":reads") || at + 2 != decl.items.size()) {
          fail(decl.items[at], "expected ':reads ((fluent ...) ...)' or ')'");
        }
        const SExpr& reads = expectList(decl.items[at + 1], "a list of fluents");
        for (const SExpr& read : reads.items) module.reads.push_back(numericTerm(scope, read));
      }
      domain_.modules.push_back(std::move(module));
    }
  }

  Term numericTerm(const ScopeParser& scope, const SExpr& expr) const {
    Term out = scope.term(expr);
    if (out.kind != Term::Kind::Function) fail(expr, "expected a fluent like '(f ?x)'");
    return out;
  }

  // A name in an action or module: a declared constant, or else a constant of type object the
  // problem must declare as an object (Contingent-FF and Fast Downward resolve such names against
  // the problem's objects; Contingent-FF's medpks domains name illnesses so).
  int constantId(const SExpr& name) {
    const auto it =
        std::find(domain_.constantNames.begin(), domain_.constantNames.end(), name.text);
    if (it != domain_.constantNames.end()) {
      return static_cast<int>(it - domain_.constantNames.begin());
    }
    domain_.undeclaredConstants.push_back(
        {static_cast<int>(domain_.constantNames.size()), name.pos});
    domain_.constantNames.push_back(name.text);
    domain_.constantTypes.push_back(0);
    return static_cast<int>(domain_.constantNames.size()) - 1;
  }

  void action(const SExpr& section) {
    Action action;
    if (section.items.size() < 2) fail(section, "expected an action name");
    action.name = expectName(section.items[1], "an action name");
    if (domain_.findAction(action.name) >= 0) {
      fail(section.items[1], "duplicate action '" + action.name + "'");
    }
    ScopeParser scope(
        file_, domain_, [this](const SExpr& n) { return constantId(n); }, action.slotTypes,
        action.slotNames);
    const SExpr* precondition = nullptr;
    const SExpr* effect = nullptr;
    for (std::size_t i = 2; i < section.items.size(); i += 2) {
      const SExpr& key = section.items[i];
      if (i + 1 >= section.items.size()) fail(key, "expected a value after '" + key.text + "'");
      const SExpr& value = section.items[i + 1];
      if (key.isAtom(":parameters")) {
        const SExpr& list = expectList(value, "a parameter list");
        scope.declareVariables(list.items, 0, list.items.size());
        action.parameterCount = static_cast<int>(action.slotTypes.size());
        action.paramNames = action.slotNames;
      } else if (key.isAtom(":precondition")) {
        precondition = &value;
      } else if (key.isAtom(":effect")) {
        effect = &value;
      } else {
        fail(key, "expected ':parameters', ':precondition' or ':effect'");
      }
    }
    if (precondition != nullptr) action.precondition = scope.formula(*precondition);
    if (effect != nullptr) action.effect = scope.effect(*effect);
    domain_.actions.push_back(std::move(action));
  }

  Domain domain_;
  std::vector<const SExpr*> pendingModules_;
};

class ProblemParser : public Parser {
 public:
  ProblemParser(const std::string& file, const Domain& domain) : Parser(file), domain_(domain) {}

  Problem parse(const std::vector<SExpr>& top) {
    problem_.file = file_;
    problem_.objectNames = domain_.constantNames;
    problem_.objectTypes = domain_.constantTypes;
    redeclared_.assign(domain_.constantNames.size(), 0);
    const SExpr& define = expectDefine(top, "problem");
    problem_.name = expectName(define.items[1].items[1], "a problem name");
    const SExpr* init = nullptr;
    const SExpr* goal = nullptr;
    for (std::size_t i = 2; i < define.items.size(); ++i) {
      const SExpr& section = expectList(define.items[i], "a problem section");
      if (section.items.empty() || !section.items[0].isAtom()) fail(section, "expected a section");
      const std::string& key = section.items[0].text;
      if (key == ":domain") {
        if (section.items.size() != 2) fail(section, "expected '(:domain NAME)'");
        const SExpr& name = section.items[1];
        if (expectName(name, "a domain name") != domain_.name) {
          // Published problems do not always name their domain right; other planners read them.
          problem_.warnings.push_back(locate(file_,
                                             "problem names domain '" + name.text + "' but " +
                                                 domain_.file + " defines domain '" + domain_.name +
                                                 "'; reading it with that domain",
                                             name.pos.line, name.pos.column));
        }
      } else if (key == ":requirements") {
        for (std::size_t k = 1; k < section.items.size(); ++k) {
          const std::string& name = expectName(section.items[k], "a requirement");
          if (std::find(kSupportedRequirements.begin(), kSupportedRequirements.end(), name) ==
              kSupportedRequirements.end()) {
            fail(section.items[k], "unsupported requirement '" + name + "'");
          }
        }
      } else if (key == ":objects") {
        objects(section);
      } else if (key == ":init") {
        init = &section;
      } else if (key == ":goal") {
        goal = &section;
      } else if (key == ":metric") {
        continue;  // plans are judged by length
      } else {
        fail(section.items[0], "unknown problem section '" + key + "'");
      }
    }
    for (const auto& [constant, pos] : domain_.undeclaredConstants) {
      if (redeclared_[constant]) continue;
      throw InputError(locate(domain_.file,
                              "undefined constant or object '" + domain_.constantNames[constant] +
                                  "': neither a domain constant nor an object of " + file_,
                              pos.line, pos.column));
    }
    if (init != nullptr) initial(*init);
    if (goal == nullptr) fail(define, "missing ':goal'");
    if (goal->items.size() != 2) fail(*goal, "expected one goal formula");
    ScopeParser scope(
        file_, domain_, [this](const SExpr& n) { return problem_.findObject(n.text); },
        problem_.goalSlotTypes, problem_.goalSlotNames);
    problem_.goal = scope.formula(goal->items[1]);
    return std::move(problem_);
  }

 private:
  void objects(const SExpr& section) {
    for (const auto& [name, type] : typedList(section.items, 1, false, section.items.size())) {
      const int declared = objectType(type);
      const ObjectId existing = problem_.findObject(name->text);
      if (existing < 0) {
        problem_.objectNames.push_back(name->text);
        problem_.objectTypes.push_back(declared);
        continue;
      }
      if (existing >= static_cast<ObjectId>(domain_.constantNames.size())) {
        fail(*name, "duplicate object '" + name->text + "'");
      }
      // A domain constant declared again as an object, as Contingent-FF accepts: it is one object
      // of the narrower of the two types.
      int& constantType = problem_.objectTypes[existing];
      if (domain_.isSubtype(declared, constantType)) {
        constantType = declared;
      } else if (!domain_.isSubtype(constantType, declared)) {
        fail(*name, "object '" + name->text + "' of type '" + domain_.types[declared].name +
                        "' is a domain constant of the unrelated type '" +
                        domain_.types[constantType].name + "'");
      }
      redeclared_[existing] = 1;
    }
  }

  // The type of problem objects; one the domain never names is read as object, with a warning
  // (no action or predicate can tell them apart), once per place it is written.
  int objectType(const SExpr* type) {
    if (type != nullptr && type->isAtom() && !type->text.empty() &&
        domain_.findType(type->text) < 0) {
      std::string warning = locate(file_,
                                   "type '" + type->text + "' is not declared by " + domain_.file +
                                       "; its objects are of type object",
                                   type->pos.line, type->pos.column);
      if (problem_.warnings.empty() || problem_.warnings.back() != warning) {
        problem_.warnings.push_back(std::move(warning));
      }
      return 0;
    }
    return typeId(domain_, type);
  }

  std::vector<ObjectId> groundArgs(const SExpr& call) const {
    std::vector<ObjectId> args;
    for (std::size_t i = 1; i < call.items.size(); ++i) {
      const std::string& name = expectName(call.items[i], "an object name");
      const ObjectId id = problem_.findObject(name);
      if (id < 0) fail(call.items[i], "undefined object '" + name + "'");
      args.push_back(id);
    }
    return args;
  }

  void initial(const SExpr& section) {
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& fact = section.items[i];
      if (fact.kind != SExpr::Kind::List || fact.items.empty()) fail(fact, "expected an atom");
      const std::string& head = expectName(fact.items[0], "a predicate name");
      if (head == "not") continue;  // closed world: negative facts are implicit
      if (head == "invariant" && domain_.findPredicate(head) < 0) {
        fail(fact.items[0],
             "PO-PRP's '(invariant …)' (uncertain initial knowledge) needs the knowledge-level "
             "planner: kaboum contingent");
      }
      if (head == "=") {
        if (fact.items.size() != 3) fail(fact, "expected '(= (f args) value)'");
        const SExpr& target = fact.items[1];
        if (target.kind != SExpr::Kind::List || target.items.empty()) {
          fail(target, "expected a function term");
        }
        const std::string& name = expectName(target.items[0], "a function name");
        const int function = domain_.findFunction(name);
        if (function < 0) fail(target.items[0], "undefined function '" + name + "'");
        const Function& declared = domain_.functions[function];
        if (target.items.size() - 1 != declared.paramTypes.size()) {
          fail(target, "function '" + name + "' takes " +
                           std::to_string(declared.paramTypes.size()) + " argument(s), " +
                           std::to_string(target.items.size() - 1) + " given");
        }
        InitialFluent value{function, groundArgs(target), 0.0};
        const SExpr& rhs = fact.items[2];
        if (declared.isNumeric()) {
          if (!rhs.isAtom() || !parseNumber(rhs.text, value.value)) fail(rhs, "expected a number");
        } else {
          const ObjectId object = problem_.findObject(expectName(rhs, "an object name"));
          if (object < 0) fail(rhs, "undefined object '" + rhs.text + "'");
          value.value = object;
        }
        problem_.initFluents.push_back(std::move(value));
        continue;
      }
      const int predicate = domain_.findPredicate(head);
      if (predicate < 0) fail(fact.items[0], "undefined predicate '" + head + "'");
      if (fact.items.size() - 1 != domain_.predicates[predicate].paramTypes.size()) {
        fail(fact, "predicate '" + head + "' takes " +
                       std::to_string(domain_.predicates[predicate].paramTypes.size()) +
                       " argument(s), " + std::to_string(fact.items.size() - 1) + " given");
      }
      problem_.init.push_back({predicate, groundArgs(fact)});
    }
  }

  const Domain& domain_;
  Problem problem_;
  std::vector<char> redeclared_;  // per domain constant: declared again as an object
};

}  // namespace

int Domain::findType(const std::string& wanted) const {
  return findByName(types, wanted);
}
int Domain::findPredicate(const std::string& wanted) const {
  return findByName(predicates, wanted);
}
int Domain::findFunction(const std::string& wanted) const {
  return findByName(functions, wanted);
}
int Domain::findModule(const std::string& wanted) const {
  return findByName(modules, wanted);
}
int Domain::findAction(const std::string& wanted) const {
  return findByName(actions, wanted);
}

bool Domain::isSubtype(int type, int ancestor) const {
  for (int t = type; t >= 0; t = types[t].parent) {
    if (t == ancestor) return true;
  }
  return false;
}

ObjectId Problem::findObject(const std::string& wanted) const {
  const auto it = std::find(objectNames.begin(), objectNames.end(), wanted);
  return it == objectNames.end() ? -1 : static_cast<ObjectId>(it - objectNames.begin());
}

std::vector<ObjectId> Problem::objectsOfType(const Domain& domain, int type) const {
  std::vector<ObjectId> out;
  for (std::size_t i = 0; i < objectTypes.size(); ++i) {
    if (domain.isSubtype(objectTypes[i], type)) out.push_back(static_cast<ObjectId>(i));
  }
  return out;
}

Domain parseDomain(std::string_view text, const std::string& file) {
  return DomainParser(file).parse(readSExprs(text, file));
}

Problem parseProblem(std::string_view text, const std::string& file, const Domain& domain) {
  return ProblemParser(file, domain).parse(readSExprs(text, file));
}

Domain parseDomain(const std::vector<SExpr>& top, const std::string& file) {
  return DomainParser(file).parse(top);
}

Problem parseProblem(const std::vector<SExpr>& top, const std::string& file, const Domain& domain) {
  return ProblemParser(file, domain).parse(top);
}

Domain loadDomain(const std::string& path) {
  return parseDomain(readTextFile(path), path);
}

Problem loadProblem(const std::string& path, const Domain& domain) {
  return parseProblem(readTextFile(path), path, domain);
}

std::string describeAtom(const Domain& domain, const Problem& problem, int predicate,
                         const std::vector<ObjectId>& args) {
  std::string out = "(" + domain.predicates[predicate].name;
  for (const ObjectId arg : args) out += " " + problem.objectNames[arg];
  return out + ")";
}

}  // namespace kaboum::symbolic
