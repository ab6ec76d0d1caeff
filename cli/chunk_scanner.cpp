#include "cli/chunk_scanner.hpp"

#include <cctype>
#include <cstring>

namespace rigidlab::cli {
namespace {

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
bool is_name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The level of the long bracket `[==[` opening at `i` (its `=` count), or -1 for a plain `[`.
// On success `i` is moved past it.
int long_bracket_level(const std::string& line, std::size_t& i) {
  std::size_t j = i + 1;
  while (j < line.size() && line[j] == '=') ++j;
  if (j >= line.size() || line[j] != '[') return -1;
  const int level = static_cast<int>(j - i - 1);
  i = j + 1;
  return level;
}

bool is_one_of(const std::string& word, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (word == w) return true;
  return false;
}

}  // namespace

bool ChunkScanner::open() const {
  return long_level_ >= 0 || quote_ != 0 || brackets_ > 0 || blocks_ > 0 || wants_more_;
}

void ChunkScanner::feed(const std::string& line) {
  std::size_t i = 0;
  if (long_level_ >= 0) scan_long_bracket(line, i);
  if (quote_ != 0) scan_short_string(line, i);
  while (i < line.size() && long_level_ < 0 && quote_ == 0) {
    const char c = line[i];
    if (is_space(c)) {
      ++i;
    } else if (c == '-' && i + 1 < line.size() && line[i + 1] == '-') {  // a comment
      i += 2;
      if (i < line.size() && line[i] == '[') {
        const int level = long_bracket_level(line, i);
        if (level >= 0) {
          long_level_ = level;
          in_comment_ = true;
          scan_long_bracket(line, i);
          continue;
        }
      }
      return;  // to the end of the line
    } else if (c == '[') {
      std::size_t after = i;
      const int level = long_bracket_level(line, after);
      if (level < 0) {
        scan_symbol(line, i);
        continue;
      }
      i = after;
      long_level_ = level;
      in_comment_ = false;
      scan_long_bracket(line, i);
    } else if (c == '"' || c == '\'') {
      quote_ = c;
      ++i;
      scan_short_string(line, i);
    } else if (is_name_start(c)) {
      scan_name(line, i);
    } else if (is_digit(c) || (c == '.' && i + 1 < line.size() && is_digit(line[i + 1]))) {
      scan_number(line, i);
    } else {
      scan_symbol(line, i);
    }
  }
}

// Inside a long string or comment of level long_level_: looks for its closing bracket.
void ChunkScanner::scan_long_bracket(const std::string& line, std::size_t& i) {
  const std::string close = "]" + std::string(static_cast<std::size_t>(long_level_), '=') + "]";
  const std::size_t end = line.find(close, i);
  if (end == std::string::npos) {
    i = line.size();
    return;
  }
  i = end + close.size();
  if (!in_comment_) wants_more_ = false;  // a string is a complete value
  long_level_ = -1;
  in_comment_ = false;
}

// Inside a short string opened by quote_: to its end, or to the end of the line when a `\`
// continues it there (or a `\z` skips the line break). A line break otherwise is Lua's
// "unfinished string": an error the parse reports, so nothing stays open.
void ChunkScanner::scan_short_string(const std::string& line, std::size_t& i) {
  while (i < line.size()) {
    const char c = line[i];
    if (skip_spaces_ && is_space(c)) {
      ++i;
      continue;
    }
    skip_spaces_ = false;
    if (c == '\\') {
      const bool line_break_next = i + 1 == line.size() || (i + 2 == line.size() && line[i + 1] == '\r');
      if (line_break_next) return;  // `\` and a newline: the string goes on
      if (line[i + 1] == 'z') skip_spaces_ = true;
      i += 2;
    } else if (c == quote_) {
      quote_ = 0;
      wants_more_ = false;
      ++i;
      return;
    } else {
      ++i;
    }
  }
  if (!skip_spaces_) {  // Lua's error: nothing stays open
    quote_ = 0;
    wants_more_ = false;
  }
}

void ChunkScanner::scan_name(const std::string& line, std::size_t& i) {
  const std::size_t start = i;
  while (i < line.size() && is_name_char(line[i])) ++i;
  const std::string word = line.substr(start, i - start);
  if (is_one_of(word, {"function", "do", "if", "repeat"})) {
    ++blocks_;
    wants_more_ = true;
  } else if (word == "end") {
    --blocks_;
    wants_more_ = false;
  } else if (word == "until") {
    --blocks_;
    wants_more_ = true;  // its condition follows
  } else {
    wants_more_ = is_one_of(word, {"and", "or", "not", "local", "in", "goto", "while", "for",
                                   "then", "else", "elseif"});
  }
}

// A numeral, read greedily as Lua's lexer does (digits, letters, points, an exponent's sign).
void ChunkScanner::scan_number(const std::string& line, std::size_t& i) {
  while (i < line.size()) {
    const char c = line[i];
    const bool exponent_sign = (c == '+' || c == '-') && std::strchr("eEpP", line[i - 1]) != nullptr;
    if (!is_name_char(c) && c != '.' && !exponent_sign) break;
    ++i;
  }
  wants_more_ = false;
}

void ChunkScanner::scan_symbol(const std::string& line, std::size_t& i) {
  const char c = line[i];
  if (c == '(' || c == '[' || c == '{') {
    ++brackets_;
    wants_more_ = true;
    ++i;
    return;
  }
  if (c == ')' || c == ']' || c == '}') {
    --brackets_;
    wants_more_ = false;
    ++i;
    return;
  }
  if (line.compare(i, 3, "...") == 0) {  // a value, not the `..` operator
    wants_more_ = false;
    i += 3;
    return;
  }
  if (line.compare(i, 2, "::") == 0) {  // a label's bracket
    wants_more_ = false;
    i += 2;
    return;
  }
  // Any other symbol is an operator or a separator that needs what follows, except `;`.
  wants_more_ = c != ';';
  ++i;
}

}  // namespace rigidlab::cli
