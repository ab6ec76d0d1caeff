// `rigidlab check [--max-instructions N] [--max-memory MB] [--timeout S] [ID|FILE ...]`: runs
// every expectation of the lessons (default: all) without pausing and prints one line per
// lesson and `N passed, M failed`. Each lesson runs in its own child process under the limits,
// so a lesson that loops, allocates without bound, hangs in a C function or crashes fails
// with a message saying why, and the remaining lessons still run.
#pragma once

#include <string>
#include <vector>

#include "cli/limits.hpp"

namespace rigidlab::cli {

// Defaults of `rigidlab check`: a lesson is meant to finish in well under 2 s.
Limits default_check_limits();

// The command: its arguments are limit options and lesson ids or files. Returns the exit
// status: 0 when every lesson passed, 1 otherwise, 2 for a usage error.
int check_command(const std::vector<std::string>& arguments);

}  // namespace rigidlab::cli
