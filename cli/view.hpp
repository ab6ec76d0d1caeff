// rigidlab view FILE.lua [ARG ...]: runs the script (its arguments in `arg`, as for
// `rigidlab FILE.lua`), which must return a world, and shows that world live (w:view{}).
#pragma once

#include <string>
#include <vector>

namespace rigidlab::cli {

int view_command(const std::vector<std::string>& arguments);

}  // namespace rigidlab::cli
