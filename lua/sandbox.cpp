#include "lua/sandbox.hpp"

#include <cstring>

#include "lua/binding.hpp"

namespace rigidlab::lua {
namespace {

const char sandbox_key = 0;

// load(chunk [, chunkname [, mode [, env]]]) with the mode forced to text: a binary chunk can
// crash the interpreter (the bytecode is not verified).
int text_only_load(lua_State* L) {
  const int args = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));  // the original load
  lua_pushvalue(L, 1);
  if (args >= 2) lua_pushvalue(L, 2); else lua_pushnil(L);
  if (args >= 3 && !lua_isnil(L, 3) && std::strcmp(luaL_checkstring(L, 3), "t") != 0)
    return luaL_error(L, "bad argument #3 to 'load' (only text chunks (\"t\") in the sandbox)");
  lua_pushliteral(L, "t");
  int pushed = 4;
  if (args >= 4) {
    lua_pushvalue(L, 4);
    ++pushed;
  }
  lua_call(L, pushed - 1, LUA_MULTRET);
  return lua_gettop(L) - args;
}

// Keeps only `kept` (nullptr-terminated) in the global library table `name`.
void keep_only(lua_State* L, const char* name, const char* const* kept) {
  if (lua_getglobal(L, name) != LUA_TTABLE) {
    lua_pop(L, 1);
    return;
  }
  lua_newtable(L);
  for (const char* const* k = kept; *k != nullptr; ++k) {
    lua_getfield(L, -2, *k);
    lua_setfield(L, -2, *k);
  }
  lua_setglobal(L, name);
  lua_pop(L, 1);
}

}  // namespace

void apply_sandbox(lua_State* L) {
  for (const char* name : {"io", "package", "dofile", "loadfile", "require"}) {
    lua_pushnil(L);
    lua_setglobal(L, name);
  }
  static const char* const os_kept[] = {"clock", "time", "date", "difftime", nullptr};
  keep_only(L, "os", os_kept);
  static const char* const debug_kept[] = {"traceback", nullptr};
  keep_only(L, "debug", debug_kept);
  if (lua_getglobal(L, "string") == LUA_TTABLE) {
    lua_pushnil(L);
    lua_setfield(L, -2, "dump");
  }
  lua_pop(L, 1);
  lua_getglobal(L, "load");
  lua_pushcclosure(L, text_only_load, 1);
  lua_setglobal(L, "load");
  // The library tables stay reachable through package.loaded only via require, which is gone;
  // the registry copy of package.loaded is not reachable without debug.getregistry.
  lua_pushboolean(L, 1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &sandbox_key);
}

bool is_sandboxed(lua_State* L) {
  const bool sandboxed = lua_rawgetp(L, LUA_REGISTRYINDEX, &sandbox_key) == LUA_TBOOLEAN;
  lua_pop(L, 1);
  return sandboxed;
}

}  // namespace rigidlab::lua
