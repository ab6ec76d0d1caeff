// The options that set limits, for the interpreter's command line and for `rigidlab check`:
// --max-instructions N, --max-memory MB, --timeout S (or --option=VALUE). 0 means no limit.
#pragma once

#include <string>
#include <vector>

#include "cli/limits.hpp"

namespace rigidlab::cli {

// When arguments[i] is a limit option, reads its value (after '=' or the next argument) into
// `limits`, leaves i on the last argument used and returns true; `error` is then "" or the
// usage error ("'--timeout' needs a number of seconds >= 0, got 'x'"). False (and nothing
// read) for any other argument.
bool take_limit_option(const std::vector<std::string>& arguments, std::size_t& i, Limits& limits,
                       std::string& error);

}  // namespace rigidlab::cli
