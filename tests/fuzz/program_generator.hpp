// Turns fuzzer bytes into a Lua program of rigidlab API calls with hostile arguments: each
// byte pair picks a call and its arguments from fixed tables (functions and methods of
// API.md; numbers such as NaN, ±Inf, 0, -1, 1e308; wrong types; earlier results). Every call
// runs under pcall, so the program goes on after each error and reaches deep states.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace rigidlab::fuzz {

std::string generate_program(const std::uint8_t* data, std::size_t size);

}  // namespace rigidlab::fuzz
