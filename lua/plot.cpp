// plot.lines{...}: a line chart of one or more series in the terminal — Unicode braille dots
// (2 x 4 per character) when the locale is UTF-8, plain ASCII otherwise — with axis ranges,
// labels and a legend, and optionally the same chart as a standalone SVG file. It prints
// through the global `print`, so whatever silences print (the lesson checker) silences it.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "lua/binding.hpp"
#include "lua/modules.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::lua {
namespace {

struct Series {
  std::vector<double> x, y;
  std::string label;
};

struct Chart {
  std::vector<Series> series;
  std::string title, xlabel, ylabel, svg;
  int width = 60, height = 15;  // plot area in characters
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
};

bool utf8_locale() {
  for (const char* name : {"LC_ALL", "LC_CTYPE", "LANG"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && *value != '\0') {
      std::string v = value;
      std::transform(v.begin(), v.end(), v.begin(), ::tolower);
      return v.find("utf-8") != std::string::npos || v.find("utf8") != std::string::npos;
    }
  }
  return false;
}

// Axis labels: four significant digits are enough to read a chart.
std::string short_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", x);
  return buffer;
}

bool use_color() { return isatty(STDOUT_FILENO) && std::getenv("NO_COLOR") == nullptr; }

// Tables are read raw (lua_rawlen, lua_rawgeti, lua_rawget): a table's metamethods are not
// run, so they cannot raise errors of their own from inside plot.lines.
std::vector<double> read_numbers(lua_State* L, int table, const char* what, int series) {
  std::vector<double> values;
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, table));
  for (lua_Integer i = 1; i <= n; ++i) {
    if (lua_rawgeti(L, table, i) != LUA_TNUMBER)
      arg_error(L, 1, "series %d: %s[%d] must be a number, got %s", series, what, (int)i,
                value_type_name(L, -1));
    const double v = lua_tonumber(L, -1);
    if (!std::isfinite(v))
      arg_error(L, 1, "series %d: %s[%d] is %s", series, what, (int)i, format_number(v).c_str());
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
std::string string_field(lua_State* L, int table, const char* name, int series = 0) {
  const int type = raw_field(L, table, name);
  if (type != LUA_TNIL && type != LUA_TSTRING) {
    if (series > 0)
      arg_error(L, 1, "series %d: field '%s' must be a string, got %s", series, name,
                value_type_name(L, -1));
    arg_error(L, 1, "field '%s' must be a string, got %s", name, value_type_name(L, -1));
  }
  std::string value = type == LUA_TSTRING ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  return value;
}

// Field `name` of the chart: an integer from `lo` to `hi`, or absent (`fallback`).
int size_field(lua_State* L, const char* name, int lo, int hi, int fallback) {
  const int type = raw_field(L, 1, name);
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    return fallback;
  }
  if (type != LUA_TNUMBER)
    arg_error(L, 1, "field '%s' must be a number, got %s", name, value_type_name(L, -1));
  const double x = lua_tonumber(L, -1);
  lua_pop(L, 1);
  if (!(x >= lo && x <= hi && x == std::floor(x)))  // NaN fails too; checked before any cast
    arg_error(L, 1, "field '%s' must be an integer from %d to %d, got %s", name, lo, hi,
              format_number(x).c_str());
  return static_cast<int>(x);
}

// The keys of the table at `table` must be in `fields` or, when `count` >= 0, integers 1 to
// `count` (the series): a misspelt option would otherwise be silently ignored.
void check_keys(lua_State* L, int table, const char* const* fields, lua_Integer count,
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
    std::string key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2)
                      : lua_type(L, -2) == LUA_TNUMBER
                          ? format_number(lua_tonumber(L, -2))
                          : std::string("a ") + value_type_name(L, -2) + " key";
    std::string list;
    for (const char* const* f = fields; *f; ++f) list += std::string(list.empty() ? "" : ", ") + *f;
    if (series > 0)
      arg_error(L, 1, "series %d: unknown field '%s' (fields are %s)", series, key.c_str(),
                list.c_str());
    arg_error(L, 1, "unknown field '%s' (fields are %s, and the series 1 to %d)", key.c_str(),
              list.c_str(), (int)count);
  }
}

// Where x lies in [lo, hi], as a fraction in [0, 1]. Computed on halves, so that no difference
// overflows even for a range from -1.8e308 to 1.8e308; span(lo, hi) > 0 (widen) keeps it finite.
double span(double lo, double hi) { return hi / 2 - lo / 2; }
double fraction(double x, double lo, double hi) {
  const double t = (x / 2 - lo / 2) / span(lo, hi);
  return t >= 0.0 ? std::min(t, 1.0) : 0.0;  // and 0 for a NaN, which cannot happen
}

Chart read_chart(lua_State* L) {
  if (lua_type(L, 1) != LUA_TTABLE) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  const lua_Integer count = static_cast<lua_Integer>(lua_rawlen(L, 1));
  static const char* const chart_fields[] = {"title", "xlabel", "ylabel", "width", "height", "svg",
                                             nullptr};
  check_keys(L, 1, chart_fields, count, 0);
  Chart chart;
  chart.title = string_field(L, 1, "title");
  chart.xlabel = string_field(L, 1, "xlabel");
  chart.ylabel = string_field(L, 1, "ylabel");
  chart.svg = string_field(L, 1, "svg");
  chart.width = size_field(L, "width", 10, 400, 60);
  chart.height = size_field(L, "height", 4, 200, 15);
  if (count == 0) arg_error(L, 1, "at least one series {x = {...}, y = {...}} expected");
  for (lua_Integer s = 1; s <= count; ++s) {
    if (lua_rawgeti(L, 1, s) != LUA_TTABLE)
      arg_error(L, 1, "series %d must be a table, got %s", (int)s, value_type_name(L, -1));
    const int table = lua_gettop(L);
    static const char* const fields[] = {"x", "y", "label", nullptr};
    check_keys(L, table, fields, -1, static_cast<int>(s));
    Series series;
    if (raw_field(L, table, "y") != LUA_TTABLE)
      arg_error(L, 1, "series %d: field 'y' must be a list of numbers", (int)s);
    series.y = read_numbers(L, lua_gettop(L), "y", static_cast<int>(s));
    lua_pop(L, 1);
    if (raw_field(L, table, "x") == LUA_TTABLE) {
      series.x = read_numbers(L, lua_gettop(L), "x", static_cast<int>(s));
      if (series.x.size() != series.y.size())
        arg_error(L, 1, "series %d: x has %d values but y has %d", (int)s, (int)series.x.size(),
                  (int)series.y.size());
    } else if (!lua_isnil(L, -1)) {
      arg_error(L, 1, "series %d: field 'x' must be a list of numbers", (int)s);
    } else {
      for (size_t i = 0; i < series.y.size(); ++i) series.x.push_back(double(i + 1));
    }
    lua_pop(L, 1);
    if (series.y.empty()) arg_error(L, 1, "series %d has no points", (int)s);
    series.label = string_field(L, table, "label", static_cast<int>(s));
    if (series.label.empty()) series.label = "series " + std::to_string(s);
    chart.series.push_back(std::move(series));
    lua_pop(L, 1);
  }
  chart.x_min = chart.y_min = HUGE_VAL;
  chart.x_max = chart.y_max = -HUGE_VAL;
  for (const Series& s : chart.series) {
    chart.x_min = std::min(chart.x_min, *std::min_element(s.x.begin(), s.x.end()));
    chart.x_max = std::max(chart.x_max, *std::max_element(s.x.begin(), s.x.end()));
    chart.y_min = std::min(chart.y_min, *std::min_element(s.y.begin(), s.y.end()));
    chart.y_max = std::max(chart.y_max, *std::max_element(s.y.begin(), s.y.end()));
  }
  auto widen = [](double& lo, double& hi) {  // a flat range still gets a visible axis
    if (span(lo, hi) > 0.0) return;
    const double pad = std::fabs(lo) < 1e-300 ? 1.0 : 0.5 * std::fabs(lo);
    lo = std::max(lo - pad, -DBL_MAX);  // near ±1.8e308 the padded range stays finite
    hi = std::min(hi + pad, DBL_MAX);
  };
  widen(chart.x_min, chart.x_max);
  widen(chart.y_min, chart.y_max);
  return chart;
}

// The dot grid: `columns` x `rows` dots, each holding the index of the series drawn there + 1.
struct Grid {
  int columns, rows;
  std::vector<int> dots;
  Grid(int c, int r) : columns(c), rows(r), dots(size_t(c) * r, 0) {}
  void set(int c, int r, int series) {
    if (c >= 0 && c < columns && r >= 0 && r < rows) dots[size_t(r) * columns + c] = series + 1;
  }
  int at(int c, int r) const { return dots[size_t(r) * columns + c]; }
};

// Draws each series as straight segments between its points (Bresenham in dot space).
Grid draw(const Chart& chart, int columns, int rows) {
  Grid grid(columns, rows);
  auto to_column = [&](double x) {
    return int(std::lround(fraction(x, chart.x_min, chart.x_max) * (columns - 1)));
  };
  auto to_row = [&](double y) {  // row 0 at the top
    return int(std::lround((1.0 - fraction(y, chart.y_min, chart.y_max)) * (rows - 1)));
  };
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const Series& series = chart.series[s];
    for (size_t i = 0; i < series.x.size(); ++i) {
      int c0 = to_column(series.x[i]), r0 = to_row(series.y[i]);
      const int c1 = i + 1 < series.x.size() ? to_column(series.x[i + 1]) : c0;
      const int r1 = i + 1 < series.x.size() ? to_row(series.y[i + 1]) : r0;
      const int dc = std::abs(c1 - c0), dr = -std::abs(r1 - r0);
      const int sc = c0 < c1 ? 1 : -1, sr = r0 < r1 ? 1 : -1;
      for (int error = dc + dr;;) {
        grid.set(c0, r0, static_cast<int>(s));
        if (c0 == c1 && r0 == r1) break;
        const int e2 = 2 * error;
        if (e2 >= dr) { error += dr; c0 += sc; }
        if (e2 <= dc) { error += dc; r0 += sr; }
      }
    }
  }
  return grid;
}

const char* const ansi_colors[] = {"\x1b[34m", "\x1b[31m", "\x1b[32m", "\x1b[35m", "\x1b[33m",
                                   "\x1b[36m"};
const char ascii_markers[] = {'*', '+', 'o', 'x', '#', '@'};

std::string encode_utf8(unsigned code) {
  std::string out;
  out += char(0xE0 | (code >> 12));
  out += char(0x80 | ((code >> 6) & 0x3F));
  out += char(0x80 | (code & 0x3F));
  return out;
}

// One character cell of the chart: braille dots of the cell, colored by the series that drew
// most of them, or the ASCII marker of that series.
std::string cell(const Grid& grid, int column, int row, bool braille, bool color) {
  static const int bits[4][2] = {{0x01, 0x08}, {0x02, 0x10}, {0x04, 0x20}, {0x40, 0x80}};
  const int dx = braille ? 2 : 1, dy = braille ? 4 : 1;
  int pattern = 0, series = 0;
  for (int r = 0; r < dy; ++r)
    for (int c = 0; c < dx; ++c)
      if (int s = grid.at(column * dx + c, row * dy + r)) {
        pattern |= braille ? bits[r][c] : 1;
        series = s;
      }
  if (pattern == 0) return " ";
  std::string glyph = braille ? encode_utf8(0x2800 + pattern)
                              : std::string(1, ascii_markers[(series - 1) % 6]);
  if (!color) return glyph;
  return ansi_colors[(series - 1) % 6] + glyph + "\x1b[0m";
}

std::string text_chart(const Chart& chart) {
  const bool braille = utf8_locale(), color = use_color();
  const Grid grid = draw(chart, chart.width * (braille ? 2 : 1), chart.height * (braille ? 4 : 1));
  const std::string top = short_number(chart.y_max), bottom = short_number(chart.y_min);
  const size_t margin = std::max(top.size(), bottom.size());
  const std::string vertical = braille ? "┤" : "|", axis = braille ? "│" : "|";
  const std::string corner = braille ? "└" : "+", horizontal = braille ? "─" : "-";
  std::string out;
  if (!chart.title.empty())
    out += std::string(margin + 2 + std::max<int>(0, (chart.width - int(chart.title.size())) / 2),
                       ' ') + chart.title + "\n";
  if (!chart.ylabel.empty()) out += std::string(margin + 1, ' ') + chart.ylabel + "\n";
  for (int row = 0; row < chart.height; ++row) {
    std::string label = row == 0 ? top : row == chart.height - 1 ? bottom : "";
    out += std::string(margin - label.size(), ' ') + label + " " + (label.empty() ? axis : vertical);
    for (int column = 0; column < chart.width; ++column)
      out += cell(grid, column, row, braille, color);
    out += "\n";
  }
  out += std::string(margin + 1, ' ') + corner;
  for (int i = 0; i < chart.width; ++i) out += horizontal;
  const std::string left = short_number(chart.x_min), right = short_number(chart.x_max);
  out += "\n" + std::string(margin + 2, ' ') + left +
         std::string(std::max<int>(1, chart.width - int(left.size() + right.size())), ' ') + right;
  if (!chart.xlabel.empty())
    out += "\n" + std::string(margin + 2 + std::max<int>(0, (chart.width - int(chart.xlabel.size())) / 2),
                              ' ') + chart.xlabel;
  out += "\n" + std::string(margin + 2, ' ');
  for (size_t s = 0; s < chart.series.size(); ++s) {
    std::string marker = braille ? encode_utf8(0x28FF) : std::string(1, ascii_markers[s % 6]);
    if (color) marker = ansi_colors[s % 6] + marker + "\x1b[0m";
    out += (s ? "   " : "") + marker + " " + chart.series[s].label;
  }
  return out;
}

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

void write_svg(lua_State* L, const Chart& chart) {
  const double W = 720, H = 440, left = 80, right = 20, top = 50, bottom = 80;
  const double pw = W - left - right, ph = H - top - bottom;
  auto sx = [&](double x) { return left + fraction(x, chart.x_min, chart.x_max) * pw; };
  auto sy = [&](double y) { return top + (1.0 - fraction(y, chart.y_min, chart.y_max)) * ph; };
  static const char* const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                       "#17becf"};
  std::FILE* file = std::fopen(chart.svg.c_str(), "w");
  if (file == nullptr)
    arg_error(L, 1, "cannot write svg '%s': %s", chart.svg.c_str(), std::strerror(errno));
  std::fprintf(file,
               "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
               "font-family=\"sans-serif\" font-size=\"13\">\n"
               "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
               W, H);
  std::fprintf(file, "<text x=\"%g\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">%s</text>\n",
               W / 2, xml_escape(chart.title).c_str());
  std::fprintf(file, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" "
               "stroke=\"#444\"/>\n", left, top, pw, ph);
  std::fprintf(file, "<text x=\"%g\" y=\"%g\" text-anchor=\"end\">%s</text>\n", left - 6, top + 5,
               short_number(chart.y_max).c_str());
  std::fprintf(file, "<text x=\"%g\" y=\"%g\" text-anchor=\"end\">%s</text>\n", left - 6,
               top + ph + 5, short_number(chart.y_min).c_str());
  std::fprintf(file, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%s</text>\n", left,
               top + ph + 20, short_number(chart.x_min).c_str());
  std::fprintf(file, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%s</text>\n", left + pw,
               top + ph + 20, short_number(chart.x_max).c_str());
  std::fprintf(file, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%s</text>\n", left + pw / 2,
               top + ph + 40, xml_escape(chart.xlabel).c_str());
  std::fprintf(file, "<text x=\"18\" y=\"%g\" text-anchor=\"middle\" transform=\"rotate(-90 18 %g)\">"
               "%s</text>\n", top + ph / 2, top + ph / 2, xml_escape(chart.ylabel).c_str());
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const Series& series = chart.series[s];
    std::fprintf(file, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"",
                 colors[s % 6]);
    for (size_t i = 0; i < series.x.size(); ++i)
      std::fprintf(file, "%s%.2f,%.2f", i ? " " : "", sx(series.x[i]), sy(series.y[i]));
    std::fprintf(file, "\"/>\n");
    const double lx = left + 10 + 150 * double(s), ly = H - 18;
    std::fprintf(file, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"%s\" "
                 "stroke-width=\"3\"/><text x=\"%g\" y=\"%g\">%s</text>\n", lx, ly - 4, lx + 24,
                 ly - 4, colors[s % 6], lx + 30, ly, xml_escape(series.label).c_str());
  }
  std::fprintf(file, "</svg>\n");
  if (std::fclose(file) != 0) function_error(L, "could not finish writing '%s'", chart.svg.c_str());
}

int plot_lines(lua_State* L) {
  const Chart chart = read_chart(L);
  if (!chart.svg.empty()) {
    if (is_sandboxed(L)) arg_error(L, 1, "svg files cannot be written in the sandbox");
    write_svg(L, chart);
  }
  const std::string text = text_chart(chart);
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
     "otherwise, colored in a terminal (NO_COLOR turns colors off), with the axis ranges,\n"
     "labels and a legend. x may be left out (1, 2, 3, ...). width and height are the plot\n"
     "area in characters (default 60 x 15). svg = \"file.svg\" also writes the chart as SVG."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_plot(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "plot", "Charts in the terminal: plot.lines{...}.");
  lua_setfield(L, lib, "plot");
}

}  // namespace rigidlab::lua
