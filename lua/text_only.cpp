#include "lua/text_only.hpp"

#include <cstring>

namespace rigidlab::lua {
namespace {

constexpr const char* lua_refusal = "attempt to load a binary chunk (mode is 't')";
constexpr const char* our_refusal = "attempt to load a binary chunk (rigidlab loads text only)";

// The mode argument at `arg` of load/loadfile: absent, nil or "t"; anything else is an error.
void check_text_mode(lua_State* L, int arg) {
  if (lua_isnoneornil(L, arg)) return;
  const char* mode = luaL_checkstring(L, arg);
  if (std::strcmp(mode, "t") != 0)
    luaL_argerror(L, arg,
                  lua_pushfstring(L, "mode must be \"t\": rigidlab loads text only, got \"%s\"",
                                  mode));
}

// load(chunk [, chunkname [, mode [, env]]]) and loadfile([filename [, mode [, env]]]): the
// original (upvalue 1) with the mode forced to "t"; `mode_arg` is where the mode goes.
template <int mode_arg>
int text_loader(lua_State* L) {
  check_text_mode(L, mode_arg);
  const int given = lua_gettop(L);
  const int count = given > mode_arg ? given : mode_arg;  // the env, when given, stays last
  lua_pushvalue(L, lua_upvalueindex(1));
  for (int i = 1; i <= count; ++i) {
    if (i == mode_arg)
      lua_pushliteral(L, "t");
    else if (i <= given)
      lua_pushvalue(L, i);
    else
      lua_pushnil(L);
  }
  lua_call(L, count, 2);
  if (lua_isnil(L, -2) && lua_type(L, -1) == LUA_TSTRING)  // loadfile names its file
    explain_text_only(L, mode_arg == 2 ? luaL_optstring(L, 1, "stdin") : nullptr);
  return 2;
}

int dofile_continued(lua_State* L, int, lua_KContext) { return lua_gettop(L) - 1; }

// dofile([filename]): lbaselib's, loading text only.
int text_dofile(lua_State* L) {
  const char* filename = luaL_optstring(L, 1, nullptr);
  lua_settop(L, 1);
  if (luaL_loadfilex(L, filename, "t") != LUA_OK) {
    explain_text_only(L, filename != nullptr ? filename : "stdin");
    return lua_error(L);
  }
  lua_callk(L, 0, LUA_MULTRET, 0, dofile_continued);
  return dofile_continued(L, 0, 0);
}

// require's searcher for Lua files: finds `name` along package.path with the original
// package.searchpath (upvalue 2) and loads it as text. As loadlib.c's searcher_Lua: returns
// the loader and the file name, or the "no file ..." message.
int text_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_getfield(L, lua_upvalueindex(1), "path");
  if (lua_type(L, -1) != LUA_TSTRING) luaL_error(L, "'package.path' must be a string");
  lua_pushvalue(L, lua_upvalueindex(2));
  lua_pushvalue(L, 1);
  lua_pushvalue(L, -3);
  lua_call(L, 2, 2);
  if (lua_isnil(L, -2)) return 1;  // the message of the files tried
  lua_pop(L, 1);
  const char* filename = lua_tostring(L, -1);
  if (luaL_loadfilex(L, filename, "t") != LUA_OK) {
    explain_text_only(L);  // the file is named by the message below
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, filename,
                      lua_tostring(L, -1));
  }
  lua_insert(L, -2);  // the loader, then the file name
  return 2;
}

void wrap_global(lua_State* L, const char* name, lua_CFunction wrapper) {
  lua_getglobal(L, name);
  lua_pushcclosure(L, wrapper, 1);
  lua_setglobal(L, name);
}

}  // namespace

void install_text_only_loaders(lua_State* L) {
  wrap_global(L, "load", text_loader<3>);
  wrap_global(L, "loadfile", text_loader<2>);
  lua_pushcfunction(L, text_dofile);
  lua_setglobal(L, "dofile");
  const int top = lua_gettop(L);
  if (lua_getglobal(L, "package") == LUA_TTABLE &&
      lua_getfield(L, -1, "searchers") == LUA_TTABLE) {
    lua_pushvalue(L, -2);                   // package
    lua_getfield(L, -3, "searchpath");      // the original package.searchpath
    lua_pushcclosure(L, text_searcher, 2);
    lua_rawseti(L, -2, 2);
  }
  lua_settop(L, top);
}

void explain_text_only(lua_State* L, const char* file) {
  const char* message = lua_tostring(L, -1);
  if (message == nullptr || std::strcmp(message, lua_refusal) != 0) return;
  if (file != nullptr)
    lua_pushfstring(L, "%s: %s", file, our_refusal);
  else
    lua_pushstring(L, our_refusal);
  lua_remove(L, -2);
}

}  // namespace rigidlab::lua
