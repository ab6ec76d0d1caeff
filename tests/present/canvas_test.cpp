// Tests for present/canvas.cpp: braille dot bits as the Unicode chart of U+2800 to U+28FF
// numbers them (dots 1-8), lines against the cells a straight line must cross, clipping of
// any coordinates, dash patterns by counting dots, ASCII output without a byte above 127.
#include "present/canvas.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rigidlab::present {
namespace {

std::string braille(int bits) {  // U+2800 + bits, encoded by hand
  const int code = 0x2800 + bits;
  return {char(0xE0 | (code >> 12)), char(0x80 | ((code >> 6) & 0x3F)), char(0x80 | (code & 0x3F))};
}

TEST(Canvas, BrailleDotsFollowTheUnicodeNumbering) {
  // Dots 1, 2, 3, 7 run down the left column (bits 0, 1, 2, 6); 4, 5, 6, 8 the right (3, 4, 5, 7).
  const int left[4] = {0x01, 0x02, 0x04, 0x40}, right[4] = {0x08, 0x10, 0x20, 0x80};
  for (int r = 0; r < 4; ++r) {
    Canvas a(1, 1, true), b(1, 1, true);
    a.dot(0, r, 1);
    b.dot(1, r, 1);
    EXPECT_EQ(a.lines()[0], braille(left[r]));
    EXPECT_EQ(b.lines()[0], braille(right[r]));
  }
  Canvas full(1, 1, true);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 2; ++x) full.dot(x, y, 1);
  EXPECT_EQ(full.lines()[0], braille(0xFF));
  EXPECT_EQ(Canvas(3, 1, true).lines()[0], "   ");
}

TEST(Canvas, LinesLightTheCellsTheyCross) {
  Canvas c(20, 10, true);
  c.line(0, 0, c.dots_x() - 1, c.dots_y() - 1, solid_stroke(1));  // the diagonal
  for (int column = 0; column < 20; ++column) {
    // The line from dot (0, 0) to (39, 39): the middle of cell column k is at dot x = 2k + 0.5,
    // where y = x, so in cell row y / 4.
    const double y = (2 * column + 0.5) * (c.dots_y() - 1.0) / (c.dots_x() - 1.0);
    const int row = static_cast<int>(y) / 4;
    EXPECT_TRUE(c.lit(column, row) || c.lit(column, row - 1) || c.lit(column, row + 1))
        << "column " << column;
  }
  int lit = 0;
  for (int row = 0; row < 10; ++row)
    for (int column = 0; column < 20; ++column) lit += c.lit(column, row);
  EXPECT_LE(lit, 20 + 10);  // a thin line, not a smear
}

TEST(Canvas, ClipsAnyCoordinatesAndIgnoresNonFinite) {
  Canvas c(10, 5, true);
  c.line(-1e6, -1e6, 1e6, 1e6, solid_stroke(1));  // through the canvas corner to corner
  EXPECT_TRUE(c.lit(0, 0));
  EXPECT_TRUE(c.lit(9, 4));
  c.line(-1e300, 3e300, 1e300, -1e300, solid_stroke(1));  // rounds, but stays on the canvas
  Canvas d(10, 5, true);
  d.line(-5, 2, -1, 30, solid_stroke(1));  // wholly outside
  d.line(NAN, 0, 5, 5, solid_stroke(1));
  d.line(0, 0, INFINITY, 5, solid_stroke(1));
  for (int row = 0; row < 5; ++row)
    for (int column = 0; column < 10; ++column) EXPECT_FALSE(d.lit(column, row));
}

int dots_on_row(const Canvas& c, int dot_row) {
  int n = 0;
  const std::string row = c.lines()[dot_row / 4];
  // Each cell is 3 bytes; bit of dot (x % 2, dot_row % 4).
  const int left[4] = {0x01, 0x02, 0x04, 0x40}, right[4] = {0x08, 0x10, 0x20, 0x80};
  for (std::size_t i = 0; i < row.size();) {
    if (row[i] == ' ') {  // a blank cell is one byte
      ++i;
      continue;
    }
    const int code = ((row[i] & 0x0F) << 12) | ((row[i + 1] & 0x3F) << 6) | (row[i + 2] & 0x3F);
    const int bits = code - 0x2800;
    n += (bits & left[dot_row % 4]) != 0;
    n += (bits & right[dot_row % 4]) != 0;
    i += 3;
  }
  return n;
}

TEST(Canvas, DashPatternsLeaveGaps) {
  const int counts_expected[4] = {60, 40, 30, 30};  // of 60 dots: all, 4 of 6, 1 of 2, 5 of 10
  for (int p = 0; p < 4; ++p) {
    Canvas c(30, 1, true);
    c.line(0, 0, 59, 0, patterned_stroke(1, p, true));
    EXPECT_EQ(dots_on_row(c, 0), counts_expected[p]) << "pattern " << p;
  }
  const char* const ascii[4] = {"------------", "-- -- -- -- ", "- - - - - - ", "--- - --- - "};
  for (int p = 0; p < 4; ++p) {
    Canvas c(12, 1, false);
    c.line(0, 0, 11, 0, patterned_stroke(1, p, false));
    EXPECT_EQ(c.lines()[0], ascii[p]) << "pattern " << p;
  }
}

TEST(Canvas, AsciiGlyphsFollowTheSlopeAndStayAscii) {
  Canvas c(20, 10, false);
  c.line(0, 0, 19, 0, solid_stroke(1));   // horizontal
  c.line(0, 2, 0, 9, solid_stroke(1));    // vertical
  c.line(5, 2, 11, 5, solid_stroke(1));   // down-right: 6 across, 3 down of cells twice as tall
  c.line(12, 9, 18, 6, solid_stroke(1));  // up-right
  const auto lines = c.lines();
  EXPECT_EQ(lines[0], std::string(20, '-'));
  EXPECT_EQ(lines[5][0], '|');
  EXPECT_EQ(lines[3][7], '\\');
  EXPECT_EQ(lines[8][14], '/');
  Stroke marked = solid_stroke(2);
  marked.glyph = '+';
  c.line(2, 7, 8, 7, marked);
  EXPECT_EQ(c.lines()[7].substr(2, 7), "+++++++");
  for (const std::string& line : c.lines())
    for (char ch : line) EXPECT_TRUE(ch >= 0x20 && ch <= 0x7E);
}

TEST(Canvas, ColoursChangeOnlyWhereTheInkDoes) {
  Canvas c(4, 1, false);
  c.dot(0, 0, 1);
  c.dot(1, 0, 1);
  c.dot(3, 0, 2);
  std::vector<std::string> palette(3);
  palette[1] = "<1>";
  palette[2] = "<2>";
  EXPECT_EQ(c.lines(palette)[0], "<1>** <2>*\x1b[0m");
  EXPECT_EQ(c.lines()[0], "** *");
}

TEST(Canvas, TextOverlaysReplaceCellsAndClip) {
  Canvas c(5, 2, true);
  c.line(0, 0, 9, 0, solid_stroke(1));
  c.text(3, 0, "ωxyz", 2);
  c.text(-1, 1, "ab", 2);
  EXPECT_EQ(c.lines()[0], braille(0x09) + braille(0x09) + braille(0x09) + "ωx");
  EXPECT_EQ(c.lines()[1], "b    ");
  EXPECT_EQ(c.cell_ink(3, 0), 2);
  EXPECT_EQ(c.cell_ink(0, 0), 1);
}

TEST(Canvas, ACellShowsTheInkWithMostDots) {
  Canvas c(1, 1, true);
  c.dot(0, 0, 1);
  c.dot(0, 1, 1);
  c.dot(1, 0, 2);
  EXPECT_EQ(c.cell_ink(0, 0), 1);
  c.dot(1, 1, 2);
  EXPECT_EQ(c.cell_ink(0, 0), 2);  // a tie goes to the higher ink
}

}  // namespace
}  // namespace rigidlab::present
