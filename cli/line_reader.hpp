// Where the REPL's lines come from: a terminal, with libedit's line editing and a history kept
// in ~/.rigidlab_history, or any other stdin (a pipe, a file), read plainly without prompts.
#pragma once

#include <lua.hpp>

#include <memory>
#include <string>

namespace rigidlab::cli {

enum class ReadStatus { line, interrupted, end };

class LineReader {
 public:
  virtual ~LineReader() = default;
  // Shows `prompt` (terminal only) and reads one line, without its newline, into `line`.
  // `interrupted`: Ctrl-C at the prompt (the line is dropped); `end`: end of input (Ctrl-D).
  virtual ReadStatus read(const char* prompt, std::string& line) = 0;
  // Records a chunk the user entered in the history (terminal only).
  virtual void remember(const std::string& chunk) = 0;
};

// The terminal reader: libedit initialised and the history loaded now, not before. Tab
// completes the names reachable from the globals of L. The history file (cli/history_file.hpp)
// is rewritten after every chunk so that os.exit or a kill loses nothing.
std::unique_ptr<LineReader> make_terminal_reader(lua_State* L);
// Plain lines from stdin.
std::unique_ptr<LineReader> make_stream_reader();

}  // namespace rigidlab::cli
