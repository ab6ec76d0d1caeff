// A line chart as a standalone SVG document (W3C SVG 1.1): the same chart as text_chart, with
// ticks and grid lines at round numbers, the labels and a legend. Every label is made
// well-formed XML character data (present/text.hpp), whatever bytes it held.
#pragma once

#include <string>

#include "present/chart.hpp"

namespace rigidlab::present {

// The whole document, ending in "</svg>\n".
std::string svg_chart(const Chart& chart);

}  // namespace rigidlab::present
