#include "cli/lua_names.hpp"

#include <cctype>
#include <cstring>

namespace rigidlab::cli {

const char* const lua_keywords[22] = {"and",   "break", "do",       "else", "elseif", "end",
                                      "false", "for",   "function", "goto", "if",     "in",
                                      "local", "nil",   "not",      "or",   "repeat", "return",
                                      "then",  "true",  "until",    "while"};

bool is_name(const char* text, std::size_t length) {
  if (length == 0 || std::isdigit(static_cast<unsigned char>(text[0]))) return false;
  for (std::size_t i = 0; i < length; ++i)
    if (!(std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) return false;
  return true;
}

bool is_keyword(const char* text, std::size_t length) {
  for (const char* keyword : lua_keywords)
    if (std::strlen(keyword) == length && std::memcmp(keyword, text, length) == 0) return true;
  return false;
}

}  // namespace rigidlab::cli
