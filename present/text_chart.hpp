// A line chart as text for a terminal: braille dots (2 x 4 per cell) in Unicode, one glyph per
// cell in ASCII, with round-number ticks on both axes, the labels and a legend. Pure: it
// returns the text (lines joined by "\n", no final newline), so a caller can print it, indent
// it or lay it out inside a lesson.
#pragma once

#include <string>

#include "present/chart.hpp"
#include "present/style.hpp"

namespace rigidlab::present {

struct TextChartOptions {
  int width = 60;   // the plot area in character cells, without the axis labels
  int height = 15;
  TextStyle style;
};

// Series are told apart by colour when the style has colour. Without colour, each series has
// its own glyph ('*', '+', 'o', 'x', '#', '@'): in ASCII every dot of a series is its glyph;
// in braille, when there is more than one series, the glyph marks the line every few cells
// (as markers on a line in print), and the legend shows it.
std::string text_chart(const Chart& chart, const TextChartOptions& options);

}  // namespace rigidlab::present
