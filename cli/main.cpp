// Temporary: replaced by the real CLI (REPL, scripts). Dispatches the lesson commands and
// runs a file or -e CODE.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/lessons.hpp"
#include "lua/rigidlab.hpp"

int main(int argc, char** argv) {
  if (argc >= 2) {
    const std::vector<std::string> rest(argv + 2, argv + argc);
    if (!std::strcmp(argv[1], "lessons")) return rigidlab::cli::list_lessons();
    if (!std::strcmp(argv[1], "lesson")) return rigidlab::cli::run_lesson(rest.empty() ? "" : rest[0]);
    if (!std::strcmp(argv[1], "check"))
      return rigidlab::cli::check_lessons(rest, rigidlab::cli::default_check_limits());
  }
  lua_State* L = luaL_newstate();
  rigidlab::lua::open_all(L);
  int status = LUA_OK;
  if (argc == 3 && std::strcmp(argv[1], "-e") == 0) status = luaL_dostring(L, argv[2]);
  else if (argc == 2) status = luaL_dofile(L, argv[1]);
  if (status != LUA_OK) std::fprintf(stderr, "rigidlab: %s\n", lua_tostring(L, -1));
  lua_close(L);
  return status == LUA_OK ? 0 : 1;
}
