#include "cli/usage.hpp"

#include <lua.hpp>

#include <algorithm>
#include <cstring>

#include "cli/commands.hpp"

namespace rigidlab::cli {

std::string version_line() {
  return std::string("rigidlab " RIGIDLAB_VERSION " (") + LUA_RELEASE + ")";
}

std::string banner() { return version_line() + " — help() lists topics, Ctrl-D exits"; }

void print_help(std::FILE* out) {
  std::fputs(
      "usage: rigidlab [options] [script [args]]\n"
      "       rigidlab COMMAND [arguments]\n"
      "\n"
      "Without a script or -e, rigidlab starts the REPL when stdin is a terminal; otherwise\n"
      "it evaluates stdin line by line as the REPL would, without prompts. In a script and in\n"
      "the REPL every rigidlab name is a global; `arg` holds the script's arguments.\n"
      "\n"
      "Options:\n"
      "  -e CODE        run CODE (repeatable; in order, before the script)\n"
      "  -l MOD         require library MOD into global MOD (-l G=MOD: into global G)\n"
      "  -i             enter the REPL after running the script and -e\n"
      "  -v, --version  print the version\n"
      "  -h, --help     print this help\n"
      "  -E             ignore the environment variables LUA_PATH and LUA_CPATH\n"
      "  -W             turn warnings on\n"
      "  --sandbox      run without io, os (but clock, time, date, difftime), require,\n"
      "                 dofile, loadfile, string.dump and debug (but traceback)\n"
      "  --             stop handling options (the next argument is the script)\n"
      "  -              run stdin as a script\n"
      "\n"
      "Limits (0 or absent: none). The script, -e and -l share them; the REPL applies them\n"
      "to each chunk. A run that passes one is stopped with a message naming it (exit 1):\n"
      "  --max-instructions N  N Lua VM instructions\n"
      "  --max-memory MB       MB megabytes of Lua memory in use\n"
      "  --timeout S           S seconds of wall-clock time, also inside w:step; a C function\n"
      "                        that has not returned 1 s later ends the process\n"
      "\n"
      "Commands (the first argument, unless a file of that name exists):\n",
      out);
  size_t width = 0;
  for (const Subcommand* command = subcommands; command->name != nullptr; ++command)
    width = std::max(width, std::strlen(command->name) + 1 + std::strlen(command->arguments));
  for (const Subcommand* command = subcommands; command->name != nullptr; ++command) {
    const std::string usage = std::string(command->name) + " " + command->arguments;
    std::fprintf(out, "  %-*s  %s\n", static_cast<int>(width), usage.c_str(), command->summary);
  }
  std::fputs(
      "\n"
      "`check` runs each lesson in its own process, by default under 500000000\n"
      "instructions, 256 MB and 10 s; LIMITS (the options above) change them.\n"
      "\n"
      "Exit status: 0 success; 1 a script error (message and traceback on stderr) or a\n"
      "failed check; 2 a usage error (unknown option, missing argument, a script that cannot\n"
      "be opened); os.exit(n) exits n.\n",
      out);
}

int usage_error(const std::string& message) {
  std::fflush(stdout);
  std::fprintf(stderr, "rigidlab: %s\nTry 'rigidlab --help' for more information.\n",
               message.c_str());
  return exit_usage;
}

}  // namespace rigidlab::cli
