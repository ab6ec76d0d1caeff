// Numbers in the engine's error messages, written as Lua's tostring writes them ("%.14g"), so
// a message read in the REPL shows the value the user typed.
#pragma once

#include <cstdio>
#include <string>

namespace rigidlab {

inline std::string format_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.14g", x);
  return buffer;
}

}  // namespace rigidlab
