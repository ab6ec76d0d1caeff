#include "lua/text_layout.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace rigidlab::lua {

namespace {
bool starts_code_point(unsigned char byte) { return (byte & 0xC0) != 0x80; }
}  // namespace

std::size_t display_width(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(
      text.begin(), text.end(), [](unsigned char c) { return starts_code_point(c); }));
}

namespace {
// Byte length of the longest head of `word` at most `columns` wide, cut after its last '/'
// when that keeps at least half the line (a path breaks between its folders), else at a code
// point.
std::size_t head_that_fits(const std::string& word, std::size_t columns) {
  std::size_t end = 0, seen = 0, after_slash = 0;
  while (end < word.size()) {
    std::size_t next = end + 1;
    while (next < word.size() && !starts_code_point(static_cast<unsigned char>(word[next]))) ++next;
    if (++seen > columns) break;
    end = next;
    if (word[end - 1] == '/') after_slash = end;
  }
  return after_slash >= columns / 2 ? after_slash : std::max<std::size_t>(end, 1);
}
}  // namespace

std::string fit_words(const std::string& text, const std::string& indent, std::size_t width) {
  std::string out, line;
  std::istringstream words(text);
  // A word wider than a whole line (a long path) is broken so that no line overflows; below
  // 8 usable columns it is left whole rather than cut into pieces nobody can read.
  const std::size_t usable = width > display_width(indent) ? width - display_width(indent) : 0;
  for (std::string word; words >> word;) {
    while (usable >= 8 && display_width(word) > usable) {
      if (!line.empty()) out += indent + line + "\n";
      line.clear();
      const std::size_t head = head_that_fits(word, usable);
      out += indent + word.substr(0, head) + "\n";
      word.erase(0, head);
    }
    if (!line.empty() && display_width(indent + line + " " + word) > width) {
      out += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + indent + line + "\n";
}

std::string fit_words_after(const std::string& prefix, const std::string& text, std::size_t width) {
  const std::string indent(display_width(prefix), ' ');
  return prefix + fit_words(text, indent, width).substr(indent.size());
}

std::string fit_paragraphs(const std::string& text, const std::string& indent, std::size_t width) {
  std::string out, paragraph;
  auto flush = [&] {
    if (paragraph.find_first_not_of(' ') != std::string::npos)
      out += fit_words(paragraph, indent, width);
    paragraph.clear();
  };
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(" \t") == std::string::npos) {
      flush();
      out += "\n";
    } else if (line[0] == ' ') {
      flush();
      out += indent + line + "\n";
    } else {
      paragraph += " " + line;
    }
  }
  flush();
  return out;
}

std::string truncate_to_width(const std::string& text, std::size_t width) {
  if (display_width(text) <= width) return text;
  if (width == 0) return "";
  std::size_t columns = 0, end = 0;
  for (; end < text.size(); ++end) {
    if (starts_code_point(static_cast<unsigned char>(text[end])) && columns++ == width - 1) break;
  }
  std::string cut = text.substr(0, end);
  while (!cut.empty() && cut.back() == ' ') cut.pop_back();
  return cut + "…";
}

std::string quoted(const char* text, std::size_t length, std::size_t max_bytes) {
  std::string out = "\"";
  const std::size_t shown = std::min(length, max_bytes);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\%d", c);
      out += escape;
    } else {
      out += static_cast<char>(c);
    }
  }
  out += '"';
  if (shown < length) out += "… (" + std::to_string(length) + " bytes)";
  return out;
}

}  // namespace rigidlab::lua
