#include "lua/sandbox.hpp"

#include "lua/binding.hpp"

namespace rigidlab::lua {
namespace {

const char sandbox_key = 0;

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
  // load is text only everywhere already (open_all: lua/text_only.hpp).
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
