// rigidlab loads Lua source only, never precompiled (binary) chunks: Lua does not verify
// bytecode, and a corrupted or hostile binary chunk can crash the process (a mutated
// string.dump given to load(s, nil, "b") segfaults). open_all installs text-only versions of
// load, loadfile, dofile and require's Lua searcher (package.searchers[2], which -l uses too);
// scripts and lessons are loaded with mode "t" by the CLI.
#pragma once

#include <lua.hpp>

namespace rigidlab::lua {

// Replaces load, loadfile, dofile and package.searchers[2] in the globals of L (after
// luaL_openlibs). load and loadfile take mode "t" or no mode; "b" and "bt" are refused.
void install_text_only_loaders(lua_State* L);

// Rewrites Lua's "attempt to load a binary chunk (mode is 't')" in the message on top of the
// stack to say why, and which file when `file` is given (Lua's message names none):
// "FILE: attempt to load a binary chunk (rigidlab loads text only)".
void explain_text_only(lua_State* L, const char* file = nullptr);

}  // namespace rigidlab::lua
