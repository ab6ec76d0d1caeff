// Tests for present/filmstrip.cpp: the grid's geometry counted by hand (rows of boxes, each
// picture line between two borders, gaps of two columns), captions in the top border, cut
// when too long, ASCII mode without a byte above 127, and how many frames fit a width.
#include "present/filmstrip.hpp"

#include <gtest/gtest.h>

#include "present/text.hpp"
#include "tests/present/split_lines.hpp"

namespace rigidlab::present {
namespace {

using testing::split;

FilmFrame frame(const std::string& caption, char fill, int width, int height) {
  FilmFrame f{caption, {}};
  for (int y = 0; y < height; ++y) f.lines.emplace_back(static_cast<std::size_t>(width), fill);
  return f;
}

TEST(Filmstrip, FramesPerRowFromTheWidth) {
  // Boxes of 26 columns and gaps of 2: k boxes take 28k - 2 columns.
  EXPECT_EQ(frames_per_row(76, 4, 26, 2), 2);   // 54 fit, 82 do not
  EXPECT_EQ(frames_per_row(82, 4, 26, 2), 3);   // exactly 3
  EXPECT_EQ(frames_per_row(81, 4, 26, 2), 2);
  EXPECT_EQ(frames_per_row(500, 4, 26, 2), 4);  // never more than there are
  EXPECT_EQ(frames_per_row(10, 4, 26, 2), 1);   // never fewer than one
}

TEST(Filmstrip, BoxesInRowsWithTheirCaptions) {
  const std::vector<FilmFrame> frames = {frame("t = 0 s", 'a', 12, 3), frame("t = 1 s", 'b', 12, 3),
                                         frame("t = 2 s", 'c', 12, 3)};
  const std::vector<std::string> lines = split(filmstrip(frames, 12, 2, "  ", false));
  ASSERT_EQ(lines.size(), 10u);  // two rows of boxes of 3 + 2 lines
  EXPECT_EQ(lines[0], "  +- t = 0 s --+  +- t = 1 s --+");
  EXPECT_EQ(lines[1], "  |aaaaaaaaaaaa|  |bbbbbbbbbbbb|");
  EXPECT_EQ(lines[4], "  +------------+  +------------+");
  EXPECT_EQ(lines[5], "  +- t = 2 s --+");
  EXPECT_EQ(lines[8], "  |cccccccccccc|");
  EXPECT_EQ(lines[9], "  +------------+");
  for (const std::string& line : lines)
    for (const char c : line) EXPECT_LT(static_cast<unsigned char>(c), 128u) << line;
}

TEST(Filmstrip, UnicodeBoxesAreAsWideAsTheAsciiOnes) {
  const std::vector<FilmFrame> frames = {frame("a caption longer than the box", 'x', 10, 2),
                                         frame("", 'y', 10, 2)};
  const std::vector<std::string> lines = split(filmstrip(frames, 10, 2, "", true));
  ASSERT_EQ(lines.size(), 4u);
  for (const std::string& line : lines) EXPECT_EQ(display_width(line), 2 * 12 + 2u) << line;
  EXPECT_EQ(lines[0].rfind("┌", 0), 0u);
  EXPECT_NE(lines[0].find("…"), std::string::npos);  // the long caption was cut
  EXPECT_EQ(lines[3], "└──────────┘  └──────────┘");
}

}  // namespace
}  // namespace rigidlab::present
