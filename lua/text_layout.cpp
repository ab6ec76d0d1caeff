#include "lua/text_layout.hpp"

#include <algorithm>
#include <sstream>

namespace rigidlab::lua {

namespace {
bool starts_code_point(unsigned char byte) { return (byte & 0xC0) != 0x80; }
}  // namespace

std::size_t display_width(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(
      text.begin(), text.end(), [](unsigned char c) { return starts_code_point(c); }));
}

std::string fit_words(const std::string& text, const std::string& indent, std::size_t width) {
  std::string out, line;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
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

}  // namespace rigidlab::lua
