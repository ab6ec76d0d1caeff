// What rigidlab says about itself: the version line, the --help text, usage errors.
#pragma once

#include <cstdio>
#include <string>

namespace rigidlab::cli {

constexpr int exit_usage = 2;  // a wrong command line (exit 1 is a failed script or check)

// "rigidlab 0.1.0 (Lua 5.4.4)"
std::string version_line();
// The REPL's first line: the version and how to get help and leave.
std::string banner();
// The usage text: every option and every subcommand.
void print_help(std::FILE* out);
// Prints "rigidlab: <message>" and the hint to --help on stderr; returns exit_usage.
int usage_error(const std::string& message);

}  // namespace rigidlab::cli
