// S-expression reader for PDDL text: lists, symbols and numbers with their line:column, so every
// later stage can report errors as "file:line:col: ...". The lexical rules are those of Fast
// Downward's translator (docs/formats.md#lexical-rules); square brackets mark PDDL/M module calls.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace kaboum::symbolic {

struct SourcePos {
  long line = 0;
  long column = 0;
};

// One node of the tree: either an atom (symbol or number, lower-cased) or a list.
struct SExpr {
  enum class Kind { Atom, List, BracketList };
  Kind kind = Kind::Atom;
  std::string text;      // atom text, lower-cased (PDDL is case-insensitive)
  std::string original;  // atom text as written (procedure and library names are case-sensitive)
  std::vector<SExpr> items;
  SourcePos pos;

  bool isAtom() const { return kind == Kind::Atom; }
  bool isList() const { return kind != Kind::Atom; }
  bool isAtom(std::string_view value) const { return isAtom() && text == value; }
  // True for a list whose first item is the atom `head`.
  bool startsWith(std::string_view head) const {
    return isList() && !items.empty() && items.front().isAtom(head);
  }
};

// Parses all top-level expressions of `text`; throws InputError naming `file`:line:col on
// unbalanced brackets or stray characters. Nesting deeper than `maxDepth` is rejected (no stack
// overflow).
std::vector<SExpr> readSExprs(std::string_view text, const std::string& file,
                              std::size_t maxDepth = 512);

// Reads a whole file; throws InputError if it cannot be opened.
std::string readTextFile(const std::string& path);

// Renders an expression back to PDDL text (used in error and validation messages).
std::string toString(const SExpr& expr);

}  // namespace kaboum::symbolic
