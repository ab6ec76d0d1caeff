#include "cli/run.hpp"

#include <cstdio>
#include <cstring>
#include <string>

#include "cli/interrupt.hpp"
#include "cli/limits.hpp"
#include "cli/pretty_print.hpp"
#include "cli/usage.hpp"
#include "lua/text_only.hpp"

namespace rigidlab::cli {
namespace {

// lua.c's msghandler: an error object that is not a string becomes its __tostring or a
// description of its type; upvalue 1 says whether to append the stack traceback.
int message_handler(lua_State* L) {
  const char* message = lua_tostring(L, 1);
  if (message == nullptr) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  // A limit's "stopped: ..." is one line: where the code was is in it, the traceback is noise.
  const LimitedState* limits = LimitedState::of(L);
  const bool limit_stop = limits != nullptr && limits->is_stop(message);
  if (lua_toboolean(L, lua_upvalueindex(1)) && !limit_stop)
    luaL_traceback(L, L, message, 1);
  else
    lua_pushstring(L, message);
  return 1;
}

// Pushes the global `name`, read raw: the CLI runs none of the user's code outside the calls
// that are limited and interruptible (an __index on _G could loop). Returns its type.
int push_raw_global(lua_State* L, const char* name) {
  lua_pushglobaltable(L);
  lua_pushstring(L, name);
  const int type = lua_rawget(L, -2);
  lua_remove(L, -2);
  return type;
}

// Pushes arg[1], ..., arg[n] (the script's arguments) and returns n, as lua.c's pushargs (raw:
// see push_raw_global).
int push_script_arguments(lua_State* L) {
  if (push_raw_global(L, "arg") != LUA_TTABLE) luaL_error(L, "'arg' is not a table");
  const int count = static_cast<int>(lua_rawlen(L, -1));
  luaL_checkstack(L, count + 3, "too many arguments to script");
  for (int i = 1; i <= count; ++i) lua_rawgeti(L, -i, i);
  lua_remove(L, -count - 1);
  return count;
}

constexpr const char* script_prefix = "rigidlab: ";

}  // namespace

int call_chunk(lua_State* L, int arguments, int results, Traceback traceback) {
  const int function = lua_gettop(L) - arguments;
  lua_pushboolean(L, traceback == Traceback::append);
  lua_pushcclosure(L, message_handler, 1);
  lua_insert(L, function);
  int status;
  {
    InterruptibleCall interruptible(L);
    status = lua_pcall(L, arguments, results, function);
  }
  lua_remove(L, function);
  return status;
}

void report_error(lua_State* L, const char* prefix) {
  const char* message = lua_tostring(L, -1);
  std::string text = message != nullptr ? message : "(error object is not a string)";
  if (const LimitedState* limits = LimitedState::of(L)) text = limits->explain(text);
  std::fflush(stdout);  // what was printed before the error comes before it
  std::fprintf(stderr, "%s%s\n", prefix, text.c_str());
  std::fflush(stderr);
  lua_pop(L, 1);
}

int load_text(lua_State* L, const char* text, size_t length, const char* chunkname) {
  return luaL_loadbufferx(L, text, length, chunkname, "t");
}

int run_code(lua_State* L, const char* code) {
  int status = load_text(L, code, std::strlen(code), "=(command line)");
  if (status == LUA_OK) status = call_chunk(L, 0, 0, Traceback::append);
  if (status != LUA_OK) report_error(L, script_prefix);
  return status;
}

int require_module(lua_State* L, const char* spec) {
  const char* equals = std::strchr(spec, '=');
  const std::string global = equals != nullptr ? std::string(spec, equals) : std::string(spec);
  push_raw_global(L, "require");
  lua_pushstring(L, equals != nullptr ? equals + 1 : spec);
  const int status = call_chunk(L, 1, 1, Traceback::append);
  if (status == LUA_OK)
    lua_setglobal(L, global.c_str());
  else
    report_error(L, script_prefix);
  return status;
}

int run_script(lua_State* L, const char* path) {
  int status = luaL_loadfilex(L, path, "t");
  if (status == LUA_ERRFILE) {  // nothing ran: the command line named a file that is not there
    usage_error(lua_tostring(L, -1));
    lua_pop(L, 1);
    return status;
  }
  // Lua's refusal of a binary chunk names no file and no reason: say which one, and why.
  if (status == LUA_ERRSYNTAX) rigidlab::lua::explain_text_only(L, path != nullptr ? path : "stdin");
  if (status == LUA_OK) status = call_chunk(L, push_script_arguments(L), 0, Traceback::append);
  if (status != LUA_OK) report_error(L, script_prefix);
  return status;
}

void create_arg_table(lua_State* L, int argc, char** argv, int script) {
  lua_createtable(L, argc - script - 1 > 0 ? argc - script - 1 : 0, script + 1);
  for (int i = 0; i < argc; ++i) {
    lua_pushstring(L, argv[i]);
    lua_rawseti(L, -2, i - script);
  }
  lua_setglobal(L, "arg");
}

void print_results(lua_State* L, int base) {
  const int count = lua_gettop(L) - base;
  if (count <= 0) return;
  luaL_checkstack(L, LUA_MINSTACK, "too many results to print");
  lua_pushcfunction(L, pretty_print);
  lua_insert(L, base + 1);
  if (call_chunk(L, count, 0, Traceback::omit) != LUA_OK) {
    const LimitedState* limits = LimitedState::of(L);
    const char* message = lua_tostring(L, -1);
    if (message != nullptr && (limits == nullptr || !limits->stopped_by(message))) {
      lua_pushfstring(L, "error printing the results (%s)", message);
      lua_remove(L, -2);
    }
    report_error(L, "");
  }
}

}  // namespace rigidlab::cli
