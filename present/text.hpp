// Text that is safe to show: labels typed by users reach a terminal (where a control character
// moves the cursor or recolours the screen) and SVG files (where a control character or a
// broken UTF-8 sequence makes the document ill-formed XML, W3C XML 1.0 section 2.2 "Characters").
// Everything here counts and cuts by code points: every character rigidlab prints is one column.
#pragma once

#include <cstddef>
#include <string>

namespace rigidlab::present {

// The UTF-8 bytes of code point `code` (at most U+10FFFF).
std::string encode_utf8(char32_t code);

// `text` with every character a terminal or an XML reader would misread replaced: in Unicode
// mode, invalid UTF-8 (overlong forms, surrogates, truncated sequences) and control characters
// (C0, DEL, C1) become U+FFFD, tab, newline and carriage return a space; in ASCII mode every
// byte outside the printable range 0x20 to 0x7E becomes '?', one per code point.
std::string printable(const std::string& text, bool unicode);

// `text` as XML character data or attribute value: printable(text, true) with the
// non-characters U+FFFE and U+FFFF replaced too, and & < > " ' escaped.
std::string xml_text(const std::string& text);

// Columns `text` takes: its code points (text as printable returns it).
std::size_t display_width(const std::string& text);

// `text` cut to at most `width` columns, ending in "…" (or "." in ASCII mode) when it was cut.
std::string fit_width(const std::string& text, std::size_t width, bool unicode);

}  // namespace rigidlab::present
