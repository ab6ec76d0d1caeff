// The limits' count hook (cli/limits.hpp) must survive what a script does to hooks. Lua has one
// hook per thread, and debug.sethook replaces it: `debug.sethook()` alone would switch
// --max-instructions, the time limit's checks and Ctrl-C off. So debug.sethook and
// debug.gethook are replaced by versions under which a script's hook runs beside the limits'
// one instead of replacing it: the original sethook does its work (checks its arguments,
// records the Lua function), the hook it installed is kept as the thread's script hook, and
// the limits' hook goes back in place, with the script's events added to its mask. The
// limits' hook then runs the script hook at the events it asked for, at exactly every
// `count` instructions for a count hook. debug.gethook reports the script hook, as if it were
// alone.
//
// A hook runs with hooks off (Lua 5.4's rule for hooks and finalizers), so a loop inside a
// script's hook function or a __gc is stopped only by the watchdog of a time limit, or by a
// second Ctrl-C (cli/interrupt.hpp).
#pragma once

#include <lua.hpp>

namespace rigidlab::cli {

// Instructions between two count events of the limits' hook, when no script hook asks for
// fewer.
constexpr int limits_hook_interval = 1000;

// Sets `hook` as the limits' hook of L (a count hook every limits_hook_interval instructions).
// Threads created afterwards inherit it.
void install_limits_hook(lua_State* L, lua_Hook hook);

// Replaces debug.sethook and debug.gethook in L's state as described above, once (the debug
// library must be open: nothing happens otherwise, and again at the next call). Never raises.
void guard_hooks(lua_State* L);

// For the limits' hook, at every event of thread L: runs the script hook of L when it asked
// for this event, and keeps the count of instructions to its next count event.
void run_script_hook(lua_State* L, lua_Debug* ar);

}  // namespace rigidlab::cli
