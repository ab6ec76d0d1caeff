#include "present/canvas.hpp"

#include <algorithm>
#include <cmath>

#include "present/text.hpp"

namespace rigidlab::present {
namespace {

// Liang and Barsky's parametric clipping ("A New Concept and Method for Line Clipping", ACM
// TOG 3(1), 1984) of the segment p0 + t (p1 - p0), t in [0, 1], to [lo_x, hi_x] x [lo_y, hi_y].
// False when nothing is left.
bool clip(double& x0, double& y0, double& x1, double& y1, double lo_x, double hi_x, double lo_y,
          double hi_y) {
  const double dx = x1 - x0, dy = y1 - y0;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - lo_x, hi_x - x0, y0 - lo_y, hi_y - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  const double ax = x0, ay = y0;
  // Clamped: with coordinates far beyond the box the products round, and what is drawn must
  // stay on the canvas whatever the rounding.
  x0 = std::clamp(ax + t0 * dx, lo_x, hi_x);
  y0 = std::clamp(ay + t0 * dy, lo_y, hi_y);
  x1 = std::clamp(ax + t1 * dx, lo_x, hi_x);
  y1 = std::clamp(ay + t1 * dy, lo_y, hi_y);
  return true;
}

// The ASCII glyph of a line going (dx, dy) in dots, y down, with dots `aspect` times taller
// than wide: '-' within 22.5 degrees of horizontal, '|' of vertical, else '/' or '\'.
char slope_glyph(double dx, double dy, double aspect) {
  const double ax = std::fabs(dx), ay = std::fabs(dy) * aspect;
  if (ay <= 0.4142 * ax) return '-';
  if (ax <= 0.4142 * ay) return '|';
  return (dx > 0) == (dy < 0) ? '/' : '\\';
}

}  // namespace

Stroke solid_stroke(Ink ink) { return Stroke{ink, 1, 1, 0}; }

Stroke patterned_stroke(Ink ink, int pattern_index, bool braille) {
  static const Stroke braille_patterns[] = {
      {0, 0x1, 1, 0},     // solid
      {0, 0xF, 6, 0},     // dashed: 4 on, 2 off
      {0, 0x1, 2, 0},     // dotted: 1 on, 1 off
      {0, 0x8F, 10, 0},   // dash-dot: 4 on, 3 off, 1 on, 2 off
  };
  static const Stroke ascii_patterns[] = {
      {0, 0x1, 1, 0},     // solid
      {0, 0x3, 3, 0},     // dashed: 2 on, 1 off
      {0, 0x1, 2, 0},     // dotted: 1 on, 1 off
      {0, 0x17, 6, 0},    // dash-dot: 3 on, 1 off, 1 on, 1 off
  };
  // Through a pointer: GCC 12 with -fsanitize=undefined indexes a conditional expression of
  // array type as if the index were 0.
  const Stroke* table = braille ? braille_patterns : ascii_patterns;
  Stroke s = table[static_cast<unsigned>(pattern_index) % 4];
  s.ink = ink;
  return s;
}

Canvas::Canvas(int columns, int rows, bool braille, double cell_aspect)
    : columns_(std::max(columns, 1)),
      rows_(std::max(rows, 1)),
      dx_(braille ? 2 : 1),
      dy_(braille ? 4 : 1),
      braille_(braille),
      aspect_(cell_aspect),
      dots_(static_cast<std::size_t>(dots_x()) * dots_y(), 0),
      glyphs_(braille ? 0 : static_cast<std::size_t>(columns_) * rows_, ' '),
      overlay_(static_cast<std::size_t>(columns_) * rows_, -1) {}

void Canvas::dot(int x, int y, Ink ink, char glyph) {
  if (x < 0 || y < 0 || x >= dots_x() || y >= dots_y()) return;
  dots_[static_cast<std::size_t>(y) * dots_x() + x] = ink;
  if (!braille_) glyphs_[static_cast<std::size_t>(y) * columns_ + x] = glyph;
}

int Canvas::line(double x0, double y0, double x1, double y1, const Stroke& stroke, int phase) {
  if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1)))
    return phase;
  const char glyph = braille_ ? '*' : stroke.glyph ? stroke.glyph
                                                   : slope_glyph(x1 - x0, y1 - y0, dot_aspect());
  if (!clip(x0, y0, x1, y1, -0.5, dots_x() - 0.5, -0.5, dots_y() - 0.5)) return phase;
  // Bresenham's algorithm on the rounded, clipped end points (both now on the canvas).
  int cx = static_cast<int>(std::lround(x0)), cy = static_cast<int>(std::lround(y0));
  const int ex = static_cast<int>(std::lround(x1)), ey = static_cast<int>(std::lround(y1));
  const int dx = std::abs(ex - cx), dy = -std::abs(ey - cy);
  const int sx = cx < ex ? 1 : -1, sy = cy < ey ? 1 : -1;
  const int length = std::clamp(stroke.length, 1, 32);
  for (int error = dx + dy;; ++phase) {
    if ((stroke.pattern >> (phase % length)) & 1u) dot(cx, cy, stroke.ink, glyph);
    if (cx == ex && cy == ey) break;
    const int e2 = 2 * error;
    if (e2 >= dy) {
      error += dy;
      cx += sx;
    }
    if (e2 <= dx) {
      error += dx;
      cy += sy;
    }
  }
  return phase + 1;
}

void Canvas::text(int column, int row, const std::string& text, Ink ink) {
  if (row < 0 || row >= rows_) return;
  for (std::size_t i = 0; i < text.size() && column < columns_; ++column) {
    std::size_t end = i + 1;
    while (end < text.size() && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) ++end;
    if (column >= 0) {
      overlay_[static_cast<std::size_t>(row) * columns_ + column] =
          static_cast<int>(overlays_.size());
      overlays_.push_back(Overlay{text.substr(i, end - i), ink});
    }
    i = end;
  }
}

bool Canvas::lit(int column, int row) const {
  Ink ink;
  return cell_glyph(column, row, ink) != " ";
}

Ink Canvas::cell_ink(int column, int row) const {
  Ink ink = 0;
  cell_glyph(column, row, ink);
  return ink;
}

bool Canvas::has_ink(int column, int row, Ink ink) const {
  if (column < 0 || row < 0 || column >= columns_ || row >= rows_) return false;
  for (int r = 0; r < dy_; ++r)
    for (int c = 0; c < dx_; ++c)
      if (dots_[static_cast<std::size_t>(row * dy_ + r) * dots_x() + column * dx_ + c] == ink)
        return true;
  return false;
}

bool Canvas::has_text(int column, int row) const {
  return column >= 0 && row >= 0 && column < columns_ && row < rows_ &&
         overlay_[static_cast<std::size_t>(row) * columns_ + column] >= 0;
}

// The glyph of a cell and, in `ink`, the ink it is shown in (0 for a blank).
std::string Canvas::cell_glyph(int column, int row, Ink& ink) const {
  ink = 0;
  if (column < 0 || row < 0 || column >= columns_ || row >= rows_) return " ";
  const std::size_t cell = static_cast<std::size_t>(row) * columns_ + column;
  if (overlay_[cell] >= 0) {
    ink = overlays_[overlay_[cell]].ink;
    return overlays_[overlay_[cell]].glyph;
  }
  if (!braille_) {
    ink = dots_[cell];
    return ink ? std::string(1, glyphs_[cell]) : " ";
  }
  static const int bits[4][2] = {{0x01, 0x08}, {0x02, 0x10}, {0x04, 0x20}, {0x40, 0x80}};
  int pattern = 0, best = 0;
  Ink inks[8];
  int counts[8] = {0}, kinds = 0;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 2; ++c) {
      const Ink d = dots_[static_cast<std::size_t>(row * 4 + r) * dots_x() + column * 2 + c];
      if (d == 0) continue;
      pattern |= bits[r][c];
      int k = 0;
      while (k < kinds && inks[k] != d) ++k;
      if (k == kinds) inks[kinds++] = d;
      ++counts[k];
    }
  }
  if (pattern == 0) return " ";
  for (int k = 1; k < kinds; ++k)  // most dots; a tie goes to the higher ink (drawn on top)
    if (counts[k] > counts[best] || (counts[k] == counts[best] && inks[k] > inks[best])) best = k;
  ink = inks[best];
  return encode_utf8(0x2800 + pattern);
}

std::vector<std::string> Canvas::lines(const std::vector<std::string>& palette) const {
  std::vector<std::string> out(rows_);
  for (int row = 0; row < rows_; ++row) {
    std::string& line = out[row];
    const std::string* current = nullptr;
    for (int column = 0; column < columns_; ++column) {
      Ink ink;
      const std::string glyph = cell_glyph(column, row, ink);
      const std::string* color =
          ink < palette.size() && !palette[ink].empty() ? &palette[ink] : nullptr;
      if (color != current && !(color == nullptr && glyph == " ")) {
        line += color ? *color : "\x1b[0m";
        current = color;
      }
      line += glyph;
    }
    if (current != nullptr) line += "\x1b[0m";
  }
  return out;
}

}  // namespace rigidlab::present
