#include "present/text.hpp"

namespace rigidlab::present {
namespace {

constexpr char32_t replacement = 0xFFFD;
constexpr char32_t invalid = 0xFFFFFFFF;

// Decodes the code point starting at text[i] and advances i past it. A malformed sequence
// (RFC 3629 section 4: no overlong forms, no surrogates, nothing above U+10FFFF) consumes one
// byte and returns `invalid`, so the next byte is tried as a new start.
char32_t next_code_point(const std::string& text, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char first = byte(i);
  if (first < 0x80) return text[i++];
  int length = first >= 0xF0 ? 4 : first >= 0xE0 ? 3 : first >= 0xC0 ? 2 : 0;
  if (length == 0 || first > 0xF4 || i + length > text.size()) {
    ++i;
    return invalid;
  }
  char32_t code = first & (0x7F >> length);
  for (int k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) {
      ++i;
      return invalid;
    }
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  static const char32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
    ++i;
    return invalid;
  }
  i += length;
  return code;
}

bool is_control(char32_t code) { return code < 0x20 || (code >= 0x7F && code <= 0x9F); }

}  // namespace

std::string encode_utf8(char32_t code) {
  std::string out;
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  return out;
}

std::string printable(const std::string& text, bool unicode) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t start = i;
    const char32_t code = next_code_point(text, i);
    if (code == '\t' || code == '\n' || code == '\r')
      out += ' ';
    else if (code == invalid || is_control(code))
      out += unicode ? encode_utf8(replacement) : "?";
    else if (!unicode && code >= 0x80)
      out += '?';
    else
      out.append(text, start, i - start);
  }
  return out;
}

std::string xml_text(const std::string& text) {
  const std::string clean = printable(text, true);
  std::string out;
  out.reserve(clean.size());
  for (std::size_t i = 0; i < clean.size();) {
    const std::size_t start = i;
    switch (next_code_point(clean, i)) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case 0xFFFE:
      case 0xFFFF: out += encode_utf8(replacement); break;
      default: out.append(clean, start, i - start);
    }
  }
  return out;
}

std::size_t display_width(const std::string& text) {
  std::size_t columns = 0;
  for (char c : text) columns += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return columns;
}

std::string fit_width(const std::string& text, std::size_t width, bool unicode) {
  if (display_width(text) <= width) return text;
  if (width == 0) return "";
  std::string out;
  std::size_t columns = 0;
  for (std::size_t i = 0; i < text.size() && columns + 1 < width; ++columns) {
    const std::size_t start = i;
    next_code_point(text, i);
    out.append(text, start, i - start);
  }
  return out + (unicode ? "…" : ".");
}

}  // namespace rigidlab::present
