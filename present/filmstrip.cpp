#include "present/filmstrip.hpp"

#include <algorithm>

#include "present/text.hpp"

namespace rigidlab::present {
namespace {

struct BoxGlyphs {
  const char *top_left, *top_right, *bottom_left, *bottom_right, *across, *down;
};
constexpr BoxGlyphs unicode_box{"┌", "┐", "└", "┘", "─", "│"};
constexpr BoxGlyphs ascii_box{"+", "+", "+", "+", "-", "|"};

std::string repeat(const char* glyph, int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += glyph;
  return out;
}

// "┌ caption ───┐" of `width` columns inside the corners.
std::string top_border(const std::string& caption, int width, const BoxGlyphs& g, bool unicode) {
  std::string label = caption.empty() ? "" : " " + caption + " ";
  if (static_cast<int>(display_width(label)) > width)
    label = fit_width(label, static_cast<std::size_t>(std::max(width, 0)), unicode);
  const int rest = width - static_cast<int>(display_width(label));
  return g.top_left + repeat(g.across, std::min(1, rest)) + label +
         repeat(g.across, rest - std::min(1, rest)) + g.top_right;
}

}  // namespace

int frames_per_row(int columns, int count, int min_width, int gap) {
  const int fit = (columns + gap) / std::max(1, min_width + gap);
  return std::max(1, std::min(count, fit));
}

std::string filmstrip(const std::vector<FilmFrame>& frames, int width, int per_row,
                      const std::string& indent, bool unicode) {
  const BoxGlyphs& g = unicode ? unicode_box : ascii_box;
  const std::string gap(filmstrip_gap, ' ');
  const std::size_t height = frames.empty() ? 0 : frames.front().lines.size();
  const std::string blank(static_cast<std::size_t>(width), ' ');
  std::string out;
  per_row = std::max(per_row, 1);
  for (std::size_t first = 0; first < frames.size(); first += static_cast<std::size_t>(per_row)) {
    const std::size_t last = std::min(frames.size(), first + static_cast<std::size_t>(per_row));
    auto row = [&](auto piece) {
      std::string line = indent;
      for (std::size_t k = first; k < last; ++k) line += (k > first ? gap : "") + piece(frames[k]);
      out += line + "\n";
    };
    row([&](const FilmFrame& f) { return top_border(f.caption, width, g, unicode); });
    for (std::size_t y = 0; y < height; ++y)
      row([&](const FilmFrame& f) {
        return g.down + (y < f.lines.size() ? f.lines[y] : blank) + g.down;
      });
    row([&](const FilmFrame&) { return g.bottom_left + repeat(g.across, width) + g.bottom_right; });
  }
  return out;
}

}  // namespace rigidlab::present
