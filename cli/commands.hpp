// The subcommands of rigidlab (`rigidlab lessons`, `rigidlab check ...`): a table, so that a
// new command is one entry here and its function elsewhere. The first argument names a command
// unless a regular file of that name exists (then it is a script, as in lua: `rigidlab check`
// runs the file ./check if there is one; `rigidlab lessons` still works where lessons/ is a
// directory).
#pragma once

#include <string>
#include <vector>

namespace rigidlab::cli {

struct Subcommand {
  const char* name;
  const char* arguments;  // for the usage text: "[ID|FILE ...]"
  const char* summary;    // one line for --help
  // Runs the command on the arguments after its name; returns the exit status.
  int (*run)(const std::vector<std::string>& arguments);
};

// Every subcommand; the array ends with an entry whose name is nullptr.
extern const Subcommand subcommands[];

// The subcommand argv[1] names, or nullptr when there is none or a file of that name exists.
const Subcommand* find_subcommand(int argc, char** argv);

}  // namespace rigidlab::cli
