// The entry points of the bindings for the CLI and the tests.
#pragma once

#include <lua.hpp>

namespace rigidlab::lua {

// lua_CFunction for luaL_requiref: builds and returns the table of every rigidlab name.
int open_library(lua_State* L);

// Opens the standard libraries and rigidlab in a fresh state: `require("rigidlab")` returns
// the table, and every name in it is also a global.
void open_all(lua_State* L);

// A message handler for lua_pcall, as lua.c's msghandler: the message with the stack
// traceback appended; an error object that is not a string becomes its __tostring, else
// "(error object is a table value)".
int traceback_handler(lua_State* L);

}  // namespace rigidlab::lua
