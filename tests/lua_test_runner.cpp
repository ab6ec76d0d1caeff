// Runs one Lua test script in a state with rigidlab opened as the CLI opens it. The script
// fails by raising an error (traceback on stderr, exit 1); `arg[0]` is the script's path.
#include <cstdio>

#include "lua/rigidlab.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lua_test_runner SCRIPT.lua\n");
    return 2;
  }
  lua_State* L = luaL_newstate();
  rigidlab::lua::open_all(L);
  lua_newtable(L);
  lua_pushstring(L, argv[1]);
  lua_rawseti(L, -2, 0);
  lua_setglobal(L, "arg");
  lua_pushcfunction(L, rigidlab::lua::traceback_handler);
  int status = luaL_loadfilex(L, argv[1], "t");
  if (status == LUA_OK) status = lua_pcall(L, 0, 0, -2);
  if (status != LUA_OK) std::fprintf(stderr, "%s\n", lua_tostring(L, -1));
  lua_close(L);
  return status == LUA_OK ? 0 : 1;
}
