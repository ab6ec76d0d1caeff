// Tests for present/text.cpp: UTF-8 encoding against the bytes of RFC 3629's examples and the
// Unicode code charts, and the replacement of what a terminal or an XML reader would misread.
#include "present/text.hpp"

#include <gtest/gtest.h>

namespace rigidlab::present {
namespace {

TEST(Text, EncodesCodePointsAsRfc3629) {
  EXPECT_EQ(encode_utf8(U'A'), "A");
  EXPECT_EQ(encode_utf8(0xE9), "\xC3\xA9");              // é
  EXPECT_EQ(encode_utf8(0x20AC), "\xE2\x82\xAC");        // €
  EXPECT_EQ(encode_utf8(0x2800), "\xE2\xA0\x80");        // the empty braille pattern
  EXPECT_EQ(encode_utf8(0x1F600), "\xF0\x9F\x98\x80");   // an emoji, four bytes
}

TEST(Text, ReplacesControlCharactersAndBrokenUtf8) {
  const std::string fffd = "\xEF\xBF\xBD";
  EXPECT_EQ(printable("a\x1b[2Jb", true), "a" + fffd + "[2Jb");
  EXPECT_EQ(printable("tab\there\nnew", true), "tab here new");
  EXPECT_EQ(printable("\x7f", true), fffd);
  EXPECT_EQ(printable("\xC2\x85", true), fffd);              // C1 control NEL
  EXPECT_EQ(printable("x\xC3", true), "x" + fffd);           // truncated sequence
  EXPECT_EQ(printable("\xC0\xAF", true), fffd + fffd);       // overlong '/'
  EXPECT_EQ(printable("\xED\xA0\x80", true), fffd + fffd + fffd);  // a surrogate
  EXPECT_EQ(printable("\xF4\x90\x80\x80", true), fffd + fffd + fffd + fffd);  // > U+10FFFF
  EXPECT_EQ(printable("ω² ✓", true), "ω² ✓");
  EXPECT_EQ(printable(std::string("a\0b", 3), true), "a" + fffd + "b");
}

TEST(Text, AsciiModeKeepsOnlyPrintableAscii) {
  EXPECT_EQ(printable("ω = 2\x1b!", false), "? = 2?!");
  EXPECT_EQ(printable("\xC3", false), "?");
  for (char c : printable("\xF0\x9F\x98\x80 ok \xFF\x01", false))
    EXPECT_TRUE(c >= 0x20 && c <= 0x7E) << int(c);
}

TEST(Text, XmlTextEscapesMarkupAndNonCharacters) {
  EXPECT_EQ(xml_text("<a & 'b' \"c\">"), "&lt;a &amp; &apos;b&apos; &quot;c&quot;&gt;");
  EXPECT_EQ(xml_text("\xEF\xBF\xBE"), "\xEF\xBF\xBD");  // U+FFFE is not an XML Char
  EXPECT_EQ(xml_text("\x01"), "\xEF\xBF\xBD");
}

TEST(Text, WidthsCountCodePoints) {
  EXPECT_EQ(display_width("ω²"), 2u);
  EXPECT_EQ(display_width(""), 0u);
  EXPECT_EQ(fit_width("abcdef", 4, true), "abc…");
  EXPECT_EQ(fit_width("abcdef", 4, false), "abc.");
  EXPECT_EQ(fit_width("ωωωωω", 3, true), "ωω…");
  EXPECT_EQ(fit_width("abc", 3, true), "abc");
}

}  // namespace
}  // namespace rigidlab::present
