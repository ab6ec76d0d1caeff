// Numbers in error messages, written as Lua's tostring writes them ("%.14g"), so a message read
// in the REPL shows the value the user typed. NaN and infinities read "nan", "inf" and "-inf"
// on every platform (printf's "%g" gives "-nan" for the NaN that 0/0 produces on x86). The one
// formatter of the engine and the bindings.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace rigidlab {

// `digits` significant digits (14 as Lua's tostring; fewer where a message lists many values).
inline std::string format_number(double x, int digits = 14) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

}  // namespace rigidlab
