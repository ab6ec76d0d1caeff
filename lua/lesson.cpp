// lesson{...} and ctx:show / ctx:expect / ctx:table. See lua/lesson.hpp and API.md "Lessons
// and checks". A failed expectation is recorded, not raised: a lesson shows every number,
// right or wrong, and the checker counts the failures.
#include "lua/lesson.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>

#include "lua/binding.hpp"
#include "lua/modules.hpp"
#include "lua/text_layout.hpp"

namespace rigidlab::lua {
namespace {

const char lesson_context_key = 0;

void write(const LessonTally& tally, const std::string& text) {
  if (tally.quiet) return;
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fflush(stdout);
}

LessonTally& check_context(lua_State* L, int arg) {
  LessonTally* tally = test_lesson_context(L, arg);
  if (tally == nullptr) type_error(L, arg, "lesson context");
  return *tally;
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

// The numbers of a value that ctx:expect can compare: a number, vec3, quat, mat3 or a table of
// numbers. Returns false for anything else.
bool components(lua_State* L, int index, std::vector<double>& out, std::string& kind) {
  out.clear();
  if (lua_type(L, index) == LUA_TNUMBER) {
    kind = "number";
    out.push_back(lua_tonumber(L, index));
  } else if (const Vec3* v = test_vec3(L, index)) {
    kind = "vec3";
    out.assign(v->data(), v->data() + 3);
  } else if (const Quat* q = test_quat(L, index)) {
    kind = "quat";
    out = {q->w(), q->x(), q->y(), q->z()};
  } else if (const Mat3* m = test_mat3(L, index)) {
    kind = "mat3";
    for (int k = 0; k < 9; ++k) out.push_back((*m)(k / 3, k % 3));
  } else if (lua_type(L, index) == LUA_TTABLE) {
    kind = "table";
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, index));
    for (lua_Integer i = 1; i <= n; ++i) {
      const bool is_number = lua_rawgeti(L, index, i) == LUA_TNUMBER;
      out.push_back(lua_tonumber(L, -1));
      lua_pop(L, 1);
      if (!is_number) return false;
    }
  } else {
    kind = value_type_name(L, index);
    return false;
  }
  return true;
}

// The tolerance argument: a number is relative to max(1, |want|); {abs =, rel =} passes when
// the difference is within either bound.
void read_tolerance(lua_State* L, int arg, double& absolute, double& relative) {
  absolute = 0.0;
  relative = 1e-9;
  if (lua_isnoneornil(L, arg)) return;
  if (lua_type(L, arg) == LUA_TNUMBER) {
    relative = check_nonnegative(L, arg, "tolerance");
    return;
  }
  if (lua_type(L, arg) != LUA_TTABLE) type_error(L, arg, "number or {abs =, rel =}");
  static const char* const fields[] = {"abs", "rel", nullptr};
  check_fields(L, arg, fields);
  absolute = field_finite(L, arg, "abs", 0.0, false);
  relative = field_finite(L, arg, "rel", 0.0, false);
  if (absolute < 0.0 || relative < 0.0) arg_error(L, arg, "tolerances must be >= 0");
}

std::string describe_tolerance(double absolute, double relative) {
  std::string text;
  if (relative > 0.0) text += "rel " + format_number(relative);
  if (absolute > 0.0) text += (text.empty() ? "abs " : ", abs ") + format_number(absolute);
  return text.empty() ? "exact" : text;
}

// ctx:show(label, value)
int context_show(lua_State* L) {
  LessonTally& tally = check_context(L, 1);
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
      text += "\n" + fit_value("    ", row, tally.width);
      start = end;
    }
    write(tally, text + "\n");
  } else
    write(tally, fit_value(prefix + " ", format_value(L, 3, ""), tally.width) + "\n");
  return 0;
}

// ctx:expect(label, got, want [, tol]) -> true when within tolerance
int context_expect(lua_State* L) {
  LessonTally& tally = check_context(L, 1);
  const char* label = check_text(L, 2);
  check_value(L, 3);
  check_value(L, 4);
  check_no_extra_args(L, 5);
  double absolute, relative;
  read_tolerance(L, 5, absolute, relative);
  std::vector<double> got, want;
  std::string got_kind, want_kind;
  const bool comparable = components(L, 3, got, got_kind) && components(L, 4, want, want_kind);
  std::string problem;
  if (!comparable || got_kind != want_kind || got.size() != want.size()) {
    problem = "got a " + got_kind + ", want a " + want_kind;
  } else {
    for (size_t i = 0; i < got.size() && problem.empty(); ++i) {
      const double difference = std::fabs(got[i] - want[i]);
      const double bound = std::max(absolute, relative * std::max(1.0, std::fabs(want[i])));
      if (!(difference <= bound))  // NaN fails
        problem = got.size() > 1 ? "component " + std::to_string(i + 1) + " off by " +
                                       format_number(difference)
                                 : "off by " + format_number(difference);
    }
  }
  const std::string got_text = format_value(L, 3, "");
  const std::string want_text = format_value(L, 4, "");
  const std::string mark = problem.empty() ? "  ✓ " : "  ✗ ";
  const std::string detail =
      problem.empty() ? "" : " (" + problem + "; tolerance " +
                                 describe_tolerance(absolute, relative) + ")";
  const std::string one_line =
      std::string(label) + ": got " + got_text + ", want " + want_text + detail;
  if (problem.empty())
    ++tally.passed;
  else
    ++tally.failed, tally.failures.push_back(one_line);
  if (display_width(mark + one_line) <= static_cast<size_t>(tally.width)) {
    write(tally, mark + one_line + "\n");
  } else {  // label, then got and want on lines of their own, aligned
    write(tally, fit_words_after(mark, label + detail, tally.width) +
                     fit_value("      got  ", got_text, tally.width) + "\n" +
                     fit_value("      want ", want_text, tally.width) + "\n");
  }
  lua_pushboolean(L, problem.empty());
  return 1;
}

// ctx:table(columns, rows): an aligned table; columns a list of headings, rows a list of lists
// of numbers or strings.
int context_table(lua_State* L) {
  LessonTally& tally = check_context(L, 1);
  if (lua_type(L, 2) != LUA_TTABLE) type_error(L, 2, "table");
  if (lua_type(L, 3) != LUA_TTABLE) type_error(L, 3, "table");
  check_no_extra_args(L, 3);
  const int columns = static_cast<int>(lua_rawlen(L, 2));
  if (columns < 1) arg_error(L, 2, "at least one column heading expected");
  std::vector<std::vector<std::string>> cells(1);
  for (int j = 1; j <= columns; ++j) {
    lua_rawgeti(L, 2, j);
    cells[0].push_back(luaL_tolstring(L, -1, nullptr));
    lua_pop(L, 2);
  }
  const lua_Integer rows = static_cast<lua_Integer>(lua_rawlen(L, 3));
  for (lua_Integer i = 1; i <= rows; ++i) {
    if (lua_rawgeti(L, 3, i) != LUA_TTABLE)
      arg_error(L, 3, "row %d must be a table, got %s", (int)i, value_type_name(L, -1));
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
  write(tally, text);
  return 0;
}

// ctx:say(text): a line of explanation printed between values.
int context_say(lua_State* L) {
  LessonTally& tally = check_context(L, 1);
  const char* text = check_text(L, 2);
  check_no_extra_args(L, 2);
  std::string out;
  for (const char* line = text;;) {  // each line of the text wrapped on its own
    const char* end = std::strchr(line, '\n');
    const std::string part = end ? std::string(line, end) : std::string(line);
    out += part.empty() ? "\n" : fit_words(part, "  ", tally.width);
    if (end == nullptr) break;
    line = end + 1;
  }
  write(tally, out);
  return 0;
}

int context_gc(lua_State* L) {
  if (LessonTally* tally = test_lesson_context(L, 1)) tally->~LessonTally();
  return 0;
}

int context_tostring(lua_State* L) {
  LessonTally& tally = check_context(L, 1);
  lua_pushfstring(L, "lesson context (%d passed, %d failed)", tally.passed, tally.failed);
  return 1;
}

// Validates one step table at the top of the stack: {title =, text =, formula =, run =}.
void check_step(lua_State* L, int arg, int number) {
  const int step = lua_gettop(L);
  if (lua_type(L, step) != LUA_TTABLE)
    arg_error(L, arg, "steps[%d] must be a table, got %s", number, value_type_name(L, step));
  static const char* const allowed[] = {"title", "text", "formula", "run", nullptr};
  lua_pushnil(L);
  while (lua_next(L, step) != 0) {
    lua_pop(L, 1);
    bool known = false;
    for (const char* const* a = allowed; *a && !known; ++a)
      known = lua_type(L, -1) == LUA_TSTRING && std::strcmp(*a, lua_tostring(L, -1)) == 0;
    if (!known)
      arg_error(L, arg, "steps[%d]: unknown field '%s' (fields are: title, text, formula, run)",
                number, luaL_tolstring(L, -1, nullptr));
  }
  const struct { const char* name; int type; bool required; } fields[] = {
      {"title", LUA_TSTRING, true}, {"text", LUA_TSTRING, true},
      {"formula", LUA_TSTRING, false}, {"run", LUA_TFUNCTION, false}};
  for (const auto& f : fields) {
    const int type = lua_getfield(L, step, f.name);
    if (type != f.type && (f.required || type != LUA_TNIL))
      arg_error(L, arg, "steps[%d]: field '%s' must be a %s, got %s", number, f.name,
                lua_typename(L, f.type), value_type_name(L, -1));
    lua_pop(L, 1);
  }
}

// lesson{id =, title =, source =, steps = {...}} -> the same table, validated.
int lesson_new(lua_State* L) {
  if (lua_type(L, 1) != LUA_TTABLE) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  static const char* const allowed[] = {"id", "title", "source", "steps", nullptr};
  check_fields(L, 1, allowed);
  for (const char* name : {"id", "title", "source"}) {
    if (lua_getfield(L, 1, name) != LUA_TSTRING || lua_rawlen(L, -1) == 0)
      arg_error(L, 1, "field '%s' must be a non-empty string, got %s", name, value_type_name(L, -1));
    lua_pop(L, 1);
  }
  lua_getfield(L, 1, "id");
  for (const char* c = lua_tostring(L, -1); *c; ++c)
    if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '-'))
      arg_error(L, 1, "field 'id' may hold only a-z, 0-9 and '-', got '%s'", lua_tostring(L, -1));
  lua_pop(L, 1);
  if (lua_getfield(L, 1, "steps") != LUA_TTABLE || lua_rawlen(L, -1) == 0)
    arg_error(L, 1, "field 'steps' must be a non-empty list of steps");
  const lua_Integer count = static_cast<lua_Integer>(lua_rawlen(L, -1));
  for (lua_Integer i = 1; i <= count; ++i) {
    lua_rawgeti(L, -1, i);
    check_step(L, 1, static_cast<int>(i));
    lua_pop(L, 1);
  }
  lua_settop(L, 1);
  return 1;
}

const Entry context_methods[] = {
    {"show", context_show, "ctx:show", "ctx:show(label, value)",
     "Prints a labelled value: a number, vec3, mat3, quat, string or table of numbers."},
    {"expect", context_expect, "ctx:expect", "ctx:expect(label, got, want [, tol]) -> ok",
     "Checks got against the document's value and prints got, want and ✓ or ✗. tol is relative\n"
     "to max(1, |want|) (default 1e-9), or {abs =, rel =}. Works component-wise for vec3, mat3,\n"
     "quat and tables of numbers. A failure is recorded (the check fails), not raised."},
    {"table", context_table, "ctx:table", "ctx:table(columns, rows)",
     "Prints an aligned table: columns a list of headings, rows a list of lists."},
    {"say", context_say, "ctx:say", "ctx:say(text)", "Prints a line of explanation."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry context_metamethods[] = {
    {"__gc", context_gc, "ctx.__gc", "", ""},
    {"__tostring", context_tostring, "ctx.__tostring", "tostring(ctx)", ""},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry functions[] = {
    {"lesson", lesson_new, "lesson", "lesson{id =, title =, source =, steps = {...}} -> lesson",
     "Declares a lesson (a file in lessons/ returns one). Each step is\n"
     "{title =, text =, formula =, run = function(ctx) ... end}: text explains in words,\n"
     "formula (optional) shows the document's formula, run computes and calls ctx:show,\n"
     "ctx:expect, ctx:table, ctx:say. `rigidlab lesson ID` steps through it,\n"
     "`rigidlab check` runs every expectation."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

LessonTally& push_lesson_context(lua_State* L, bool quiet) {
  void* memory = lua_newuserdatauv(L, sizeof(LessonTally), 0);
  LessonTally* tally = new (memory) LessonTally();
  tally->quiet = quiet;
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &lesson_context_key) != LUA_TTABLE) {
    lua_pop(L, 1);
    new_metatable(L, "lesson context", &lesson_context_key);
    register_entries(L, -1, context_metamethods);
    lua_newtable(L);
    register_entries(L, -1, context_methods);
    lua_setfield(L, -2, "__index");
  }
  lua_setmetatable(L, -2);
  return *tally;
}

LessonTally* test_lesson_context(lua_State* L, int index) {
  return has_metatable(L, index, &lesson_context_key)
             ? static_cast<LessonTally*>(lua_touserdata(L, index))
             : nullptr;
}

namespace {
std::string lesson_number(double x) { return format_number(x == 0.0 ? 0.0 : x, 10); }

std::string number_list(const double* x, int n) {
  std::string text;
  for (int i = 0; i < n; ++i) text += (i ? ", " : "") + lesson_number(x[i]);
  return text;
}
}  // namespace

std::string format_value(lua_State* L, int index, const std::string& indent) {
  index = lua_absindex(L, index);
  if (lua_type(L, index) == LUA_TNUMBER) {
    if (lua_isinteger(L, index)) return std::to_string(lua_tointeger(L, index));
    return lesson_number(lua_tonumber(L, index));
  }
  if (const Vec3* v = test_vec3(L, index)) return "(" + number_list(v->data(), 3) + ")";
  if (const Quat* q = test_quat(L, index)) {
    const double wxyz[] = {q->w(), q->x(), q->y(), q->z()};
    return "quat(" + number_list(wxyz, 4) + ")";
  }
  if (const Mat3* m = test_mat3(L, index)) {
    std::string text = indent.empty() ? "(" : "";
    for (int i = 0; i < 3; ++i) {
      const double row[] = {(*m)(i, 0), (*m)(i, 1), (*m)(i, 2)};
      const std::string opening = indent.empty() ? (i ? ", (" : "(") : "\n" + indent + "(";
      text += opening + number_list(row, 3) + ")";
    }
    return indent.empty() ? text + ")" : text;
  }
  if (lua_type(L, index) == LUA_TTABLE) {
    std::string text = "{";
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, index));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, index, i);
      if (i > 1) text += ", ";
      if (lua_type(L, -1) == LUA_TNUMBER) {
        text += format_value(L, -1, "");
      } else {  // by tostring: no recursion into nested (possibly cyclic) tables
        text += luaL_tolstring(L, -1, nullptr);
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
    }
    return text + "}";
  }
  std::string text = luaL_tolstring(L, index, nullptr);
  lua_pop(L, 1);
  return text;
}

void open_lesson(lua_State* L, int lib) { register_entries(L, lib, functions); }

}  // namespace rigidlab::lua
