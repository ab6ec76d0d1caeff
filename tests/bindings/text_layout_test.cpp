// Text laid out in columns (lua/text_layout): widths count code points, lines never pass the
// width (a word wider than a line of 8 or more columns is broken), and cut text ends in "…" at a code point boundary.
#include "lua/text_layout.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace rigidlab::lua {
namespace {

size_t widest_line(const std::string& text) {
  std::istringstream lines(text);
  size_t widest = 0;
  for (std::string line; std::getline(lines, line);) widest = std::max(widest, display_width(line));
  return widest;
}

TEST(TextLayout, WidthCountsCodePointsNotBytes) {
  EXPECT_EQ(display_width(""), 0u);
  EXPECT_EQ(display_width("abc"), 3u);
  EXPECT_EQ(display_width("ω²✓—"), 4u);  // 2 + 2 + 3 + 3 bytes
}

TEST(TextLayout, FitWordsBreaksBetweenWordsWithinTheWidth) {
  EXPECT_EQ(fit_words("aaa bbb ccc", "  ", 9), "  aaa bbb\n  ccc\n");
  EXPECT_EQ(fit_words("ωωω ωωω ωωω", "", 7), "ωωω ωωω\nωωω\n");  // counted in columns
  EXPECT_EQ(fit_words("tiny enormousword", "", 6), "tiny\nenormousword\n");  // never split
  const std::string text =
      "The centre of mass is where a body would balance on a pin: the average of its particles.";
  for (size_t width = 20; width <= 60; ++width) {
    const std::string fitted = fit_words(text, "  ", width);
    EXPECT_LE(widest_line(fitted), width);
    std::istringstream a(text), b(fitted);  // the same words in the same order
    for (std::string x, y; a >> x;) {
      ASSERT_TRUE(b >> y);
      EXPECT_EQ(x, y);
    }
  }
}

TEST(TextLayout, AWordWiderThanTheLineBreaksAfterASlashOrAtACodePoint) {
  // A path breaks between folders when that keeps half the line or more.
  EXPECT_EQ(fit_words("from /home/student/lessons/mine/x.lua", "", 16),
            "from\n/home/student/\nlessons/mine/\nx.lua\n");
  // No slash late enough: cut at the width, counting code points (ω is 2 bytes).
  EXPECT_EQ(fit_words("ωωωωωωωωωωωω", "  ", 10), "  ωωωωωωωω\n  ωωωω\n");
  EXPECT_EQ(fit_words_after("from: ", "/tmp/a-very-long-folder", 16), "from: /tmp/\n      a-very-lon\n      g-folder\n");
}

TEST(TextLayout, HangingLinesLineUpUnderTheFirst) {
  EXPECT_EQ(fit_words_after("  source: ", "one two three", 18),
            "  source: one two\n          three\n");
  EXPECT_EQ(fit_words_after("id — ", "a b", 40), "id — a b\n");
}

TEST(TextLayout, ParagraphsKeepBlankLinesAndIndentedLines) {
  EXPECT_EQ(fit_paragraphs("a b\nc\n\n  F = m a\nd", "  ", 80), "  a b c\n\n    F = m a\n  d\n");
}

TEST(TextLayout, TruncateEndsInAnEllipsisAtACodePoint) {
  EXPECT_EQ(truncate_to_width("short", 5), "short");
  EXPECT_EQ(truncate_to_width("shorter", 5), "shor…");
  EXPECT_EQ(truncate_to_width("ab cd", 4), "ab…");  // no space before the ellipsis
  EXPECT_EQ(truncate_to_width("ωωωωω", 3), "ωω…");
  EXPECT_EQ(display_width(truncate_to_width("ωωωωω", 3)), 3u);
  EXPECT_EQ(truncate_to_width("abc", 0), "");
}

}  // namespace
}  // namespace rigidlab::lua
