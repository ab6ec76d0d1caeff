// The values a lesson shows and checks: how ctx:show and ctx:expect write a value, and how
// ctx:expect compares what a lesson computed with what the document says (API.md "Lessons and
// checks"). Lua-side only: reads values, never changes them, runs no metamethod.
#pragma once

#include <lua.hpp>

#include <string>

namespace rigidlab::lua {

// How far a number may be from the document's: it passes when |got − want| <=
// max(absolute, relative · max(1, |want|)), or when got == want (so ±inf equal themselves).
struct Tolerance {
  double absolute = 0.0;
  double relative = 1e-9;
  std::string reason;  // why a teacher chose it, printed with the check ("" for the default)
};

// "rel 1e-09", "abs 1e-12", "rel 0.001, abs 1e-06", "exact".
std::string describe_tolerance(const Tolerance& tolerance);

// Compares `got` with `want` (stack indices) by the rules of ctx:expect: numbers within the
// tolerance; vec3, mat3 and quat component-wise; strings, booleans and nil exactly; tables
// deeply, every key of both (array and hash part, read raw), their values by these same
// rules; any other value only equal to itself. Returns "" when they agree, else the reason,
// naming the first difference in a fixed order (list entries first, then other keys sorted):
// "off by 0.5", "component y off by 0.5", "key a: off by 1", "key pos.y: off by 2",
// "key x: missing (want 7)", "strings differ at character 3", "got a string, want a number".
// Cyclic tables are compared as far as they unfold; nesting deeper than 64 levels fails.
std::string compare_values(lua_State* L, int got, int want, const Tolerance& tolerance);

// How a lesson writes a value: numbers with 10 significant digits (−0 as 0, so a rounding sign
// does not distract), vec3 (x, y, z), quat quat(w, x, y, z), mat3 ((..), (..), (..)) or, with
// a non-empty `indent`, on three rows each starting with a newline and `indent`; tables as
// {1, 2, x = 5, name = "a"} (list entries, then the other keys sorted; nested tables too, up
// to a depth of 3 and 16 entries each); a string as itself, or quoted (with escapes for
// control characters) when `quote` is set or inside a table; anything else by tostring (its
// __tostring runs).
std::string format_value(lua_State* L, int index, const std::string& indent, bool quote = false);

// The type of the value at `index` as a reason names it: "a number", "an integer", "nil".
std::string a_type_name(lua_State* L, int index);

// A lesson number: 10 significant digits, −0 as 0.
std::string lesson_number(double x);

}  // namespace rigidlab::lua
