// Lua's lexical names (manual §3.1), for the REPL's completion and printing.
#pragma once

#include <cstddef>

namespace rigidlab::cli {

// Lua's reserved words, in alphabetical order.
extern const char* const lua_keywords[22];

// Whether text[0..length) is a name: letters, digits and '_', not starting with a digit (a
// keyword is a name too: see is_keyword).
bool is_name(const char* text, std::size_t length);
bool is_keyword(const char* text, std::size_t length);

}  // namespace rigidlab::cli
