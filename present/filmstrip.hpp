// A short sequence of frames laid out as a film strip for a page of text (a lesson's
// ctx:motion): frames left to right in rows, each in a box whose top border carries its
// caption ("t = 0.50 s"). Box-drawing characters in Unicode mode, + - | in ASCII mode.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::present {

struct FilmFrame {
  std::string caption;
  std::vector<std::string> lines;  // the picture, each line `width` columns (display_width)
};

// How many frames of at least `min_width` columns (their box included) fit side by side in
// `columns`, with `gap` columns between them: at least 1, at most `count`.
int frames_per_row(int columns, int count, int min_width, int gap);

// The frames, `per_row` to a row, every picture `width` columns wide and as many lines as
// the first; each line of the strip starts with `indent` and ends in "\n". A caption too long
// for its border is cut.
std::string filmstrip(const std::vector<FilmFrame>& frames, int width, int per_row,
                      const std::string& indent, bool unicode);

constexpr int filmstrip_gap = 2;  // columns between two boxes

}  // namespace rigidlab::present
