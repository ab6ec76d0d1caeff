// How the REPL shows the values of an expression (issue 16 item 6), as luaprompt and IPython
// do rather than lua.c's tostring: a table shows its fields, nested, on one line when it fits
// the terminal's width and indented otherwise —
//
//   > motion.simulate{method = "rk4", accel = function(t, x) return -x end, x0 = 1, v0 = 0,
//   >> dt = 0.1, steps = 100}
//   {t = {0.0, 0.1, 0.2, ... (98 more)}, v = {...}, x = {...}}
//
// The array part comes first in order, then the other keys sorted (numbers, then strings,
// then the rest). Limits keep any value short and quick: nesting depth, entries per table,
// characters per string and in all. No metamethod of a table runs except __tostring (the value
// then shows as that string, as print shows it; an error in it is shown, not raised): keys and
// values are read raw, so __index, __pairs and __len cannot loop; a table met again inside
// itself shows as <cycle>; a __name titles the table. The rigidlab types show as tostring
// does, a string at the top level as itself (w:render's frames), inside a table quoted.
#pragma once

#include <lua.hpp>

namespace rigidlab::cli {

// lua_CFunction: writes its arguments to stdout as above, tab separated, then a newline.
// Meant to run protected and limited (cli/run.hpp print_results): a __tostring may loop.
int pretty_print(lua_State* L);

}  // namespace rigidlab::cli
