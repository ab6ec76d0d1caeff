#include "tests/fuzz/api_names.hpp"

#include <lua.hpp>

#include <algorithm>
#include <set>

#include "lua/binding.hpp"
#include "lua/rigidlab.hpp"

namespace rigidlab::fuzz {
namespace {

// Sorts the documented function at the top of the stack by its qualified name: "type:method"
// is a method, "module.__meta" is skipped (operators are generated apart), anything else is a
// function reachable by that dotted name from the globals.
void classify(lua_State* L, std::set<std::string>& functions, std::set<std::string>& methods) {
  const lua::Entry* entry = lua::find_entry(L, -1);
  if (entry == nullptr || entry->function == nullptr) return;
  const std::string name = entry->qualified;
  const std::size_t colon = name.find(':');
  if (colon != std::string::npos) methods.insert(name.substr(colon + 1));
  else if (name.find(".__") == std::string::npos) functions.insert(name);
}

ApiNames read_names() {
  lua_State* L = luaL_newstate();
  lua::open_all(L);
  std::set<std::string> functions, methods;
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_getfield(L, -1, "rigidlab");
  const int lib = lua_gettop(L);
  for (lua_pushnil(L); lua_next(L, lib) != 0; lua_pop(L, 1)) {
    if (lua_type(L, -1) == LUA_TFUNCTION) classify(L, functions, methods);
    if (lua_type(L, -1) != LUA_TTABLE) continue;
    const int table = lua_gettop(L);
    for (lua_pushnil(L); lua_next(L, table) != 0; lua_pop(L, 1))
      if (lua_type(L, -1) == LUA_TFUNCTION) classify(L, functions, methods);
    if (lua_getmetatable(L, table)) {  // a callable type table: vec3(...), body{...}
      lua_getfield(L, -1, "__call");
      classify(L, functions, methods);
      lua_pop(L, 2);
    }
  }
  lua_close(L);
  return ApiNames{{functions.begin(), functions.end()}, {methods.begin(), methods.end()}};
}

}  // namespace

const ApiNames& api_names() {
  static const ApiNames names = read_names();
  return names;
}

}  // namespace rigidlab::fuzz
