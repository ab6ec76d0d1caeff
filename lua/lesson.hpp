// Lessons: the `lesson{...}` constructor that validates a lesson table, and the `ctx` object a
// step's run(ctx) receives, which shows values and checks them against the document's numbers.
// The CLI's lesson runner reads the lesson with read_lesson, creates one context per lesson
// run and reads its tally afterwards.
#pragma once

#include <lua.hpp>

#include <string>
#include <vector>

#include "lua/lesson_values.hpp"
#include "present/chart.hpp"
#include "present/style.hpp"

namespace rigidlab::lua {

// The size ctx:plot asks for: the plot area in character cells (`width` 0: fit the lesson's
// `columns`, less the axis labels and the indent).
struct PlotSize {
  int width = 0, height = 15;
  int columns = 80;
};

// Where a lesson's ctx writes: the terminal, a transcript being exported.
class LessonOutput {
 public:
  virtual ~LessonOutput() = default;
  // Lines as the lesson shows them, each ending in "\n".
  virtual void write(const std::string& lines) = 0;
  // A chart of ctx:plot. By default drawn as text (plot_text, in the terminal's style) and
  // written as lines; a transcript writes it as an SVG file. Must not throw.
  virtual void plot(const present::Chart& chart, const PlotSize& size);
};

// A chart as a lesson shows it in text: present/text_chart indented like the lesson's tables
// (4 columns) and, unless its width was asked for, as wide as fits in size.columns.
std::string plot_text(const present::Chart& chart, const PlotSize& size, present::TextStyle style);

// One run of a lesson: where its ctx writes and how its checks went. The runner owns it and
// keeps it alive as long as the Lua state (declared before the state): the ctx userdata only
// points to it. Once `ended` is set, or the ctx has been garbage-collected, every method of
// the ctx raises an error: a ctx kept past its lesson (in a table whose __gc uses it) checks
// nothing and writes nothing.
struct LessonContext {
  int passed = 0;
  int failed = 0;
  std::vector<std::string> failures;  // "label: got X, want Y (reason; tolerance ...)"
  LessonOutput* output = nullptr;     // nullptr: check mode, nothing is written
  int width = 80;                     // columns to fit the shown values and checks into
  Tolerance tolerance;                // the lesson's default (lesson{tolerance = ...})
  bool ended = false;
};

// Pushes a new ctx userdata for `context`.
void push_lesson_context(lua_State* L, LessonContext& context);
// The context of the ctx at `index` if it is a live ctx (not garbage-collected), else nullptr.
LessonContext* test_lesson_context(lua_State* L, int index);

// A lesson as lesson{} validated it.
struct LessonStep {
  std::string title, text, formula;
};
struct LessonSpec {
  std::string id, title, source;
  Tolerance tolerance;  // lesson{tolerance = {rel =, abs =, reason =}}, else the default
  bool has_tolerance = false;
  std::vector<LessonStep> steps;
};

// Reads the lesson table at `index` by the rules of lesson{} with raw reads only (no
// metamethod of the table, of its steps or of their fields runs), into `spec`, and pushes the
// list of the steps' run functions (false for a step without one). The runner then works from
// these copies, so nothing the lesson does to its table later changes what runs. On a table
// that is not a lesson, pushes nothing and returns false with the reason in `error`
// ("field 'id' must be a non-empty string, got nil", "steps[2]: unknown field 'txt' ...").
bool read_lesson(lua_State* L, int index, LessonSpec& spec, std::string& error);

}  // namespace rigidlab::lua
