// Running Lua chunks as lua.c does: every call in protected mode through a message handler,
// Ctrl-C interruptible, errors reported on stderr, results printed with the global `print`.
#pragma once

#include <lua.hpp>

namespace rigidlab::cli {

// Whether a runtime error's message gets a stack traceback appended (scripts and the REPL in
// a terminal) or stays one line (the REPL reading a pipe).
enum class Traceback { append, omit };

// Calls the function below its `arguments` on the stack, Ctrl-C interruptible. Returns the
// status; leaves `results` results (LUA_MULTRET: all) or the error message.
int call_chunk(lua_State* L, int arguments, int results, Traceback traceback);

// Prints the error message on top of the stack on stderr, after `prefix` ("rigidlab: " for
// scripts, "" in the REPL), and pops it.
void report_error(lua_State* L, const char* prefix);

// Loads text (never bytecode) as a chunk; returns the status, chunk or message on the stack.
int load_text(lua_State* L, const char* text, size_t length, const char* chunkname);

// -e CODE: runs CODE as chunk "(command line)". Reports errors; returns the status.
int run_code(lua_State* L, const char* code);
// -l [GLOBAL=]MODULE: GLOBAL = require(MODULE). Reports errors; returns the status.
int require_module(lua_State* L, const char* spec);
// Runs the script `path` (nullptr: stdin) with the positive entries of the global `arg` as
// its `...`. Reports errors; returns the status (LUA_ERRFILE: it could not be opened).
int run_script(lua_State* L, const char* path);

// Sets the global `arg` as lua.c does: arg[0] the script, arg[1..] its arguments, negative
// indices the interpreter and its options. `script` is the index of the script in argv, 0 if
// none (then arg[0] is the interpreter).
void create_arg_table(lua_State* L, int argc, char** argv, int script);

// Prints every value above stack index `base` (cli/pretty_print.hpp: tables with their fields,
// tab separated), then removes them; limited and interruptible as a chunk is. An error (a
// limit, Ctrl-C) is reported, not raised.
void print_results(lua_State* L, int base);

}  // namespace rigidlab::cli
