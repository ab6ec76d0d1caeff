// The read-eval-print loop, lua.c's doREPL: each line is first tried as `return <line>;` so
// that an expression prints its values (tab separated, through the global `print`); otherwise
// it is a statement, and while the syntax error ends in <eof> another line is read. Errors are
// reported and the loop goes on; it ends at end of input (Ctrl-D).
#pragma once

#include <lua.hpp>

namespace rigidlab::cli {

// Runs the REPL on stdin. In a terminal: banner, prompts `> ` and `>> ` (or the globals
// _PROMPT and _PROMPT2), libedit and its history, Ctrl-C handling, tracebacks after runtime
// errors. Otherwise: no banner or prompts, each error on one line of stderr.
void run_repl(lua_State* L, bool terminal);

}  // namespace rigidlab::cli
