// Prints the Lua program a fuzzer input stands for: fuzz_print_program FILE > program.lua
// (to read a finding; the input itself is what tests/fuzz/regressions keeps).
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/fuzz/harness.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_print_program INPUT\n");
    return 2;
  }
  std::ifstream file(argv[1], std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string program = rigidlab::fuzz::program_for(
      reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  std::fwrite(program.data(), 1, program.size(), stdout);
  return 0;
}
