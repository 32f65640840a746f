#include "kaboum/io/text_cursor.hpp"

#include <charconv>
#include <cmath>

#include "kaboum/core/error.hpp"

namespace kaboum::io {

namespace {

// from_chars rejects a leading '+', which the text formats allow.
std::string_view withoutPlus(std::string_view token) {
  if (token.size() > 1 && token.front() == '+') token.remove_prefix(1);
  return token;
}

std::string shown(std::string_view token) {
  constexpr std::size_t kShown = 40;
  if (token.size() > kShown) return "'" + std::string(token.substr(0, kShown)) + "...'";
  return "'" + std::string(token) + "'";
}

}  // namespace

TextCursor::TextCursor(std::string_view text, const std::string& file, TextSyntax syntax)
    : pos_(text.data()),
      end_(text.data() + text.size()),
      lineStart_(text.data()),
      file_(file),
      syntax_(syntax) {}

bool TextCursor::isPunctuation(char c) const {
  return syntax_.punctuation.find(c) != std::string_view::npos;
}

bool TextCursor::isSeparator(char c) const {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f' ||
         (syntax_.hashComments && c == '#') || (syntax_.commaIsSpace && c == ',') ||
         isPunctuation(c);
}

void TextCursor::skipBlanks() {
  while (pos_ != end_) {
    const char c = *pos_;
    if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' ||
        (syntax_.commaIsSpace && c == ',')) {
      ++pos_;
    } else if (syntax_.hashComments && c == '#') {
      while (pos_ != end_ && *pos_ != '\n') ++pos_;
    } else {
      return;
    }
  }
}

void TextCursor::skipWhitespace() {
  for (;;) {
    skipBlanks();
    if (pos_ == end_ || *pos_ != '\n') return;
    advanceLine();
  }
}

bool TextCursor::atLineEnd() {
  skipBlanks();
  return pos_ == end_ || *pos_ == '\n';
}

void TextCursor::skipLine() {
  while (pos_ != end_ && *pos_ != '\n') ++pos_;
  if (pos_ != end_) advanceLine();
}

void TextCursor::advanceLine() {
  ++pos_;
  ++line_;
  lineStart_ = pos_;
}

std::string_view TextCursor::word() {
  skipBlanks();
  last_ = locationOf(pos_);
  const char* start = pos_;
  if (pos_ == end_ || *pos_ == '\n') return {};
  if (isPunctuation(*pos_)) {
    ++pos_;
  } else {
    while (pos_ != end_ && !isSeparator(*pos_)) ++pos_;
  }
  return {start, static_cast<std::size_t>(pos_ - start)};
}

std::string_view TextCursor::nextWord() {
  skipWhitespace();
  return word();
}

std::string_view TextCursor::peekWord() {
  skipWhitespace();
  const char* savedPos = pos_;
  const TextLocation savedLast = last_;
  const std::string_view token = word();
  pos_ = savedPos;
  last_ = savedLast;
  return token;
}

std::string TextCursor::quoted() {
  const TextLocation opening = last_;
  std::string value;
  while (pos_ != end_ && *pos_ != '"') {
    if (*pos_ == '\\' && pos_ + 1 != end_) ++pos_;
    if (*pos_ == '\n') {
      value += '\n';
      advanceLine();
    } else {
      value += *pos_++;
    }
  }
  if (pos_ == end_) fail(opening, "unterminated string");
  ++pos_;
  return value;
}

std::string_view TextCursor::restOfLine() {
  const char* start = pos_;
  while (pos_ != end_ && *pos_ != '\n') ++pos_;
  std::string_view line{start, static_cast<std::size_t>(pos_ - start)};
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

double TextCursor::toNumber(std::string_view token, std::string_view what) const {
  const std::string_view digits = withoutPlus(token);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error == std::errc::result_out_of_range) {
    fail("non-finite " + std::string(what) + " " + shown(token));
  }
  if (error != std::errc() || end != digits.data() + digits.size()) {
    fail("expected " + std::string(what) + ", found " + shown(token));
  }
  if (!std::isfinite(value)) fail("non-finite " + std::string(what) + " " + shown(token));
  return value;
}

long long TextCursor::toInteger(std::string_view token, std::string_view what) const {
  const std::string_view digits = withoutPlus(token);
  long long value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size()) {
    fail("expected " + std::string(what) + ", found " + shown(token));
  }
  return value;
}

double TextCursor::number(std::string_view what) {
  const std::string_view token = word();
  if (token.empty()) fail("expected " + std::string(what) + ", found end of line");
  return toNumber(token, what);
}

long long TextCursor::integer(std::string_view what) {
  const std::string_view token = word();
  if (token.empty()) fail("expected " + std::string(what) + ", found end of line");
  return toInteger(token, what);
}

TextLocation TextCursor::locationOf(const char* at) const {
  return {line_, static_cast<long>(at - lineStart_) + 1};
}

TextLocation TextCursor::here() const {
  return locationOf(pos_);
}

void TextCursor::fail(const std::string& what) const {
  fail(last_, what);
}

void TextCursor::fail(TextLocation at, const std::string& what) const {
  throw InputError(locate(file_, what, at.line, at.column));
}

}  // namespace kaboum::io
