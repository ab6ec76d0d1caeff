// plot.lines{...}: argument parsing only. The chart is drawn by present/text_chart (braille or
// ASCII, colour or glyphs per series) and written by present/svg_chart. It prints through the
// global `print`, so whatever silences print (the lesson checker) silences it.
#include "lua/plot.hpp"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "lua/binding.hpp"
#include "lua/modules.hpp"
#include "lua/output_file.hpp"
#include "present/file.hpp"
#include "present/svg_chart.hpp"
#include "present/text_chart.hpp"

namespace rigidlab::lua {
namespace {

// Reads the list at `table` raw (lua_rawlen, lua_rawgeti): its metamethods are not run, so
// they cannot raise errors of their own from inside plot.lines.
std::vector<double> read_numbers(lua_State* L, int arg, int table, const char* what, int series) {
  std::vector<double> values;
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, table));
  for (lua_Integer i = 1; i <= n; ++i) {
    if (lua_rawgeti(L, table, i) != LUA_TNUMBER)
      arg_error(L, arg, "series %d: %s[%d] must be a number, got %s", series, what, (int)i,
                value_type_name(L, -1));
    const double v = lua_tonumber(L, -1);
    if (!std::isfinite(v))
      arg_error(L, arg, "series %d: %s[%d] is %s", series, what, (int)i, format_number(v).c_str());
    values.push_back(v);
    lua_pop(L, 1);
  }
  return values;
}

int raw_field(lua_State* L, int table, const char* name) {
  lua_pushstring(L, name);
  return lua_rawget(L, table);
}

// Field `name` of the table at `table`: a string or absent. `series` > 0 names the series.
std::string string_field(lua_State* L, int arg, int table, const char* name, int series = 0) {
  const int type = raw_field(L, table, name);
  if (type != LUA_TNIL && type != LUA_TSTRING) {
    if (series > 0)
      arg_error(L, arg, "series %d: field '%s' must be a string, got %s", series, name,
                value_type_name(L, -1));
    arg_error(L, arg, "field '%s' must be a string, got %s", name, value_type_name(L, -1));
  }
  std::size_t size = 0;
  const char* text = type == LUA_TSTRING ? lua_tolstring(L, -1, &size) : "";
  std::string value(text, size);
  lua_pop(L, 1);
  return value;
}

// Field `name` of the chart: an integer from `lo` to `hi`, or absent (`fallback`).
int size_field(lua_State* L, int arg, const char* name, int lo, int hi, int fallback) {
  const int type = raw_field(L, arg, name);
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    return fallback;
  }
  if (type != LUA_TNUMBER)
    arg_error(L, arg, "field '%s' must be a number, got %s", name, value_type_name(L, -1));
  const double x = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (!(x >= lo && x <= hi && x == std::floor(x)))  // NaN fails too; checked before any cast
    arg_error(L, arg, "field '%s' must be an integer from %d to %d, got %s", name, lo, hi,
              format_number(x).c_str());
  return static_cast<int>(x);
}

// The keys of the table at `table` must be in `fields` or, when `count` >= 0, integers 1 to
// `count` (the series): a misspelt option would otherwise be silently ignored.
void check_keys(lua_State* L, int arg, int table, const char* const* fields, lua_Integer count,
                int series) {
  for (lua_pushnil(L); lua_next(L, table) != 0; lua_pop(L, 1)) {
    bool known = false;
    if (lua_type(L, -2) == LUA_TSTRING) {
      for (const char* const* f = fields; *f && !known; ++f)
        known = std::strcmp(*f, lua_tostring(L, -2)) == 0;
    } else if (count >= 0 && lua_isinteger(L, -2)) {
      known = lua_tointeger(L, -2) >= 1 && lua_tointeger(L, -2) <= count;
    }
    if (known) continue;
    const char* key = push_key_name(L, -2);
    std::string list;
    for (const char* const* f = fields; *f; ++f) list += std::string(list.empty() ? "" : ", ") + *f;
    if (series > 0)
      arg_error(L, arg, "series %d: unknown field '%s' (fields are %s)", series, key, list.c_str());
    arg_error(L, arg, "unknown field '%s' (fields are %s, and the series 1 to %d)", key,
              list.c_str(), (int)count);
  }
}

present::Series read_series(lua_State* L, int arg, int s) {
  if (lua_rawgeti(L, arg, s) != LUA_TTABLE)
    arg_error(L, arg, "series %d must be a table, got %s", s, value_type_name(L, -1));
  const int table = lua_gettop(L);
  static const char* const fields[] = {"x", "y", "label", nullptr};
  check_keys(L, arg, table, fields, -1, s);
  present::Series series;
  if (raw_field(L, table, "y") != LUA_TTABLE)
    arg_error(L, arg, "series %d: field 'y' must be a list of numbers", s);
  series.y = read_numbers(L, arg, lua_gettop(L), "y", s);
  lua_pop(L, 1);
  if (raw_field(L, table, "x") == LUA_TTABLE) {
    series.x = read_numbers(L, arg, lua_gettop(L), "x", s);
    if (series.x.size() != series.y.size())
      arg_error(L, arg, "series %d: x has %d values but y has %d", s, (int)series.x.size(),
                (int)series.y.size());
  } else if (!lua_isnil(L, -1)) {
    arg_error(L, arg, "series %d: field 'x' must be a list of numbers", s);
  } else {
    for (std::size_t i = 0; i < series.y.size(); ++i) series.x.push_back(double(i + 1));
  }
  lua_pop(L, 1);
  if (series.y.empty()) arg_error(L, arg, "series %d has no points", s);
  series.label = string_field(L, arg, table, "label", s);
  if (series.label.empty()) series.label = "series " + std::to_string(s);
  lua_pop(L, 1);
  return series;
}

int plot_lines(lua_State* L) {
  check_no_extra_args(L, 1);
  const PlotRequest request = check_plot_request(L, 1);
  if (!request.svg.empty())
    write_or_raise(L, 1, "svg",
                   [&] { present::write_file(request.svg, present::svg_chart(request.chart)); });
  present::TextChartOptions options;
  options.width = request.width;
  options.height = request.height;
  options.style = present::terminal_style(STDOUT_FILENO);
  const std::string text = present::text_chart(request.chart, options);
  lua_getglobal(L, "print");
  lua_pushlstring(L, text.data(), text.size());
  lua_call(L, 1, 0);
  return 0;
}

const Entry functions[] = {
    {"lines", plot_lines, "plot.lines",
     "plot.lines{ {x = xs, y = ys, label = \"rk4\"}, ..., title =, xlabel =, ylabel =, width =, "
     "height =, svg = }",
     "Prints a line chart of one or more series: braille dots when the locale is UTF-8, ASCII\n"
     "otherwise, with ticks at round numbers, the labels and a legend. In a terminal each\n"
     "series has its colour; without colour (NO_COLOR, a pipe) each has its glyph (* + o x # @),\n"
     "marked along its line and in the legend. x may be left out (1, 2, 3, ...). width and\n"
     "height are the plot area in characters (default 60 x 15). svg = \"file.svg\" also writes\n"
     "the chart as an SVG file with ticks and grid lines."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

PlotRequest check_plot_request(lua_State* L, int arg) {
  if (lua_type(L, arg) != LUA_TTABLE) type_error(L, arg, "table");
  const lua_Integer count = static_cast<lua_Integer>(lua_rawlen(L, arg));
  static const char* const chart_fields[] = {"title", "xlabel", "ylabel", "width", "height", "svg",
                                             nullptr};
  check_keys(L, arg, arg, chart_fields, count, 0);
  PlotRequest request;
  request.chart.title = string_field(L, arg, arg, "title");
  request.chart.xlabel = string_field(L, arg, arg, "xlabel");
  request.chart.ylabel = string_field(L, arg, arg, "ylabel");
  if (raw_field(L, arg, "svg") != LUA_TNIL) request.svg = check_output_path(L, arg, -1, "svg");
  lua_pop(L, 1);
  request.width = size_field(L, arg, "width", 10, 400, 60);
  request.height = size_field(L, arg, "height", 4, 200, 15);
  if (count == 0) arg_error(L, arg, "at least one series {x = {...}, y = {...}} expected");
  for (lua_Integer s = 1; s <= count; ++s)
    request.chart.series.push_back(read_series(L, arg, static_cast<int>(s)));
  return request;
}

void open_plot(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "plot", "Charts in the terminal: plot.lines{...}.");
  lua_setfield(L, lib, "plot");
}

}  // namespace rigidlab::lua
