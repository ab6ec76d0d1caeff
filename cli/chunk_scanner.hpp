// Whether the lines of a REPL chunk typed so far can be a complete chunk, told line by line in
// time linear in the text: the REPL parses the pending chunk after each line to find out (as
// lua.c does), and parsing all of it again after every line made reading quadratic — a
// 20,000-line `--[[` comment took 20 s. The scanner reads each line once, as Lua's lexer
// would (long brackets of any level, comments, strings with escapes, numbers, names), and
// keeps what stays open at the end: a long string or comment, a string continued with `\`,
// brackets, blocks (`function`, `do`, `if`, `repeat` against `end` and `until`) and a last
// token that needs another (`x = 1 +`). While something is open the chunk cannot be complete,
// so the REPL need not parse it (cli/repl.cpp).
//
// The scanner only says "open" where Lua's parser would stop at <eof> or at an error: it never
// makes a complete chunk wait. An error inside an open chunk is found by the parses the REPL
// still makes while the chunk is small, or as it doubles.
#pragma once

#include <string>

namespace rigidlab::cli {

class ChunkScanner {
 public:
  // Reads the next line of the chunk (without its newline).
  void feed(const std::string& line);
  // True when the chunk read so far cannot be complete: something above is open.
  bool open() const;

 private:
  void scan_long_bracket(const std::string& line, std::size_t& i);
  void scan_short_string(const std::string& line, std::size_t& i);
  void scan_name(const std::string& line, std::size_t& i);
  void scan_number(const std::string& line, std::size_t& i);
  void scan_symbol(const std::string& line, std::size_t& i);

  int long_level_ = -1;   // level of the long string or comment open at the end, or -1
  bool in_comment_ = false;
  char quote_ = 0;        // the quote of a short string continued on the next line, or 0
  bool skip_spaces_ = false;  // a `\z` in that string: the next line's spaces are skipped
  long brackets_ = 0;     // ( [ { minus ) ] }
  long blocks_ = 0;       // function do if repeat minus end until
  bool wants_more_ = false;  // the last token needs another one (an operator, `local`, ...)
};

}  // namespace rigidlab::cli
