// Temporary: replaced by the real CLI.
#include <cstdio>
#include <cstring>
#include "lua/rigidlab.hpp"
int main(int argc, char** argv) {
  lua_State* L = luaL_newstate();
  rigidlab::lua::open_all(L);
  if (argc == 3 && std::strcmp(argv[1], "-e") == 0) {
    if (luaL_dostring(L, argv[2]) != LUA_OK) { std::fprintf(stderr, "%s\n", lua_tostring(L, -1)); return 1; }
  }
  lua_close(L);
  return 0;
}
