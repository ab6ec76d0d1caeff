// libFuzzer target: every input runs through the harness (harness.hpp) that fuzz_replay and
// CTest use too. Any crash, sanitizer report, leak or timeout is a finding; a Lua error is not.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rigidlab::fuzz::run_input(data, size);
  return 0;
}
