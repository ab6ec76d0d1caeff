// The one code path of the fuzz target (fuzz_lua, libFuzzer) and of its replay (fuzz_replay,
// CTest): an input becomes a Lua program (program_for) that runs in a fresh sandboxed state
// under instruction, memory and time limits (run_input). A Lua error is the expected outcome;
// a crash, an abort, a sanitizer report or a hang is a finding.
//
// Lua's own pattern functions are bounded here, not in rigidlab: string.find/match/gmatch/gsub
// refuse (with a Lua error) a subject longer than 256 bytes or a pattern with more than two
// quantifiers, unless find is plain. A backtracking match such as
// ("a"):rep(40):find(("a*"):rep(20) .. "b") is one long C call that no hook can stop; without
// the bound libFuzzer would report timeouts of Lua's string library that are not rigidlab bugs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace rigidlab::fuzz {

struct RunLimits {
  long long max_instructions = 2'000'000;
  std::size_t max_memory_bytes = std::size_t(64) << 20;  // Lua's and the engine's together
  double timeout_seconds = 2.0;  // checked by the count hook and the engine's stop check
};

// The Lua text an input stands for: the first byte chooses between the rest as raw Lua text
// (byte % 4 == 0) and a program of rigidlab API calls generated from the rest.
std::string program_for(const std::uint8_t* data, std::size_t size);

// Runs the program of an input. Returns the first line of its Lua error, or "" when it ran to
// the end (or the input was empty).
std::string run_input(const std::uint8_t* data, std::size_t size, const RunLimits& limits = {});

}  // namespace rigidlab::fuzz
