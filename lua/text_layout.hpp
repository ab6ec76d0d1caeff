// Laying text out in a terminal's columns: what lessons print (ctx:say, the step texts, the
// lesson list) fits the width of the terminal they are read in. Widths count code points, not
// bytes, so labels with ω, ², ✓ or — line up (every character rigidlab prints is one column).
#pragma once

#include <cstddef>
#include <string>

namespace rigidlab::lua {

// Columns `text` takes: its UTF-8 code points.
std::size_t display_width(const std::string& text);

// The words of `text` on lines of at most `width` columns, each line starting with `indent`
// and ending in "\n". A word longer than the line gets a line of its own (never split).
std::string fit_words(const std::string& text, const std::string& indent, std::size_t width);

// fit_words with a hanging first line: the first line starts with `prefix` ("  source: "),
// the others with as many spaces as it is wide, so the text lines up under itself.
std::string fit_words_after(const std::string& prefix, const std::string& text, std::size_t width);

// fit_words for each paragraph of `text`: blank lines separate paragraphs, and a line that
// starts with a space (a formula, a list) is kept as it is, after `indent`.
std::string fit_paragraphs(const std::string& text, const std::string& indent, std::size_t width);

// `text` cut to at most `width` columns, ending in "…" when it was cut (at a code point).
std::string truncate_to_width(const std::string& text, std::size_t width);

// `length` bytes of `text` as a Lua string literal: in double quotes, with \" \\ \n \t and
// \ddd for the other control bytes, so a trailing space or a newline is visible; UTF-8 passes
// as it is. Past `max_bytes` the literal is cut and "… (N bytes)" follows it.
std::string quoted(const char* text, std::size_t length,
                   std::size_t max_bytes = static_cast<std::size_t>(-1));

}  // namespace rigidlab::lua
