// Tab completion in the REPL: global names and Lua keywords (`ine<Tab>` → `inertia`), fields
// of tables (`inertia.so<Tab>` → `inertia.solid_box`) and methods of rigidlab values
// (`v:cr<Tab>` → `v:cross` for a vec3 v: the keys of the global table named by the value's
// type). Inside a string literal Tab completes file names (`dofile("less<Tab>`).
// Nothing runs while completing: tables are read raw, no __index function is called.
#pragma once

#include <lua.hpp>

namespace rigidlab::cli {

// Makes libedit's Tab complete from the globals of L. libedit's completion callback receives
// no user data, so L is kept in a file-level variable until the process ends.
void install_completion(lua_State* L);

}  // namespace rigidlab::cli
