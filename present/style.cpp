#include "present/style.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <string>

namespace rigidlab::present {

bool utf8_locale() {
  for (const char* name : {"LC_ALL", "LC_CTYPE", "LANG"}) {
    const char* value = std::getenv(name);
    if (value == nullptr || *value == '\0') continue;
    std::string v = value;
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return v.find("utf-8") != std::string::npos || v.find("utf8") != std::string::npos;
  }
  return false;
}

TextStyle terminal_style(int fd) {
  TextStyle style;
  style.unicode = utf8_locale();
  const char* no_color = std::getenv("NO_COLOR");
  const char* term = std::getenv("TERM");
  style.color = isatty(fd) != 0 && (no_color == nullptr || *no_color == '\0') &&
                !(term != nullptr && std::strcmp(term, "dumb") == 0);
  return style;
}

}  // namespace rigidlab::present
