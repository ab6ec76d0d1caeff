#include "present/svg_chart.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <vector>

#include "present/text.hpp"

namespace rigidlab::present {
namespace {

const char* const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"};
// Past six series the colours repeat, each time with another dash pattern.
const char* const dashes[] = {"", " stroke-dasharray=\"8 4\"", " stroke-dasharray=\"2 3\"",
                              " stroke-dasharray=\"8 3 2 3\""};

std::string format(const char* spec, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* spec, ...) {
  char buffer[512];
  va_list args;
  va_start(args, spec);
  std::vsnprintf(buffer, sizeof buffer, spec, args);
  va_end(args);
  return buffer;
}

struct Frame {
  double width = 720, height = 440, left = 80, right = 20, top = 50, bottom = 80;
  double plot_width() const { return width - left - right; }
  double plot_height() const { return height - top - bottom; }
};

// Legend entries placed left to right, on a new row when the next would pass the right edge:
// x and row of each entry. Widths are estimated at 7.5 px per character of 13 px sans-serif.
std::vector<std::pair<double, int>> legend_places(const Chart& chart, const Frame& frame) {
  std::vector<std::pair<double, int>> places;
  double x = frame.left;
  int row = 0;
  for (const Series& s : chart.series) {
    const double w = 30 + 7.5 * display_width(printable(s.label, true)) + 24;
    if (x > frame.left && x + w > frame.width - frame.right) {
      x = frame.left;
      ++row;
    }
    places.emplace_back(x, row);
    x += w;
  }
  return places;
}

void grid(std::string& out, const Axis& x, const Axis& y, const Frame& f) {
  const double bottom = f.top + f.plot_height();
  for (std::size_t i = 0; i < y.ticks.size(); ++i) {
    const double py = f.top + (1 - y.fraction(y.ticks[i])) * f.plot_height();
    out += format("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#ddd\"/>\n",
                  f.left, py, f.left + f.plot_width(), py);
    out += format("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#444\"/>\n",
                  f.left - 5, py, f.left, py);
    out += format("<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">%s</text>\n", f.left - 8,
                  py + 4.5, xml_text(y.labels[i]).c_str());
  }
  for (std::size_t i = 0; i < x.ticks.size(); ++i) {
    const double px = f.left + x.fraction(x.ticks[i]) * f.plot_width();
    out += format("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#ddd\"/>\n", px,
                  f.top, px, bottom);
    out += format("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#444\"/>\n", px,
                  bottom, px, bottom + 5);
    out += format("<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%s</text>\n", px,
                  bottom + 20, xml_text(x.labels[i]).c_str());
  }
}

void series_lines(std::string& out, const Chart& chart, const Axis& x, const Axis& y,
                  const Frame& f) {
  const std::vector<std::pair<double, int>> places = legend_places(chart, f);
  const double legend_top = f.top + f.plot_height() + 62;
  for (std::size_t s = 0; s < chart.series.size(); ++s) {
    const Series& series = chart.series[s];
    const char* color = colors[s % 6];
    const char* dash = dashes[(s / 6) % 4];
    out += format("<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\"%s points=\"", color,
                  dash);
    for (std::size_t i = 0; i < series.x.size(); ++i)
      out += format("%s%.2f,%.2f", i ? " " : "", f.left + x.fraction(series.x[i]) * f.plot_width(),
                    f.top + (1 - y.fraction(series.y[i])) * f.plot_height());
    out += "\"/>\n";
    const double lx = places[s].first, ly = legend_top + 20 * places[s].second;
    out += format("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" "
                  "stroke-width=\"3\"%s/>", lx, ly - 4, lx + 24, ly - 4, color, dash);
    out += "<text x=\"" + format("%.2f", lx + 30) + "\" y=\"" + format("%.2f", ly) + "\">" +
           xml_text(series.label) + "</text>\n";
  }
}

}  // namespace

std::string svg_chart(const Chart& chart) {
  check_chart(chart);
  Frame f;
  const std::vector<std::pair<double, int>> places = legend_places(chart, f);
  f.height += 20 * places.back().second;
  f.bottom += 20 * places.back().second;
  const Axis x = x_axis(chart, 8), y = y_axis(chart, 6);
  std::size_t widest = 0;  // the y labels' room: 7.5 px per character, as the legend's
  for (const std::string& label : y.labels) widest = std::max(widest, label.size());
  f.left = std::max(f.left, 24 + 7.5 * static_cast<double>(widest));
  std::string out = format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" viewBox=\"0 0 %g %g\" "
      "font-family=\"sans-serif\" font-size=\"13\">\n",
      f.width, f.height, f.width, f.height);
  if (!chart.title.empty()) out += "<title>" + xml_text(chart.title) + "</title>\n";
  out += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out += format("<text x=\"%g\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">", f.width / 2) +
         xml_text(chart.title) + "</text>\n";
  grid(out, x, y, f);
  out += format("<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"#444\"/>\n",
                f.left, f.top, f.plot_width(), f.plot_height());
  out += format("<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">", f.left + f.plot_width() / 2,
                f.top + f.plot_height() + 42) + xml_text(chart.xlabel) + "</text>\n";
  out += format("<text x=\"18\" y=\"%g\" text-anchor=\"middle\" transform=\"rotate(-90 18 %g)\">",
                f.top + f.plot_height() / 2, f.top + f.plot_height() / 2) +
         xml_text(chart.ylabel) + "</text>\n";
  series_lines(out, chart, x, y, f);
  return out + "</svg>\n";
}

}  // namespace rigidlab::present
