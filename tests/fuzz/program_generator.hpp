// Turns fuzzer bytes into a Lua program of rigidlab API calls with hostile arguments: each
// group of four bytes picks a call and its arguments: a function or method of the API (read
// from the library, api_names.hpp), a field assignment or an operator, with values such as
// NaN, ±Inf, 0, -1, 1e308, wrong types, broken tables and earlier results. Every call runs
// under pcall, so the program goes on after each error and reaches deep states.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace rigidlab::fuzz {

std::string generate_program(const std::uint8_t* data, std::size_t size);

}  // namespace rigidlab::fuzz
