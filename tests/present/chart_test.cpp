// Tests for present/chart.cpp: round-number axes checked by their defining properties (ticks
// are consecutive multiples of 1, 2 or 5 times a power of ten, covering the data, labels that
// read back as the ticks), on hand-worked ranges and on random ones.
#include "present/chart.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <random>
#include <set>

namespace rigidlab::present {
namespace {

TEST(NiceAxis, HandWorkedRanges) {
  // Heckbert's example shape: -1 to 3 with 5 ticks: a step of 1.
  Axis a = nice_axis(-1, 3, 5);
  EXPECT_EQ(a.labels, (std::vector<std::string>{"-1", "0", "1", "2", "3"}));
  // 0.13 to 2.87: range rounds up to 5, step 5/4 rounds to 1; the ends widen to 0 and 3.
  a = nice_axis(0.13, 2.87, 5);
  EXPECT_EQ(a.labels, (std::vector<std::string>{"0", "1", "2", "3"}));
  EXPECT_EQ(a.lo, 0.0);
  EXPECT_EQ(a.hi, 3.0);
  // Tenths print with one decimal, and 3 * 0.1 reads 0.3, not 0.30000000000000004.
  a = nice_axis(0, 0.3, 5);
  EXPECT_EQ(a.labels, (std::vector<std::string>{"0.0", "0.1", "0.2", "0.3"}));
  // A step of 2000 in the thousands.
  a = nice_axis(0, 9000, 6);
  EXPECT_EQ(a.labels, (std::vector<std::string>{"0", "2000", "4000", "6000", "8000", "10000"}));
}

// The properties every axis must have, whatever the data.
void expect_nice(double lo, double hi, int n) {
  SCOPED_TRACE(testing::Message() << "data " << lo << " .. " << hi << ", " << n << " ticks");
  const Axis a = nice_axis(lo, hi, n);
  ASSERT_GE(a.ticks.size(), 2u);
  ASSERT_EQ(a.ticks.size(), a.labels.size());
  EXPECT_LE(a.lo, lo);
  EXPECT_GE(a.hi, hi);
  EXPECT_EQ(a.ticks.front(), a.lo);
  EXPECT_EQ(a.ticks.back(), a.hi);
  EXPECT_LE(a.ticks.size(), 2u * n + 1);
  const double step = a.ticks[1] - a.ticks[0];
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  EXPECT_TRUE(std::fabs(mantissa - 1) < 1e-9 || std::fabs(mantissa - 2) < 1e-9 ||
              std::fabs(mantissa - 5) < 1e-9 || std::fabs(mantissa - 10) < 1e-9)
      << "step " << step;
  std::set<std::string> distinct(a.labels.begin(), a.labels.end());
  EXPECT_EQ(distinct.size(), a.labels.size());
  for (std::size_t i = 0; i < a.ticks.size(); ++i) {
    EXPECT_NEAR(std::strtod(a.labels[i].c_str(), nullptr), a.ticks[i], 1e-9 * step)
        << a.labels[i];
    // Each tick is a whole multiple of the step.
    EXPECT_NEAR(a.ticks[i] / step, std::round(a.ticks[i] / step), 1e-6);
  }
}

TEST(NiceAxis, RandomRangesAreRound) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), e(-8, 8);
  for (int i = 0; i < 2000; ++i) {
    const double scale = std::pow(10.0, e(rng));
    double lo = u(rng) * scale, hi = lo + std::fabs(u(rng)) * scale * std::pow(10.0, e(rng) / 4);
    if (!(hi > lo)) continue;
    expect_nice(lo, hi, 2 + i % 9);
  }
}

TEST(NiceAxis, DegenerateRangesStayFiniteAndLabelled) {
  const double cases[][2] = {{2, 2}, {0, 0}, {-1.7e308, 1.7e308}, {1.7e308, 1.7e308},
                             {5e-324, 5e-324}, {0, 5e-324}, {1, 1 + 2.3e-16}, {-DBL_MAX, DBL_MAX}};
  for (const auto& c : cases) {
    SCOPED_TRACE(testing::Message() << c[0] << " .. " << c[1]);
    const Axis a = nice_axis(c[0], c[1], 5);
    ASSERT_GE(a.ticks.size(), 2u);
    EXPECT_TRUE(std::isfinite(a.lo) && std::isfinite(a.hi));
    EXPECT_LT(a.lo, a.hi);
    EXPECT_LE(a.lo, c[0]);
    EXPECT_GE(a.hi, c[1]);
    std::set<std::string> distinct(a.labels.begin(), a.labels.end());
    EXPECT_EQ(distinct.size(), a.labels.size());
    for (double v : {c[0], c[1], a.lo, a.hi}) {
      const double f = a.fraction(v);
      EXPECT_TRUE(f >= 0 && f <= 1) << f;
    }
    EXPECT_EQ(a.fraction(a.lo), 0.0);
    EXPECT_EQ(a.fraction(a.hi), 1.0);
  }
}

TEST(Chart, CheckRefusesWhatCannotBeDrawn) {
  Chart chart;
  EXPECT_THROW(check_chart(chart), std::invalid_argument);
  chart.series.push_back(Series{{1, 2}, {1}, "ragged"});
  EXPECT_THROW(check_chart(chart), std::invalid_argument);
  chart.series[0] = Series{{1, 2}, {1, NAN}, "nan"};
  EXPECT_THROW(check_chart(chart), std::invalid_argument);
  chart.series[0] = Series{{1, 2}, {1, 2}, "fine"};
  EXPECT_NO_THROW(check_chart(chart));
}

}  // namespace
}  // namespace rigidlab::present
