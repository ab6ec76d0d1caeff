// The sandbox for scripts and lessons from untrusted sources (`rigidlab --sandbox FILE`, and
// `rigidlab check` for lessons outside the project's lessons/): no io, no os but clock, time,
// date and difftime, no package/require of C modules, no dofile/loadfile, no string.dump, no
// debug but traceback; and rigidlab's own file writers (plot.lines{svg =}, csv.write) refuse
// to write. Binary chunks are refused everywhere, not only here (lua/text_only.hpp).
#pragma once

#include <lua.hpp>

namespace rigidlab::lua {

// Applies the sandbox to a state opened with open_all (which made loading text only).
// Irreversible.
void apply_sandbox(lua_State* L);
// True in a sandboxed state: functions that touch the file system must refuse.
bool is_sandboxed(lua_State* L);

}  // namespace rigidlab::lua
