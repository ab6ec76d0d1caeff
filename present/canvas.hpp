// A character canvas drawn in dots: in braille mode each character cell holds 2 x 4 dots (the
// Unicode braille patterns U+2800 to U+28FF, one bit per dot), in ASCII mode one dot, shown as
// a glyph ('*', or '-', '|', '/', '\' along a line's slope). Every dot remembers the ink that
// drew it; a cell is shown in the colour of the ink with most dots in it. Text laid over cells
// (labels, markers) replaces their dots. The canvas never writes anywhere: lines() returns the
// rows, so a caller can indent them or lay them out beside other text.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rigidlab::present {

// An ink is an index into the palette given to Canvas::lines (1 to 255; 0 is an empty dot).
using Ink = std::uint8_t;

// Along a line, dot k (counted from the line's start, continuing across the segments of a
// polyline) is drawn when bit (k mod length) of `pattern` is set: a dash pattern, so lines of
// one ink stay distinct from another's without colour.
struct Stroke {
  Ink ink = 1;
  std::uint32_t pattern = 1;
  int length = 1;   // 1 to 32
  char glyph = 0;   // ASCII mode: every lit cell shows it; 0: a glyph for the line's slope
};

// Dash patterns, distinct at a glance: solid, dashed, dotted, dash-dot (index 0 to 3, then
// again). Counted in dots, so shorter in ASCII, where a dot is a whole cell.
Stroke solid_stroke(Ink ink);
Stroke patterned_stroke(Ink ink, int pattern_index, bool braille);

class Canvas {
 public:
  // `columns` x `rows` character cells; `cell_aspect` is a cell's height over its width (about
  // 2 in terminals), which makes an ASCII dot twice as tall as wide and a braille dot square.
  Canvas(int columns, int rows, bool braille, double cell_aspect = 2.0);

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  bool braille() const { return braille_; }
  int dots_x() const { return columns_ * dx_; }  // dots across
  int dots_y() const { return rows_ * dy_; }     // dots down; row 0 at the top
  double dot_aspect() const { return aspect_ * dx_ / dy_; }  // a dot's height over its width

  // Sets dot (x, y) when it lies on the canvas; `glyph` shows it in ASCII mode.
  void dot(int x, int y, Ink ink, char glyph = '*');
  // The segment from (x0, y0) to (x1, y1) in dot coordinates (dot centres at integers), clipped
  // to the canvas, so any finite coordinates are fine; a non-finite one draws nothing. Dots
  // are counted for the stroke's pattern from `phase`; returns the phase after the segment.
  int line(double x0, double y0, double x1, double y1, const Stroke& stroke, int phase = 0);
  // Text laid over the cells from (column, row) to the right, one cell per code point, clipped
  // at the canvas's edges. The text must be printable (present/text.hpp), and ASCII when the
  // canvas is not braille.
  void text(int column, int row, const std::string& text, Ink ink);

  // Queries, for tests and layouts: whether a cell shows anything, and the ink it shows in.
  bool lit(int column, int row) const;
  Ink cell_ink(int column, int row) const;
  bool has_ink(int column, int row, Ink ink) const;  // some dot of the cell has this ink
  bool has_text(int column, int row) const;          // text was laid over the cell

  // The rows as text. `palette[ink]` is the ANSI SGR sequence of an ink ("\x1b[34m"); an empty
  // palette (or an empty entry) draws without colour. Each row ends with a reset when coloured.
  std::vector<std::string> lines(const std::vector<std::string>& palette = {}) const;

 private:
  std::string cell_glyph(int column, int row, Ink& ink) const;

  int columns_, rows_, dx_, dy_;
  bool braille_;
  double aspect_;
  std::vector<Ink> dots_;           // dots_x() * dots_y(), row-major
  std::vector<char> glyphs_;        // ASCII mode: the glyph of each cell
  std::vector<int> overlay_;        // per cell: index into overlays_, or -1
  struct Overlay {
    std::string glyph;
    Ink ink;
  };
  std::vector<Overlay> overlays_;
};

}  // namespace rigidlab::present
