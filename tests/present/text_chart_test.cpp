// Tests for present/text_chart.cpp: the chart's cells against the line y = x computed here,
// ticks at round numbers on the rows and columns where they belong, series told apart
// without colour, and labels that cannot reach the terminal as control characters.
#include "present/text_chart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "tests/present/split_lines.hpp"

namespace rigidlab::present {
namespace {

using testing::split;

// The code points of a line (the chart's cells are one code point each).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < line.size();) {
    std::size_t end = i + 1;
    while (end < line.size() && (static_cast<unsigned char>(line[end]) & 0xC0) == 0x80) ++end;
    out.push_back(line.substr(i, end - i));
    i = end;
  }
  return out;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

Chart diagonal() {
  Chart chart;
  Series s;
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i / 100.0);
    s.y.push_back(i / 100.0);
  }
  s.label = "y = x";
  chart.series.push_back(s);
  return chart;
}

TEST(TextChart, TheLineLightsTheCellsOfYEqualsX) {
  TextChartOptions options;
  options.width = 40;
  options.height = 10;
  const auto lines = split(text_chart(diagonal(), options));
  ASSERT_EQ(lines.size(), 10u + 3);  // rows, axis, x labels, legend
  // The axes run 0 to 1 (round already): cell column c holds x from c/40 to (c+1)/40, so
  // its y = x lies in cell row floor((1 - x) * 10) from the top, within one cell.
  for (int c = 0; c < 40; ++c) {
    const double x = (c + 0.5) / 40;
    const int expected = std::min(9, static_cast<int>((1 - x) * 10));
    bool found = false;
    for (int r = std::max(0, expected - 1); r <= std::min(9, expected + 1); ++r) {
      const auto row = cells(lines[r]);
      const std::string& cell = row[row.size() - 40 + c];
      found = found || cell != " ";
    }
    EXPECT_TRUE(found) << "column " << c;
  }
}

TEST(TextChart, TicksAreRoundAndOnTheirRows) {
  Chart chart;
  chart.series.push_back(Series{{0, 10}, {-1, 3}, "a"});
  TextChartOptions options;
  options.width = 50;
  options.height = 9;  // 36 dot rows: the ticks -1 .. 3 fall on dot rows 0, 9, 17.5, 26, 35
  const auto lines = split(text_chart(chart, options));
  EXPECT_EQ(lines[0].substr(0, 6), " 3 ┤");
  EXPECT_EQ(lines[8].substr(0, 6), "-1 ┤");
  int labelled = 0;
  for (int r = 0; r < 9; ++r) labelled += lines[r].find("┤") != std::string::npos;
  EXPECT_EQ(labelled, 5);
  // x from 0 to 10 in 50 columns (about 8 labels fit): 0, 2, ..., 10 under '┬' marks.
  const std::string& axis = lines[9];
  const std::string& xlabels = lines[10];
  EXPECT_NE(axis.find("└┬"), std::string::npos);
  std::istringstream in(xlabels);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  EXPECT_EQ(words, (std::vector<std::string>{"0", "2", "4", "6", "8", "10"}));
  EXPECT_EQ(count(axis, "┬"), 6);
}

Chart two_series() {
  Chart chart;
  Series a, b;
  for (int i = 0; i <= 60; ++i) {
    a.x.push_back(i);
    a.y.push_back(std::sin(i / 10.0));
    b.x.push_back(i);
    b.y.push_back(std::cos(i / 10.0));
  }
  a.label = "sin";
  b.label = "cos";
  chart.series = {a, b};
  return chart;
}

TEST(TextChart, WithoutColourEachSeriesHasItsGlyph) {
  TextChartOptions options;
  options.style = TextStyle{true, false};
  const std::string text = text_chart(two_series(), options);
  const auto lines = split(text);
  EXPECT_NE(lines.back().find("─*─ sin"), std::string::npos);
  EXPECT_NE(lines.back().find("─+─ cos"), std::string::npos);
  std::string plot;
  for (int r = 0; r < 15; ++r) plot += lines[r];
  EXPECT_GE(count(plot, "*"), 3);  // marks along each line, not only one
  EXPECT_GE(count(plot, "+"), 3);
  EXPECT_EQ(text.find("\x1b"), std::string::npos);
}

TEST(TextChart, WithColourSeriesAreColouredNotMarked) {
  TextChartOptions options;
  options.style = TextStyle{true, true};
  const std::string text = text_chart(two_series(), options);
  EXPECT_NE(text.find("\x1b[34m"), std::string::npos);
  EXPECT_NE(text.find("\x1b[31m"), std::string::npos);
  EXPECT_EQ(count(text, "*"), 0);
}

TEST(TextChart, AsciiIsAsciiWithAGlyphPerSeries) {
  TextChartOptions options;
  options.style = TextStyle{false, false};
  Chart chart = two_series();
  chart.title = "ω and \xCE";  // non-ASCII and broken UTF-8 in a label
  const std::string text = text_chart(chart, options);
  for (char c : text) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c <= 0x7E)) << int(c);
  EXPECT_GE(count(text, "*"), 20);
  EXPECT_GE(count(text, "+"), 20);
  EXPECT_NE(text.find("* sin"), std::string::npos);
  EXPECT_NE(text.find("+ cos"), std::string::npos);
}

TEST(TextChart, LabelsCannotControlTheTerminal) {
  Chart chart = diagonal();
  chart.title = "\x1b[2J\x1b]0;owned\x07";
  chart.series[0].label = "a\rb\x9b";
  const std::string text = text_chart(chart, TextChartOptions{});
  EXPECT_EQ(text.find('\x1b'), std::string::npos);
  EXPECT_EQ(text.find('\x07'), std::string::npos);
  EXPECT_EQ(text.find('\r'), std::string::npos);
}

TEST(TextChart, ALongLegendWraps) {
  Chart chart;
  for (int s = 0; s < 6; ++s)
    chart.series.push_back(Series{{0, 1}, {0, double(s)}, "a rather long label " + std::to_string(s)});
  TextChartOptions options;
  options.width = 30;
  const auto lines = split(text_chart(chart, options));
  for (const std::string& line : lines) EXPECT_LE(cells(line).size(), 30u + 4) << line;
}

}  // namespace
}  // namespace rigidlab::present
