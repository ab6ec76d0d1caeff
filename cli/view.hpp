// rigidlab view [LIMITS] FILE.lua [ARG ...]: runs the script (its arguments in `arg`, as for
// `rigidlab FILE.lua`), which must return a world or an articulation, and shows it live (w:view{}, art:view{}).
// LIMITS: --max-memory MB and --max-instructions N hold for the script and the view (the
// view's history of saved states counts against the memory limit); --timeout S bounds the
// script only, not the time spent watching.
#pragma once

#include <lua.hpp>

#include <string>
#include <vector>

namespace rigidlab::cli {

int view_command(const std::vector<std::string>& arguments);

// A lesson's key v: whether the step just shown drew a motion (ctx:motion), and its live view
// (w:view from the strip's first state), run like a step (Ctrl-C and errors come back as
// `error`, false).
bool has_lesson_motion(lua_State* L);
bool view_lesson_motion(lua_State* L, std::string& error);

}  // namespace rigidlab::cli
