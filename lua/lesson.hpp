// Lessons: the `lesson{...}` constructor that validates a lesson table, and the `ctx` object a
// step's run(ctx) receives, which shows values and checks them against the document's numbers.
// The CLI's lesson runner creates one context per lesson and reads the tally afterwards.
#pragma once

#include <lua.hpp>

#include <string>
#include <vector>

namespace rigidlab::lua {

// The outcome of the expectations recorded by one context.
struct LessonTally {
  int passed = 0;
  int failed = 0;
  std::vector<std::string> failures;  // "label: got X, want Y (tolerance ...)"
  bool quiet = false;                 // check mode: record, print nothing
  int width = 80;                     // columns to fit the shown values and checks into
};

// Pushes a new ctx userdata and returns its tally (valid while the userdata lives).
LessonTally& push_lesson_context(lua_State* L, bool quiet);
// The tally of the ctx at `index`, or nullptr if it is not a ctx.
LessonTally* test_lesson_context(lua_State* L, int index);

// Formats a value as a lesson shows it: numbers with 10 significant digits (−0 as 0, so a
// rounding sign does not distract), vec3 (x, y, z), quat quat(w, x, y, z), mat3 ((..), (..),
// (..)) or, with a non-empty `indent`, on three rows each starting with a newline and
// `indent`; a table of numbers as {a, b, c}; anything else by tostring.
std::string format_value(lua_State* L, int index, const std::string& indent);

}  // namespace rigidlab::lua
