// The argument of plot.lines{...} read into the chart model of present/, for plot.lines and
// for every other function that takes a chart the same way (ctx:plot in lessons).
#pragma once

#include <lua.hpp>

#include <string>

#include "present/chart.hpp"

namespace rigidlab::lua {

struct PlotRequest {
  present::Chart chart;
  int width = 60, height = 15;  // the plot area in character cells
  std::string svg;              // a file to write the chart to as SVG, or empty
};

// Reads the chart table at `arg`: {series..., title =, xlabel =, ylabel =, width =, height =,
// svg =}. Errors name the running function and `arg` ("bad argument #1 to 'plot.lines'
// (series 2: y[3] is nan)"). Tables are read raw: their metamethods are not run. The svg path
// is checked (output_file.hpp) but nothing is written.
PlotRequest check_plot_request(lua_State* L, int arg);

}  // namespace rigidlab::lua
