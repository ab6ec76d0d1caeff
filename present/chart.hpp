// The chart model shared by the terminal chart and the SVG writer: series of (x, y) points
// with labels, and axes whose ticks fall on round numbers.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::present {

struct Series {
  std::vector<double> x, y;  // the same length, at least one point, all finite
  std::string label;         // as typed; renderers make it printable
};

struct Chart {
  std::vector<Series> series;  // at least one
  std::string title, xlabel, ylabel;
};

// Throws std::invalid_argument when the chart breaks the rules above (the Lua binding checks
// first, with messages that name the argument; this guards the C++ callers).
void check_chart(const Chart& chart);

// An axis from `lo` to `hi` with ticks at multiples of `step`, each 1, 2 or 5 times a power of
// ten (Heckbert, "Nice numbers for graph labels", Graphics Gems, 1990): the data range is
// widened outwards to the nearest ticks ("loose" labelling), so both ends are labelled with
// round numbers. When the range is too wide or too narrow for that (near the largest double,
// or a few units in the last place), the ends are the data's own and are the only ticks.
struct Axis {
  double lo = 0.0, hi = 1.0;
  std::vector<double> ticks;         // ascending, from lo to hi
  std::vector<std::string> labels;   // one per tick, as few digits as tell them apart

  // Where `value` lies between lo and hi, from 0 to 1 (clamped). Computed on halves, so that
  // no difference overflows even for a range from -1.8e308 to 1.8e308.
  double fraction(double value) const;
};

// The axis for data from `data_lo` to `data_hi` (finite, lo <= hi; a single value is widened
// to a visible range) with about `max_ticks` ticks (at least 2).
Axis nice_axis(double data_lo, double data_hi, int max_ticks);

// The axes that fit every series of the chart.
Axis x_axis(const Chart& chart, int max_ticks);
Axis y_axis(const Chart& chart, int max_ticks);

// Heckbert's nice number: 1, 2, 5 or 10 times the power of ten below x (> 0), the nearest one
// when `round`, else the smallest not below x; 0 when x is too small or too large for that.
double nice_number(double x, bool round);

// Axis labels: four significant digits are enough to read a chart ("%.4g").
std::string short_number(double x);

}  // namespace rigidlab::present
