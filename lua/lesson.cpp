// lesson{...} and the ctx of a lesson run: ctx:show / expect / expect_range / table / say /
// plot. See lua/lesson.hpp and API.md "Lessons and checks". A failed expectation is recorded,
// not raised: a lesson shows every number, right or wrong, and the checker counts the failures.
#include "lua/lesson.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "lua/binding.hpp"
#include "lua/modules.hpp"
#include "lua/output_file.hpp"
#include "lua/plot.hpp"
#include "lua/render.hpp"
#include "lua/text_layout.hpp"
#include "present/file.hpp"
#include "present/svg_chart.hpp"
#include "present/text_chart.hpp"

namespace rigidlab::lua {
namespace {

const char lesson_context_key = 0;

// The ctx userdata holds only a pointer to the runner's LessonContext, behind a tag (see
// Tagged in lua/binding.hpp): nothing else can pass for a ctx, and __gc only clears the
// pointer, so a ctx finalised once, twice or used from a finaliser frees nothing.
using ContextBox = LessonContext*;

void write(LessonContext& context, const std::string& text) {
  if (context.output != nullptr) context.output->write(text);
}

LessonContext& check_context(lua_State* L, int arg) {
  ContextBox* box = test_tagged<ContextBox>(L, arg, lesson_context_tag);
  if (box == nullptr) type_error(L, arg, "lesson context");
  if (*box == nullptr)
    arg_error(L, arg, "the lesson context was garbage-collected (it is used from a finaliser)");
  if ((*box)->ended)
    arg_error(L, arg, "the lesson has ended: its ctx can no longer show or check anything");
  return **box;
}

// luaL_checkstring and luaL_checkany name the function as Lua saw it ('show'); these name it
// as rigidlab documents it ('ctx:show').
const char* check_text(lua_State* L, int arg) {
  if (!lua_isstring(L, arg)) type_error(L, arg, "string");
  return lua_tostring(L, arg);
}

void check_value(lua_State* L, int arg) {
  if (lua_isnone(L, arg)) arg_error(L, arg, "value expected");
}

// `prefix` + `value` on as many lines as the width needs: one line when it fits, else broken
// after the ", " separators of the value, continuation lines lined up under its first entry. A
// matrix breaks between its rows first, the rows lined up under the first one (one column in
// from the outer parenthesis).
std::string fit_value(const std::string& prefix, const std::string& value, size_t width) {
  if (display_width(prefix) + display_width(value) <= width) return prefix + value;
  const bool matrix = value.rfind("((", 0) == 0;
  const std::string row_indent(display_width(prefix) + (matrix ? 1 : 0), ' ');
  // entries line up under the first one, past "((", "(", "{" or "quat("
  const size_t first_entry = value.find_first_not_of("({abcdefghijklmnopqrstuvwxyz");
  const std::string entry_indent(
      display_width(prefix) + (first_entry == std::string::npos ? 0 : first_entry), ' ');
  std::vector<std::string> pieces;  // each keeps its "," (a matrix row its "),")
  for (size_t start = 0;;) {
    const size_t at = value.find(", ", start);
    if (at == std::string::npos) {
      pieces.push_back(value.substr(start));
      break;
    }
    pieces.push_back(value.substr(start, at + 1 - start));
    start = at + 2;
  }
  std::string text = prefix + pieces[0], line = text;
  for (size_t i = 1; i < pieces.size(); ++i) {
    const bool new_row = matrix && pieces[i - 1].size() >= 2 &&
                         pieces[i - 1].compare(pieces[i - 1].size() - 2, 2, "),") == 0;
    if (new_row || display_width(line) + 1 + display_width(pieces[i]) > width) {
      line = (new_row ? row_indent : entry_indent) + pieces[i];
      text += "\n" + line;
    } else {
      line += " " + pieces[i];
      text += " " + pieces[i];
    }
  }
  return text;
}

// ---- raw reading of lesson tables ----------------------------------------------------------

// Raw field `name` of the table at `table`, pushed; returns its type.
int raw_field(lua_State* L, int table, const char* name) {
  lua_pushstring(L, name);
  return lua_rawget(L, table);
}

// The first key of the table at `table` that is not in `allowed` (nullptr-terminated), as a
// message; "" when there is none.
std::string unknown_field(lua_State* L, int table, const char* const* allowed) {
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    lua_pop(L, 1);
    bool known = false;
    for (const char* const* a = allowed; *a && !known; ++a)
      known = lua_type(L, -1) == LUA_TSTRING && std::strcmp(*a, lua_tostring(L, -1)) == 0;
    if (known) continue;
    std::string message = std::string("unknown field '") + push_key_name(L, -1) + "' (fields are: ";
    for (const char* const* a = allowed; *a; ++a)
      message += (a == allowed ? "" : ", ") + std::string(*a);
    lua_pop(L, 2);
    return message + ")";
  }
  return "";
}

// ---- tolerances ------------------------------------------------------------------------------

// Reads {abs =, rel =, reason =} at `index` raw (no metamethod runs) into `tolerance`: a
// field left out is 0 (the reason ""). False with the reason in `error` for anything else.
bool read_tolerance_table(lua_State* L, int index, Tolerance& tolerance, std::string& error) {
  index = lua_absindex(L, index);
  tolerance = Tolerance{0.0, 0.0, ""};
  static const char* const allowed[] = {"abs", "rel", "reason", nullptr};
  error = unknown_field(L, index, allowed);
  if (!error.empty()) return false;
  for (const char* name : {"abs", "rel"}) {
    lua_pushstring(L, name);
    const int type = lua_rawget(L, index);
    const double x = lua_tonumber(L, -1);
    const bool good = type == LUA_TNIL || (type == LUA_TNUMBER && x >= 0.0 && std::isfinite(x));
    if (!good)
      error = std::string("field '") + name + "' must be a finite number >= 0, got " +
              (type == LUA_TNUMBER ? format_number(x) : value_type_name(L, -1));
    lua_pop(L, 1);
    if (!good) return false;
    (name[0] == 'a' ? tolerance.absolute : tolerance.relative) = x;
  }
  lua_pushliteral(L, "reason");
  const int type = lua_rawget(L, index);
  if (type == LUA_TSTRING)
    tolerance.reason = lua_tostring(L, -1);
  else if (type != LUA_TNIL)
    error = std::string("field 'reason' must be a string, got ") + value_type_name(L, -1);
  lua_pop(L, 1);
  return error.empty();
}

// The tolerance argument of ctx:expect: a number is relative to max(1, |want|); a table
// {abs =, rel =, reason =} passes when the difference is within either bound; none: the
// lesson's.
Tolerance check_tolerance(lua_State* L, int arg, const LessonContext& context) {
  if (lua_isnoneornil(L, arg)) return context.tolerance;
  if (lua_type(L, arg) == LUA_TNUMBER)
    return Tolerance{0.0, check_nonnegative(L, arg, "tolerance"), ""};
  if (lua_type(L, arg) != LUA_TTABLE) type_error(L, arg, "number or {abs =, rel =, reason =}");
  {
    Tolerance tolerance;
    std::string error;
    if (read_tolerance_table(L, arg, tolerance, error)) return tolerance;
    lua_pushlstring(L, error.data(), error.size());
  }  // the C++ strings are freed before the error jumps past this frame
  arg_error(L, arg, "%s", lua_tostring(L, -1));
}

// ---- checks ----------------------------------------------------------------------------------

// Records a check and writes it: "  ✓ label: got X, want Y" on one line when it fits, else
// the label (and the detail) on a line, got and want lined up below it. `problem` is "" when
// the check passed; `note` (the tolerance and its reason) is shown on a failure, and on a
// pass when the tolerance has a reason.
bool report_check(lua_State* L, LessonContext& context, const std::string& label,
                  const std::string& got, const std::string& want, const std::string& problem,
                  const std::string& note) {
  (void)L;
  const bool ok = problem.empty();
  const std::string mark = ok ? "  ✓ " : "  ✗ ";
  std::string detail;
  // A reason that only repeats the values ("got false, want true" of two booleans) is left
  // out, and the tolerance with it: it says nothing about such values.
  const bool repeats_values = problem == "got " + got + ", want " + want;
  if (!ok && !repeats_values)
    detail = " (" + problem + (note.empty() ? "" : "; " + note) + ")";
  else if (!note.empty())
    detail = " (" + note + ")";
  const std::string one_line = label + ": got " + got + ", want " + want + detail;
  if (ok) {
    ++context.passed;
  } else {
    ++context.failed;
    context.failures.push_back(one_line);
  }
  if (display_width(mark + one_line) <= static_cast<size_t>(context.width)) {
    write(context, mark + one_line + "\n");
  } else {  // label, then got and want on lines of their own, aligned
    write(context, fit_words_after(mark, label + detail, context.width) +
                       fit_value("      got  ", got, context.width) + "\n" +
                       fit_value("      want ", want, context.width) + "\n");
  }
  return ok;
}

// What a check says about its tolerance: on a failure by a number ("off by"), the tolerance;
// the reason of a tolerance given to this check, on a pass too ("tolerance rel 0.001: the
// document gives 4 digits"). A lesson-wide tolerance's reason is in the lesson's heading.
std::string tolerance_note(const Tolerance& tolerance, bool given, const std::string& problem) {
  const bool numeric = problem.find("off by") != std::string::npos;
  const bool has_reason = given && !tolerance.reason.empty();
  if (!numeric && !(problem.empty() && has_reason)) return "";
  const std::string note = "tolerance " + describe_tolerance(tolerance);
  return has_reason ? note + ": " + tolerance.reason : note;
}

// ctx:expect(label, got, want [, tol]) -> true when got agrees with want
int context_expect(lua_State* L) {
  LessonContext& context = check_context(L, 1);
  const char* label = check_text(L, 2);  // no C++ string before the last argument check
  check_value(L, 3);
  check_value(L, 4);
  check_no_extra_args(L, 5);
  const Tolerance tolerance = check_tolerance(L, 5, context);
  const std::string problem = compare_values(L, 3, 4, tolerance);
  const bool ok =
      report_check(L, context, label, format_value(L, 3, "", true), format_value(L, 4, "", true),
                   problem, tolerance_note(tolerance, !lua_isnoneornil(L, 5), problem));
  lua_pushboolean(L, ok);
  return 1;
}

// A bound of ctx:expect_range: a number (not nan) or nil.
bool check_bound(lua_State* L, int arg, double& bound) {
  if (lua_isnoneornil(L, arg)) return false;
  if (lua_type(L, arg) != LUA_TNUMBER) type_error(L, arg, "number or nil");
  bound = lua_tonumber(L, arg);
  if (std::isnan(bound)) arg_error(L, arg, "a bound must be a number, got nan");
  return true;
}

// ctx:expect_range(label, got, low, high) -> true when low <= got <= high (a nil bound is
// no bound)
int context_expect_range(lua_State* L) {
  LessonContext& context = check_context(L, 1);
  const char* label = check_text(L, 2);
  check_value(L, 3);
  check_no_extra_args(L, 5);
  double low = 0.0, high = 0.0;
  const bool has_low = check_bound(L, 4, low), has_high = check_bound(L, 5, high);
  if (!has_low && !has_high) arg_error(L, 4, "a bound expected: low and high are both nil");
  if (has_low && has_high && !(low <= high))
    arg_error(L, 5, "high must be >= low, got low %s and high %s", lesson_number(low).c_str(),
              lesson_number(high).c_str());
  std::string want;
  if (has_low && has_high)
    want = "in [" + lesson_number(low) + ", " + lesson_number(high) + "]";
  else if (has_low)
    want = "≥ " + lesson_number(low);
  else
    want = "≤ " + lesson_number(high);
  std::string problem;
  if (lua_type(L, 3) != LUA_TNUMBER) {
    problem = "got " + a_type_name(L, 3) + ", want a number";
  } else {
    const double got = lua_tonumber(L, 3);
    if (std::isnan(got))
      problem = "got nan: nan is in no range";
    else if (has_low && got < low)
      problem = "below the low bound by " + format_number(low - got, 4);
    else if (has_high && got > high)
      problem = "above the high bound by " + format_number(got - high, 4);
  }
  const bool ok = report_check(L, context, label, format_value(L, 3, "", true), want, problem, "");
  lua_pushboolean(L, ok);
  return 1;
}

// ---- showing ---------------------------------------------------------------------------------

// ctx:show(label, value)
int context_show(lua_State* L) {
  LessonContext& context = check_context(L, 1);
  const char* label = check_text(L, 2);
  check_value(L, 3);
  check_no_extra_args(L, 3);
  const std::string prefix = std::string("  ") + label + " =";
  if (test_mat3(L, 3) != nullptr) {  // on its rows, under the label
    std::string text = prefix;
    const std::string rows = format_value(L, 3, "    ");  // "\n    (..)" three times
    for (size_t start = rows.find("\n    ("); start != std::string::npos;) {
      const size_t end = rows.find("\n", start + 1);
      const size_t length = end == std::string::npos ? end : end - start - 5;
      const std::string row = rows.substr(start + 5, length);  // past "\n    "
      text += "\n" + fit_value("    ", row, context.width);
      start = end;
    }
    write(context, text + "\n");
  } else {
    write(context, fit_value(prefix + " ", format_value(L, 3, ""), context.width) + "\n");
  }
  return 0;
}

// ctx:table(columns, rows): an aligned table; columns a list of headings, rows a list of lists
// of numbers or strings.
int context_table(lua_State* L) {
  LessonContext& context = check_context(L, 1);
  if (lua_type(L, 2) != LUA_TTABLE) type_error(L, 2, "table");
  if (lua_type(L, 3) != LUA_TTABLE) type_error(L, 3, "table");
  check_no_extra_args(L, 3);
  const int columns = static_cast<int>(lua_rawlen(L, 2));
  if (columns < 1) arg_error(L, 2, "at least one column heading expected");
  const lua_Integer rows = static_cast<lua_Integer>(lua_rawlen(L, 3));
  for (lua_Integer i = 1; i <= rows; ++i) {  // checked before any C++ string is made
    if (lua_rawgeti(L, 3, i) != LUA_TTABLE)
      arg_error(L, 3, "row %d must be a table, got %s", (int)i, value_type_name(L, -1));
    lua_pop(L, 1);
  }
  std::vector<std::vector<std::string>> cells(1);
  for (int j = 1; j <= columns; ++j) {
    lua_rawgeti(L, 2, j);
    cells[0].push_back(luaL_tolstring(L, -1, nullptr));
    lua_pop(L, 2);
  }
  for (lua_Integer i = 1; i <= rows; ++i) {
    lua_rawgeti(L, 3, i);
    std::vector<std::string> row;
    for (int j = 1; j <= columns; ++j) {
      lua_rawgeti(L, -1, j);
      row.push_back(lua_isnil(L, -1) ? "" : format_value(L, lua_gettop(L), ""));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    cells.push_back(row);
  }
  // Widths in code points, so headings like "n²" align.
  std::vector<size_t> width(columns, 0);
  for (const auto& row : cells)
    for (int j = 0; j < columns; ++j) width[j] = std::max(width[j], display_width(row[j]));
  std::string text;
  for (size_t i = 0; i < cells.size(); ++i) {
    text += "   ";
    for (int j = 0; j < columns; ++j)
      text += " " + std::string(width[j] - display_width(cells[i][j]), ' ') + cells[i][j];
    text += "\n";
    if (i == 0) {
      text += "   ";
      for (int j = 0; j < columns; ++j) text += " " + std::string(width[j], '-');
      text += "\n";
    }
  }
  write(context, text);
  return 0;
}

// ctx:say(text): a line of explanation printed between values.
int context_say(lua_State* L) {
  LessonContext& context = check_context(L, 1);
  const char* text = check_text(L, 2);
  check_no_extra_args(L, 2);
  std::string out;
  for (const char* line = text;;) {  // each line of the text wrapped on its own
    const char* end = std::strchr(line, '\n');
    const std::string part = end ? std::string(line, end) : std::string(line);
    out += part.empty() ? "\n" : fit_words(part, "  ", context.width);
    if (end == nullptr) break;
    line = end + 1;
  }
  write(context, out);
  return 0;
}

// ctx:plot{series..., title =, xlabel =, ylabel =, width =, height =, svg =}: plot.lines laid
// out in the lesson (its chart model and checks: lua/plot.hpp).
int context_plot(lua_State* L) {
  LessonContext& context = check_context(L, 1);
  check_no_extra_args(L, 2);
  const PlotRequest request = check_plot_request(L, 2);
  lua_pushliteral(L, "width");
  const bool width_given = lua_rawget(L, 2) != LUA_TNIL;
  lua_pop(L, 1);
  if (!request.svg.empty())
    write_or_raise(L, 2, "svg",
                   [&] { present::write_file(request.svg, present::svg_chart(request.chart)); });
  if (context.output != nullptr)
    context.output->plot(request.chart,
                         PlotSize{width_given ? request.width : 0, request.height, context.width});
  return 0;
}

int context_gc(lua_State* L) {
  if (ContextBox* box = test_tagged<ContextBox>(L, 1, lesson_context_tag)) *box = nullptr;
  return 0;
}

int context_tostring(lua_State* L) {
  ContextBox* box = test_tagged<ContextBox>(L, 1, lesson_context_tag);
  if (box == nullptr) type_error(L, 1, "lesson context");
  if (*box == nullptr)
    lua_pushliteral(L, "lesson context (garbage-collected)");
  else
    lua_pushfstring(L, "lesson context (%d passed, %d failed%s)", (*box)->passed, (*box)->failed,
                    (*box)->ended ? "; its lesson has ended" : "");
  return 1;
}

// ---- lesson{} --------------------------------------------------------------------------------

// Field `name` of the table at `table` into `out`: a string (non-empty when `non_empty`).
bool read_text(lua_State* L, int table, const char* name, bool required, bool non_empty,
               std::string& out, std::string& error) {
  const int type = raw_field(L, table, name);
  if (type == LUA_TSTRING && (!non_empty || lua_rawlen(L, -1) > 0)) {
    size_t length = 0;
    const char* text = lua_tolstring(L, -1, &length);
    out.assign(text, length);
  } else if (type != LUA_TNIL || required) {
    error = std::string("field '") + name + "' must be a " + (non_empty ? "non-empty " : "") +
            "string, got " + value_type_name(L, -1);
  }
  lua_pop(L, 1);
  return error.empty();
}

// Step `number`, the table at the top of the stack, into `step`; its run function (or false)
// becomes runs[number] of the table at `runs`.
bool read_step(lua_State* L, int number, int runs, LessonStep& step, std::string& error) {
  const int table = lua_gettop(L);
  const std::string where = "steps[" + std::to_string(number) + "]";
  if (lua_type(L, table) != LUA_TTABLE) {
    error = where + " must be a table, got " + value_type_name(L, table);
    return false;
  }
  static const char* const allowed[] = {"title", "text", "formula", "run", nullptr};
  error = unknown_field(L, table, allowed);
  if (error.empty()) read_text(L, table, "title", true, false, step.title, error);
  if (error.empty()) read_text(L, table, "text", true, false, step.text, error);
  if (error.empty()) read_text(L, table, "formula", false, false, step.formula, error);
  if (!error.empty()) {
    error = where + ": " + error;
    return false;
  }
  const int type = raw_field(L, table, "run");
  if (type != LUA_TFUNCTION && type != LUA_TNIL) {
    error = where + ": field 'run' must be a function, got " + value_type_name(L, -1);
    lua_pop(L, 1);
    return false;
  }
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    lua_pushboolean(L, false);
  }
  lua_rawseti(L, runs, number);
  return true;
}

// The steps list of the lesson at `lesson` into `spec`, their run functions into `runs`.
bool read_steps(lua_State* L, int lesson, int runs, LessonSpec& spec, std::string& error) {
  const char* const message = "field 'steps' must be a non-empty list of steps";
  if (raw_field(L, lesson, "steps") != LUA_TTABLE || lua_rawlen(L, -1) == 0) {
    error = message;
    lua_pop(L, 1);
    return false;
  }
  const int steps = lua_gettop(L);
  const lua_Integer count = static_cast<lua_Integer>(lua_rawlen(L, steps));
  lua_Integer keys = 0;  // a list has exactly the keys 1..count: no holes, no named field
  lua_pushnil(L);
  while (lua_next(L, steps) != 0) {
    lua_Integer key = 0;
    lua_pop(L, 1);
    if (!to_integer(L, -1, key) || key < 1 || key > count) {
      error = std::string(message) + ": unexpected key '" + push_key_name(L, -1) + "'";
      lua_settop(L, steps - 1);
      return false;
    }
    ++keys;
  }
  for (lua_Integer i = 1; i <= count && error.empty(); ++i) {
    lua_rawgeti(L, steps, i);
    spec.steps.emplace_back();
    read_step(L, static_cast<int>(i), runs, spec.steps.back(), error);
    lua_settop(L, steps);
  }
  lua_pop(L, 1);
  return error.empty() && keys == count;
}

// lesson{tolerance = {rel =, abs =, reason =}}: a lesson-wide tolerance must say why.
bool read_lesson_tolerance(lua_State* L, int lesson, LessonSpec& spec, std::string& error) {
  const int type = raw_field(L, lesson, "tolerance");
  if (type == LUA_TTABLE) {
    if (read_tolerance_table(L, -1, spec.tolerance, error) && spec.tolerance.reason.empty())
      error =
          "needs a reason, printed with the lesson: tolerance = {rel = 1e-6, reason = "
          "\"the document gives 7 digits\"}";
    spec.has_tolerance = true;
  } else if (type != LUA_TNIL) {
    error = std::string("must be a table {rel =, abs =, reason =}, got ") + value_type_name(L, -1);
  }
  lua_pop(L, 1);
  if (!error.empty()) error = "field 'tolerance': " + error;
  return error.empty();
}

// lesson{id =, title =, source =, steps = {...}, tolerance =} -> the same table, validated.
int lesson_new(lua_State* L) {
  if (lua_type(L, 1) != LUA_TTABLE) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  {
    LessonSpec spec;
    std::string error;
    if (read_lesson(L, 1, spec, error)) {
      lua_settop(L, 1);
      return 1;
    }
    lua_pushlstring(L, error.data(), error.size());
  }  // the C++ strings are freed before the error jumps past this frame
  arg_error(L, 1, "%s", lua_tostring(L, -1));
}

// A std::bad_alloc from the strings a method builds (while a lesson runs, C++ memory is charged
// to its memory limit) becomes Lua's memory error instead of crossing Lua's frames.
template <lua_CFunction F>
int guarded(lua_State* L) {
  return protect(L, [L] { return F(L); });
}

const Entry context_methods[] = {
    {"show", guarded<context_show>, "ctx:show", "ctx:show(label, value)",
     "Prints a labelled value: a number, vec3, mat3, quat, string or table."},
    {"expect", guarded<context_expect>, "ctx:expect", "ctx:expect(label, got, want [, tol]) -> ok",
     "Checks got against the document's value and prints got, want and ✓ or ✗ (with the\n"
     "reason: the first key or component that differs). Numbers agree within tol: relative to\n"
     "max(1, |want|) (default 1e-9, or the lesson's tolerance), or {abs =, rel =, reason =}\n"
     "(the reason is printed); ±inf equal themselves, nan nothing. vec3, mat3 and quat are\n"
     "compared component-wise, strings, booleans and nil exactly, tables deeply (every key).\n"
     "A failure is recorded (the check fails), not raised."},
    {"expect_range", guarded<context_expect_range>, "ctx:expect_range",
     "ctx:expect_range(label, got, low, high) -> ok",
     "Checks low <= got <= high and prints ✓ or ✗; either bound may be nil (no bound)."},
    {"plot", guarded<context_plot>, "ctx:plot",
     "ctx:plot{ {x = xs, y = ys, label =}, ..., title =, xlabel =, ylabel =, width =, height = }",
     "A line chart in the lesson, as plot.lines draws it, indented like the lesson's tables and\n"
     "as wide as the lesson (unless width is given). An exported transcript (rigidlab lesson ID\n"
     "--export FILE.md) has it as an SVG file beside the Markdown."},
    {"table", guarded<context_table>, "ctx:table", "ctx:table(columns, rows)",
     "Prints an aligned table: columns a list of headings, rows a list of lists."},
    {"say", guarded<context_say>, "ctx:say", "ctx:say(text)", "Prints a line of explanation."},
    {"motion", guarded<context_motion>, "ctx:motion",
     "ctx:motion(w [, {seconds =, frames =, dt =, show =, camera =, height =, ascii =}])",
     "Steps the world (or articulation) w for seconds (default 2) in steps of dt (default\n"
     "1/60 s) and shows frames (default 4) evenly spaced over that time, w's state now the\n"
     "first, as a film strip fitted to the lesson's width: one camera frames the whole motion;\n"
     "show and camera as for w:render. No colour; ASCII when the terminal is not UTF-8 or\n"
     "ascii = true. In check mode it only steps (the state after it is the same). In a\n"
     "terminal the lesson's prompt then offers v: the same motion live (w:view)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry context_metamethods[] = {
    {"__gc", context_gc, "ctx.__gc", "", ""},
    {"__tostring", guarded<context_tostring>, "ctx.__tostring", "tostring(ctx)", ""},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

// The ctx of lesson_context(): one for the process, never freed, so that no ctx made by it
// can outlive it; it writes to stdout.
class StdoutOutput : public LessonOutput {
 public:
  void write(const std::string& lines) override {
    std::fwrite(lines.data(), 1, lines.size(), stdout);
    std::fflush(stdout);
  }
};

// lesson_context() -> ctx: a ctx outside any lesson, for trying a step's code in the REPL.
int lesson_context(lua_State* L) {
  check_no_extra_args(L, 0);
  static StdoutOutput output;
  static LessonContext* const context = new LessonContext{};  // never freed (see above)
  context->output = &output;
  push_lesson_context(L, *context);
  return 1;
}

const Entry functions[] = {
    {"lesson_context", guarded<lesson_context>, "lesson_context", "lesson_context() -> ctx",
     "A lesson's ctx outside any lesson, printing what it shows and checks: to try the code\n"
     "of a step (the lesson's key c shows it) in the REPL, run(lesson_context()).\n"
     "tostring(ctx) counts its checks."},
    {"lesson", guarded<lesson_new>, "lesson",
     "lesson{id =, title =, source =, steps = {...} [, tolerance =]} -> lesson",
     "Declares a lesson (a file in lessons/ returns one). Each step is\n"
     "{title =, text =, formula =, run = function(ctx) ... end}: text explains in words,\n"
     "formula (optional) shows the document's formula, run computes and calls ctx:show,\n"
     "ctx:expect, ctx:expect_range, ctx:table, ctx:say. tolerance = {rel =, abs =, reason =}\n"
     "sets the default of every ctx:expect, with the reason shown. `rigidlab lesson ID`\n"
     "steps through it, `rigidlab check` runs every expectation."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

std::string plot_text(const present::Chart& chart, const PlotSize& size, present::TextStyle style) {
  const std::string indent = "    ";
  present::TextChartOptions options;
  options.height = size.height;
  options.style = style;
  options.width = size.width > 0 ? size.width : std::max(10, size.columns - 16);
  std::string text = present::text_chart(chart, options);
  if (size.width == 0) {  // widen or narrow the plot area to the lesson's columns
    size_t widest = 0;
    for (size_t start = 0; start <= text.size();) {
      const size_t end = std::min(text.find('\n', start), text.size());
      widest = std::max(widest, display_width(text.substr(start, end - start)));
      start = end + 1;
    }
    const int spare = size.columns - static_cast<int>(indent.size() + widest);
    if (spare != 0 && options.width + spare >= 10) {
      options.width += spare;
      text = present::text_chart(chart, options);
    }
  }
  std::string out = "\n";  // a blank line above and below: a chart is a figure of its own
  for (size_t start = 0; start <= text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    out += indent + text.substr(start, end - start) + "\n";
    start = end + 1;
  }
  return out + "\n";
}

void LessonOutput::plot(const present::Chart& chart, const PlotSize& size) {
  write(plot_text(chart, size, present::terminal_style(STDOUT_FILENO)));
}

void push_lesson_context(lua_State* L, LessonContext& context) {
  void* memory = lua_newuserdatauv(L, sizeof(Tagged<ContextBox>), 0);
  new (memory) Tagged<ContextBox>{lesson_context_tag, &context};
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &lesson_context_key) != LUA_TTABLE) {
    lua_pop(L, 1);
    new_metatable(L, "lesson context", &lesson_context_key);
    register_entries(L, -1, context_metamethods);
    lua_newtable(L);
    register_entries(L, -1, context_methods);
    lua_setfield(L, -2, "__index");
  }
  lua_setmetatable(L, -2);
}

LessonContext* test_lesson_context(lua_State* L, int index) {
  ContextBox* box = test_tagged<ContextBox>(L, index, lesson_context_tag);
  return box != nullptr ? *box : nullptr;
}

bool read_lesson(lua_State* L, int index, LessonSpec& spec, std::string& error) {
  index = lua_absindex(L, index);
  static const char* const allowed[] = {"id", "title", "source", "steps", "tolerance", nullptr};
  error = unknown_field(L, index, allowed);
  if (error.empty()) read_text(L, index, "id", true, true, spec.id, error);
  if (error.empty() &&
      spec.id.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") != std::string::npos)
    error = "field 'id' may hold only a-z, 0-9 and '-', got '" + spec.id + "'";
  if (error.empty()) read_text(L, index, "title", true, true, spec.title, error);
  if (error.empty()) read_text(L, index, "source", true, true, spec.source, error);
  if (error.empty()) read_lesson_tolerance(L, index, spec, error);
  if (!error.empty()) return false;
  lua_newtable(L);
  if (!read_steps(L, index, lua_gettop(L), spec, error)) {
    lua_pop(L, 1);
    return false;
  }
  return true;
}

void open_lesson(lua_State* L, int lib) { register_entries(L, lib, functions); }

}  // namespace rigidlab::lua
