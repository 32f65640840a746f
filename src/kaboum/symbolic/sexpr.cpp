#include "kaboum/symbolic/sexpr.hpp"

#include <cctype>
#include <fstream>
#include <sstream>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {
namespace {

class Reader {
 public:
  Reader(std::string_view text, const std::string& file, std::size_t maxDepth)
      : text_(text), file_(file), maxDepth_(maxDepth) {}

  std::vector<SExpr> readAll() {
    std::vector<SExpr> out;
    if (text_.starts_with("\xEF\xBB\xBF")) at_ = 3;  // a UTF-8 byte order mark
    skipBlank();
    while (at_ < text_.size()) {
      out.push_back(readOne(0));
      skipBlank();
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what, SourcePos pos) const {
    throw InputError(locate(file_, what, pos.line, pos.column));
  }

  SourcePos here() const { return {line_, column_}; }

  // A line ends at "\n", "\r\n" or a lone "\r" (Python's universal newlines, as Fast Downward
  // reads files).
  bool endsLine(std::size_t at) const {
    return text_[at] == '\n' ||
           (text_[at] == '\r' && (at + 1 == text_.size() || text_[at + 1] != '\n'));
  }

  void advance() {
    if (endsLine(at_)) {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++at_;
  }

  void skipBlank() {
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == ';') {
        while (at_ < text_.size() && !endsLine(at_)) advance();
      } else if (isBlank(c)) {
        advance();
      } else {
        return;
      }
    }
  }

  // Whitespace as Python's str.split() sees it in ASCII text: also the separators 0x1c-0x1f.
  static bool isBlank(char c) {
    const auto ch = static_cast<unsigned char>(c);
    return std::isspace(ch) || (ch >= 0x1c && ch <= 0x1f);
  }

  static bool isDelimiter(char c) {
    return c == '(' || c == ')' || c == '[' || c == ']' || c == ';' || isBlank(c);
  }

  SExpr readOne(std::size_t depth) {
    SExpr node;
    node.pos = here();
    const char c = text_[at_];
    if (c == '(' || c == '[') {
      if (depth >= maxDepth_) fail("expressions nested too deeply", node.pos);
      const char close = c == '(' ? ')' : ']';
      node.kind = c == '(' ? SExpr::Kind::List : SExpr::Kind::BracketList;
      advance();
      skipBlank();
      while (true) {
        if (at_ >= text_.size()) {
          fail(std::string("expected '") + close + "' to close the list opened here", node.pos);
        }
        const char next = text_[at_];
        if (next == close) {
          advance();
          return node;
        }
        if (next == ')' || next == ']') {
          fail(std::string("expected '") + close + "' but found '" + next + "'", here());
        }
        node.items.push_back(readOne(depth + 1));
        skipBlank();
      }
    }
    if (c == ')' || c == ']') fail(std::string("unexpected '") + c + "'", node.pos);
    // Fast Downward's tokenizer rules: a '?' starts a new token, so "(aircraft?a)" reads as
    // "aircraft ?a"; names may hold any other printable ASCII character ('-', digits, ':', '.').
    while (at_ < text_.size() && !isDelimiter(text_[at_]) &&
           !(text_[at_] == '?' && !node.text.empty())) {
      const auto ch = static_cast<unsigned char>(text_[at_]);
      if (ch >= 0x80) fail("non-ASCII character outside a comment", here());
      if (ch < 0x20 || ch == 0x7f) fail("unexpected control character in name", here());
      node.original.push_back(static_cast<char>(ch));
      node.text.push_back(static_cast<char>(std::tolower(ch)));
      advance();
    }
    return node;
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t maxDepth_;
  std::size_t at_ = 0;
  long line_ = 1;
  long column_ = 1;
};

}  // namespace

std::vector<SExpr> readSExprs(std::string_view text, const std::string& file,
                              std::size_t maxDepth) {
  return Reader(text, file, maxDepth).readAll();
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(locate(path, "cannot open file"));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::string toString(const SExpr& expr) {
  if (expr.isAtom()) return expr.text;
  std::string out(1, expr.kind == SExpr::Kind::List ? '(' : '[');
  for (std::size_t i = 0; i < expr.items.size(); ++i) {
    if (i > 0) out += ' ';
    out += toString(expr.items[i]);
  }
  out += expr.kind == SExpr::Kind::List ? ')' : ']';
  return out;
}

}  // namespace kaboum::symbolic
