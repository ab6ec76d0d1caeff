// The lines of a text (without their "\n"), for the tests of present/'s text renderers.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace rigidlab::present::testing {

inline std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace rigidlab::present::testing
