// rigidlab: the command line. Behaves as Lua's own `lua` (lua.c) where they overlap: options,
// the `arg` table, a protected main, the REPL; and dispatches the subcommands of
// cli/commands.hpp. Exit status: 0 success, 1 a script error, 2 a usage error.
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/limits.hpp"
#include "cli/options.hpp"
#include "cli/repl.hpp"
#include "cli/run.hpp"
#include "cli/usage.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"

namespace {

using namespace rigidlab::cli;

// What pmain needs and what it reports back.
struct Session {
  int argc;
  char** argv;
  const Options* options;
  int exit_status = 0;
};

// Runs -e and -l in order; false after the first failure (already reported).
bool run_actions(lua_State* L, const Options& options) {
  for (const Options::Action& action : options.actions) {
    const int status = action.option == 'e' ? run_code(L, action.value.c_str())
                                            : require_module(L, action.value.c_str());
    if (status != LUA_OK) return false;
  }
  return true;
}

// lua.c's pmain: everything that touches Lua runs here, in protected mode.
int protected_main(lua_State* L) {
  Session& session = *static_cast<Session*>(lua_touserdata(L, 1));
  const Options& options = *session.options;
  lua_settop(L, 0);
  if (options.version) std::printf("%s\n", version_line().c_str());
  if (options.ignore_environment) {  // read by the package library as it opens
    lua_pushboolean(L, 1);
    lua_setfield(L, LUA_REGISTRYINDEX, "LUA_NOENV");
  }
  rigidlab::lua::open_all(L);
  if (options.sandbox) rigidlab::lua::apply_sandbox(L);
  create_arg_table(L, session.argc, session.argv, options.script);
  lua_gc(L, LUA_GCRESTART);
  lua_gc(L, LUA_GCGEN, 0, 0);  // as lua.c: generational collection
  if (options.warnings) lua_warning(L, "@on", 0);
  {
    const TimedRun timed(L);  // -e, -l and the script share the limits; the REPL times each chunk
    if (!run_actions(L, options)) {
      session.exit_status = 1;
      return 0;
    }
    if (options.script > 0) {
      const char* path = script_is_stdin(session.argv, options) ? nullptr
                                                                : session.argv[options.script];
      const int status = run_script(L, path);
      if (status != LUA_OK) {
        session.exit_status = status == LUA_ERRFILE ? exit_usage : 1;
        return 0;
      }
    }
  }
  const bool nothing_to_run = options.script == 0 && options.actions.empty() && !options.version;
  if (options.interactive || nothing_to_run) run_repl(L, isatty(STDIN_FILENO) != 0);
  return 0;
}

int run_lua(int argc, char** argv, const Options& options) {
  LimitedState state(options.limits, WhenStuck::exit);
  lua_State* L = state.get();
  if (L == nullptr) {
    std::fprintf(stderr, "rigidlab: cannot create the Lua state: %s\n",
                 state_failure_reason(options.limits));
    return 1;
  }
  lua_gc(L, LUA_GCSTOP);  // no collection while the libraries are built
  Session session{argc, argv, &options};
  lua_pushcfunction(L, protected_main);
  lua_pushlightuserdata(L, &session);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
    report_error(L, "rigidlab: ");
    session.exit_status = 1;
  }
  return session.exit_status;
}

}  // namespace

int main(int argc, char** argv) {
  if (const Subcommand* command = find_subcommand(argc, argv))
    return command->run(std::vector<std::string>(argv + 2, argv + argc));
  Options options;
  const std::string error = parse_options(argc, argv, options);
  if (!error.empty()) return usage_error(error);
  if (options.help) {
    print_help(stdout);
    return 0;
  }
  return run_lua(argc, argv, options);
}
