#include "cli/view.hpp"

#include <cstdio>

#include "cli/interrupt.hpp"
#include "cli/limit_options.hpp"
#include "cli/limits.hpp"
#include "cli/run.hpp"
#include "cli/usage.hpp"
#include "lua/articulation.hpp"
#include "lua/binding.hpp"
#include "lua/render.hpp"
#include "lua/rigidlab.hpp"
#include "lua/world.hpp"

namespace rigidlab::cli {
namespace {

struct ViewSession {
  std::vector<std::string> arguments;  // the script, then its arguments
  int exit_status = 0;
};

// As main's protected_main: everything that touches Lua runs in protected mode.
int protected_view(lua_State* L) {
  ViewSession& session = *static_cast<ViewSession*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  rigidlab::lua::open_all(L);
  std::vector<char*> argv = {const_cast<char*>("rigidlab")};
  for (std::string& a : session.arguments) argv.push_back(a.data());
  create_arg_table(L, static_cast<int>(argv.size()), argv.data(), 1);
  lua_gc(L, LUA_GCRESTART);
  lua_gc(L, LUA_GCGEN, 0, 0);
  const char* path = session.arguments[0].c_str();
  int status = luaL_loadfilex(L, path, "t");
  if (status == LUA_ERRFILE) {
    session.exit_status = usage_error(lua_tostring(L, -1));
    return 0;
  }
  if (status == LUA_OK) {
    const TimedRun timed(L);  // --timeout bounds the script, not the time spent watching
    status = call_chunk(L, 0, 1, Traceback::append);
  }
  if (status != LUA_OK) {
    report_error(L, "rigidlab: ");
    session.exit_status = 1;
    return 0;
  }
  if (rigidlab::lua::test_world(L, -1) == nullptr &&
      rigidlab::lua::test_articulation(L, -1) == nullptr) {
    std::fprintf(stderr, "rigidlab: view: %s must return a world or an articulation, got %s\n",
                 path, rigidlab::lua::value_type_name(L, -1));
    session.exit_status = 1;
    return 0;
  }
  lua_getfield(L, -1, "view");
  lua_insert(L, -2);
  if (call_chunk(L, 1, 0, Traceback::append) != LUA_OK) {
    report_error(L, "rigidlab: ");
    session.exit_status = 1;
  }
  return 0;
}

}  // namespace

int view_command(const std::vector<std::string>& arguments) {
  // The limits come before the script; what follows it is the script's.
  Limits limits;
  std::size_t i = 0;
  for (; i < arguments.size() && arguments[i].size() > 1 && arguments[i][0] == '-'; ++i) {
    std::string error;
    if (arguments[i] == "--") {
      ++i;
      break;
    }
    if (!take_limit_option(arguments, i, limits, error))
      return usage_error("unrecognized option '" + arguments[i] + "' for 'view'");
    if (!error.empty()) return usage_error(error);
  }
  if (i == arguments.size())
    return usage_error("'view' needs a script that returns a world: rigidlab view FILE.lua");
  LimitedState state(limits, WhenStuck::exit);
  lua_State* L = state.get();
  if (L == nullptr) {
    std::fprintf(stderr, "rigidlab: cannot create the Lua state: %s\n",
                 state_failure_reason(limits));
    return 1;
  }
  lua_gc(L, LUA_GCSTOP);
  ViewSession session{std::vector<std::string>(arguments.begin() + static_cast<long>(i),
                                                arguments.end())};
  lua_pushcfunction(L, protected_view);
  lua_pushlightuserdata(L, &session);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
    report_error(L, "rigidlab: ");
    session.exit_status = 1;
  }
  return session.exit_status;
}

bool has_lesson_motion(lua_State* L) {
  lua::push_motion_view(L);
  const bool has = lua_isfunction(L, -1);
  lua_pop(L, 1);
  return has;
}

bool view_lesson_motion(lua_State* L, std::string& error) {
  const int top = lua_gettop(L);
  lua_pushcfunction(L, lua::traceback_handler);
  lua::push_motion_view(L);
  if (!lua_isfunction(L, -1)) {
    lua_settop(L, top);
    return true;
  }
  int status;
  {
    const InterruptibleCall interruptible(L);
    status = lua_pcall(L, 0, 0, top + 1);
  }
  if (status != LUA_OK) error = lua_tostring(L, -1) != nullptr ? lua_tostring(L, -1) : "error";
  lua_settop(L, top);
  return status == LUA_OK;
}

}  // namespace rigidlab::cli
