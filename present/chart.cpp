#include "present/chart.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rigidlab::present {
namespace {

std::string format(const char* spec, int precision, double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, spec, precision, x + 0.0);  // + 0.0: no "-0"
  return buffer;
}

// Labels for `ticks`, with as many digits as the step needs (Heckbert's nfrac), more when two
// labels would still read the same.
std::vector<std::string> tick_labels(const std::vector<double>& ticks, double step) {
  double largest = 0.0;
  for (double t : ticks) largest = std::max(largest, std::fabs(t));
  const bool fixed = largest < 1e7 && step >= 1e-6;
  int precision = fixed ? std::max(0, -static_cast<int>(std::floor(std::log10(step))))
                        : std::clamp(static_cast<int>(std::floor(std::log10(largest)) -
                                                      std::floor(std::log10(step))) + 1, 1, 17);
  for (;; ++precision) {
    std::vector<std::string> labels;
    for (double t : ticks) labels.push_back(format(fixed ? "%.*f" : "%.*g", precision, t));
    if (std::adjacent_find(labels.begin(), labels.end()) == labels.end() || precision >= 17)
      return labels;
  }
}

// The ends alone, when round ticks cannot be placed.
Axis end_ticks(double lo, double hi) {
  Axis axis;
  axis.lo = lo;
  axis.hi = hi;
  axis.ticks = {lo, hi};
  for (int precision = 4;; ++precision) {
    axis.labels = {format("%.*g", precision, lo), format("%.*g", precision, hi)};
    if (axis.labels[0] != axis.labels[1] || precision >= 17) return axis;
  }
}

}  // namespace

double nice_number(double x, bool round) {
  const double power = std::pow(10.0, std::floor(std::log10(x)));
  if (!(power > 0.0) || !std::isfinite(power)) return 0.0;
  const double f = x / power;
  const double nice = round ? (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10)
                            : (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10);
  return nice * power;
}

void check_chart(const Chart& chart) {
  if (chart.series.empty()) throw std::invalid_argument("a chart needs at least one series");
  for (const Series& s : chart.series) {
    if (s.y.empty() || s.x.size() != s.y.size())
      throw std::invalid_argument("a series needs as many x as y values, at least one");
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
        throw std::invalid_argument("a series' values must be finite");
  }
}

double Axis::fraction(double value) const {
  const double t = (value / 2 - lo / 2) / (hi / 2 - lo / 2);
  return t >= 0.0 ? std::min(t, 1.0) : 0.0;  // and 0 for a NaN, which cannot happen
}

namespace {

// Heckbert's loose labelling of [lo, hi] (lo < hi, finite) for `n` ticks; false when the
// ticks cannot be placed (the span overflows, or ticks would repeat at the precision limit).
bool heckbert_ticks(double lo, double hi, int n, std::vector<double>& ticks, double& step) {
  const double span = hi - lo;
  if (!std::isfinite(span)) return false;
  const double range = nice_number(span, false);
  step = range > 0.0 ? nice_number(range / (n - 1), true) : 0.0;
  if (!(step > 0.0) || !std::isfinite(step)) return false;
  double first = std::floor(lo / step), last = std::ceil(hi / step);
  if (first * step > lo) first -= 1;  // a quotient rounded across an integer
  if (last * step < hi) last += 1;
  const double count = last - first + 1;
  if (!(count >= 2 && count <= 2.0 * n + 1) || !std::isfinite(first * step) ||
      !std::isfinite(last * step))
    return false;
  ticks.clear();
  for (int i = 0; i < static_cast<int>(count); ++i) {
    const double tick = (first + i) * step + 0.0;
    if (!ticks.empty() && !(tick > ticks.back())) return false;
    ticks.push_back(tick);
  }
  return ticks.back() / 2 - ticks.front() / 2 > 0.0;
}

}  // namespace

// Heckbert's procedure for each tick count up to `max_ticks`, keeping the tightest axis that
// has at most max_ticks + 1 ticks (ties: the most ticks): for 1 to 25 with 4 ticks it gives 0
// to 30 by 10, where n = 4 alone gives 0 to 40 by 20 and leaves a third of the chart empty.
Axis nice_axis(double lo, double hi, int max_ticks) {
  if (!(hi / 2 - lo / 2 > 0.0)) {  // a flat range still gets a visible axis
    const double pad = std::fabs(lo) < 1e-300 ? 1.0 : 0.5 * std::fabs(lo);
    lo = std::max(lo - pad, -DBL_MAX);  // near ±1.8e308 the padded range stays finite
    hi = std::min(hi + pad, DBL_MAX);
  }
  const int most = std::max(2, max_ticks);
  Axis best;
  double best_step = 0.0;
  std::vector<double> ticks;
  for (int n = 2; n <= most + 1; ++n) {
    double step = 0.0;
    if (!heckbert_ticks(lo, hi, n, ticks, step) || ticks.size() > static_cast<std::size_t>(most) + 1)
      continue;
    const double extent = ticks.back() - ticks.front();
    const double best_extent = best.ticks.empty() ? HUGE_VAL : best.hi - best.lo;
    if (extent < best_extent || (extent == best_extent && ticks.size() > best.ticks.size())) {
      best.ticks = ticks;
      best.lo = ticks.front();
      best.hi = ticks.back();
      best_step = step;
    }
  }
  if (best.ticks.empty()) return end_ticks(lo, hi);
  best.labels = tick_labels(best.ticks, best_step);
  return best;
}

namespace {
template <class Values>
Axis fit_axis(const Chart& chart, Values values, int max_ticks) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const Series& s : chart.series) {
    const std::vector<double>& v = values(s);
    if (v.empty()) continue;
    const auto [min, max] = std::minmax_element(v.begin(), v.end());
    lo = std::min(lo, *min);
    hi = std::max(hi, *max);
  }
  if (lo > hi) lo = hi = 0.0;  // no values: check_chart refuses such a chart
  return nice_axis(lo, hi, max_ticks);
}
}  // namespace

Axis x_axis(const Chart& chart, int max_ticks) {
  return fit_axis(chart, [](const Series& s) -> const std::vector<double>& { return s.x; },
                  max_ticks);
}

Axis y_axis(const Chart& chart, int max_ticks) {
  return fit_axis(chart, [](const Series& s) -> const std::vector<double>& { return s.y; },
                  max_ticks);
}

std::string short_number(double x) { return format("%.*g", 4, x); }

}  // namespace rigidlab::present
