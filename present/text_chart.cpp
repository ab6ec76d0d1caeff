#include "present/text_chart.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "present/canvas.hpp"
#include "present/text.hpp"

namespace rigidlab::present {
namespace {

const char* const series_colors[] = {"\x1b[34m", "\x1b[31m", "\x1b[32m",
                                     "\x1b[35m", "\x1b[33m", "\x1b[36m"};
const char series_glyphs[] = {'*', '+', 'o', 'x', '#', '@'};

Ink series_ink(std::size_t s) { return static_cast<Ink>(1 + s % 255); }
char series_glyph(std::size_t s) { return series_glyphs[s % 6]; }

struct Layout {
  Axis x, y;
  std::size_t margin = 0;  // width of the y tick labels
};

std::size_t widest(const std::vector<std::string>& labels) {
  std::size_t w = 0;
  for (const std::string& l : labels) w = std::max(w, l.size());
  return w;
}

// Axes with as many ticks as fit: y labels at least two rows apart, x labels with two spaces
// between them.
Layout layout(const Chart& chart, int width, int height) {
  Layout out;
  out.y = y_axis(chart, std::clamp(height / 2 + 1, 2, 8));
  for (int n = std::clamp(width / 6, 2, 10);; --n) {
    out.x = x_axis(chart, n);
    if (n <= 2 || static_cast<int>(out.x.ticks.size() * (widest(out.x.labels) + 2)) <= width)
      break;
  }
  out.margin = widest(out.y.labels);
  return out;
}

// Draws every series as straight segments between its points.
void draw_series(Canvas& canvas, const Chart& chart, const Layout& axes) {
  const double w = canvas.dots_x() - 1, h = canvas.dots_y() - 1;
  for (std::size_t s = 0; s < chart.series.size(); ++s) {
    const Series& series = chart.series[s];
    Stroke stroke = solid_stroke(series_ink(s));
    stroke.glyph = series_glyph(s);
    double px = axes.x.fraction(series.x[0]) * w, py = (1 - axes.y.fraction(series.y[0])) * h;
    canvas.line(px, py, px, py, stroke);
    for (std::size_t i = 1; i < series.x.size(); ++i) {
      const double qx = axes.x.fraction(series.x[i]) * w;
      const double qy = (1 - axes.y.fraction(series.y[i])) * h;
      canvas.line(px, py, qx, qy, stroke);
      px = qx;
      py = qy;
    }
  }
}

// Without colour, in braille: each series' glyph on its line every `spacing` columns, the
// series staggered so their marks do not meet; at least one mark per series.
void mark_series(Canvas& canvas, std::size_t count) {
  const int spacing = std::max<int>(6, 2 * static_cast<int>(count));
  for (std::size_t s = 0; s < count; ++s) {
    const Ink ink = series_ink(s);
    const int offset = static_cast<int>(s) * spacing / static_cast<int>(count);
    bool marked = false;
    int first_column = -1, first_row = -1;
    for (int column = 0; column < canvas.columns(); ++column) {
      std::vector<int> rows;
      for (int row = 0; row < canvas.rows(); ++row)
        if (canvas.has_ink(column, row, ink)) rows.push_back(row);
      if (rows.empty()) continue;
      if (first_column < 0) {
        first_column = column;
        first_row = rows[rows.size() / 2];
      }
      if (column % spacing != offset) continue;
      canvas.text(column, rows[rows.size() / 2], std::string(1, series_glyph(s)), ink);
      marked = true;
    }
    if (!marked && first_column >= 0)
      canvas.text(first_column, first_row, std::string(1, series_glyph(s)), ink);
  }
}

std::string colored(const std::string& text, std::size_t s, bool color) {
  return color ? series_colors[s % 6] + text + "\x1b[0m" : text;
}

// The legend's entries, wrapped to `width` columns, each line starting with `indent`.
std::vector<std::string> legend(const Chart& chart, const TextStyle& style, bool marks,
                                std::size_t indent, std::size_t width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t used = 0;
  for (std::size_t s = 0; s < chart.series.size(); ++s) {
    std::string key = !style.unicode ? std::string(1, series_glyph(s))
                      : marks        ? "─" + std::string(1, series_glyph(s)) + "─"
                                     : "⣿";
    const std::string label = printable(chart.series[s].label, style.unicode);
    const std::size_t entry = display_width(key) + 1 + display_width(label);
    if (used > 0 && indent + used + 3 + entry > width) {
      lines.push_back(line);
      line.clear();
      used = 0;
    }
    if (used == 0) line = std::string(indent, ' ');
    else line += "   ", used += 3;
    line += colored(key, s, style.color) + " " + label;
    used += entry;
  }
  lines.push_back(line);
  return lines;
}

std::string centred(const std::string& text, std::size_t indent, int width) {
  const int pad = std::max(0, (width - static_cast<int>(display_width(text))) / 2);
  return std::string(indent + pad, ' ') + text;
}

// The x axis line with a tick mark under each labelled column, and the labels' line.
void x_axis_lines(const Layout& axes, int width, int dots_per_cell, const TextStyle& style,
                  std::vector<std::string>& out) {
  std::string labels(axes.margin + 2 + width + 8, ' ');
  std::vector<bool> ticked(width, false);
  int free_from = 0;  // the first column of `labels` a new label may use
  const int dots = width * dots_per_cell - 1;
  for (std::size_t i = 0; i < axes.x.ticks.size(); ++i) {
    const int column = static_cast<int>(std::lround(axes.x.fraction(axes.x.ticks[i]) * dots)) /
                       dots_per_cell;
    const std::string& label = axes.x.labels[i];
    const int at = static_cast<int>(axes.margin) + 2 + column;
    const int start = std::max(at - static_cast<int>(label.size() - 1) / 2, free_from);
    if (start + label.size() > labels.size()) continue;
    labels.replace(start, label.size(), label);
    free_from = start + static_cast<int>(label.size()) + 2;
    ticked[column] = true;
  }
  std::string axis = std::string(axes.margin + 1, ' ') + (style.unicode ? "└" : "+");
  for (int c = 0; c < width; ++c)
    axis += style.unicode ? (ticked[c] ? "┬" : "─") : (ticked[c] ? "+" : "-");
  out.push_back(axis);
  out.push_back(labels.substr(0, labels.find_last_not_of(' ') + 1));
}

}  // namespace

std::string text_chart(const Chart& chart, const TextChartOptions& options) {
  check_chart(chart);
  const TextStyle& style = options.style;
  const int width = std::max(options.width, 2), height = std::max(options.height, 2);
  const Layout axes = layout(chart, width, height);
  Canvas canvas(width, height, style.unicode);
  draw_series(canvas, chart, axes);
  const bool marks = style.unicode && !style.color && chart.series.size() > 1;
  if (marks) mark_series(canvas, chart.series.size());
  std::vector<std::string> palette;
  if (style.color) {
    palette.assign(256, "");
    for (std::size_t s = 0; s < chart.series.size() && s < 255; ++s)
      palette[series_ink(s)] = series_colors[s % 6];
  }
  std::vector<std::string> out;
  const std::size_t inset = axes.margin + 2;  // where the plot area starts
  if (!chart.title.empty()) out.push_back(centred(printable(chart.title, style.unicode), inset, width));
  if (!chart.ylabel.empty())
    out.push_back(std::string(axes.margin + 1, ' ') + printable(chart.ylabel, style.unicode));
  std::vector<std::string> labels(height);
  const int dots = canvas.dots_y() - 1, per_cell = canvas.dots_y() / height;
  for (std::size_t i = axes.y.ticks.size(); i-- > 0;) {  // from the top: the top row's is hi
    const int row = static_cast<int>(std::lround((1 - axes.y.fraction(axes.y.ticks[i])) * dots)) /
                    per_cell;
    if (labels[row].empty()) labels[row] = axes.y.labels[i];
  }
  const std::vector<std::string> rows = canvas.lines(palette);
  for (int row = 0; row < height; ++row) {
    const std::string& label = labels[row];
    const char* edge = style.unicode ? (label.empty() ? "│" : "┤") : "|";
    out.push_back(std::string(axes.margin - label.size(), ' ') + label + " " + edge + rows[row]);
  }
  x_axis_lines(axes, width, canvas.dots_x() / width, style, out);
  if (!chart.xlabel.empty())
    out.push_back(centred(printable(chart.xlabel, style.unicode), inset, width));
  for (const std::string& line : legend(chart, style, marks, inset, inset + width))
    out.push_back(line);
  std::string text;
  for (std::size_t i = 0; i < out.size(); ++i) text += (i ? "\n" : "") + out[i];
  return text;
}

}  // namespace rigidlab::present
