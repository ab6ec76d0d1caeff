// The command line of `rigidlab [options] [script [args]]`, parsed as Lua's lua.c parses its
// own: options come first, the first argument that is not an option is the script, and every
// argument after it belongs to the script. -e and -l run in the order given, before the script.
#pragma once

#include <string>
#include <vector>

#include "cli/limits.hpp"

namespace rigidlab::cli {

struct Options {
  // An -e CODE or -l [GLOBAL=]MODULE, kept in command-line order.
  struct Action {
    char option;  // 'e' or 'l'
    std::string value;
  };
  std::vector<Action> actions;
  bool interactive = false;         // -i: the REPL after the script and the actions
  bool version = false;             // -v, --version
  bool help = false;                // -h, --help
  bool warnings = false;            // -W: Lua's warn() prints
  bool ignore_environment = false;  // -E: LUA_PATH and LUA_CPATH are not read
  bool sandbox = false;             // --sandbox: lua/sandbox.hpp
  Limits limits;                    // --max-instructions, --max-memory, --timeout
  int script = 0;                   // index in argv of the script ("-": stdin), 0 if none
};

// Fills `options` from argv; returns "" or the message of a usage error ("unrecognized option
// '-x'", "'-e' needs an argument", "'--timeout' needs a number of seconds >= 0, got 'x'").
std::string parse_options(int argc, char** argv, Options& options);

// True when the script argument means "read the script from stdin" (`-`, unless written after
// `--`, where it names a file called "-").
bool script_is_stdin(char** argv, const Options& options);

}  // namespace rigidlab::cli
