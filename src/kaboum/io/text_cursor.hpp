// A position in a text file that tracks line and column, reads words and numbers, and throws
// located InputErrors ("file:line:col: what"). Shared by the OBJ, OFF, PLY, STL and VRML readers.
#pragma once

#include <string>
#include <string_view>

namespace kaboum::io {

// Which characters separate words beyond spaces, tabs and line ends.
struct TextSyntax {
  bool hashComments = false;     // '#' starts a comment running to the end of the line
  bool commaIsSpace = false;     // ',' separates like a space (VRML)
  std::string_view punctuation;  // characters that form one-character words on their own
};

struct TextLocation {
  long line = 0;
  long column = 0;
};

class TextCursor {
 public:
  TextCursor(std::string_view text, const std::string& file, TextSyntax syntax = {});

  // Skips spaces, tabs, carriage returns and (when enabled) commas and comments on this line.
  void skipBlanks();
  // skipBlanks() across line ends too.
  void skipWhitespace();
  // True when only blanks remain before the next line end (or the end of the text).
  bool atLineEnd();
  // Moves past the next line end.
  void skipLine();
  bool atEnd() const { return pos_ == end_; }
  // Where the cursor is in the text it was given.
  const char* position() const { return pos_; }

  // The next word after blanks on this line (a punctuation character alone, or a run up to the
  // next separator); empty at a line end.
  std::string_view word();
  // Like word() but skips line ends first; empty only at the end of the text.
  std::string_view nextWord();
  // Returns the next word without consuming it (crossing line ends).
  std::string_view peekWord();
  // After an opening '"': the string up to the closing quote (\" and \\ unescaped), which may
  // span lines. Throws when the text ends first.
  std::string quoted();
  // Rest of the current line, without the line end.
  std::string_view restOfLine();

  // Parses `token` as a whole: a finite double / a 64-bit integer. Throws at `where` otherwise;
  // `what` names the expected value, e.g. "vertex coordinate".
  double toNumber(std::string_view token, std::string_view what) const;
  long long toInteger(std::string_view token, std::string_view what) const;
  // word() parsed as above; throws "expected <what>" when the line ended.
  double number(std::string_view what);
  long long integer(std::string_view what);

  // Location of the start of the most recently returned word.
  TextLocation wordLocation() const { return last_; }
  TextLocation here() const;
  [[noreturn]] void fail(const std::string& what) const;  // at the last word
  [[noreturn]] void fail(TextLocation at, const std::string& what) const;

 private:
  bool isSeparator(char c) const;
  bool isPunctuation(char c) const;
  void advanceLine();  // pos_ is at '\n': moves past it
  TextLocation locationOf(const char* at) const;

  const char* pos_;
  const char* end_;
  const char* lineStart_;
  long line_ = 1;
  TextLocation last_{1, 1};
  const std::string& file_;
  TextSyntax syntax_;
};

}  // namespace kaboum::io
