// Prints the Lua program a fuzzer input stands for: print_program FILE > regression.lua
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/fuzz/program_generator.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_print_program INPUT\n");
    return 2;
  }
  std::ifstream file(argv[1], std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (bytes.empty()) return 0;
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  const std::string program = data[0] % 4 == 0
                                  ? bytes.substr(1)
                                  : rigidlab::fuzz::generate_program(data + 1, bytes.size() - 1);
  std::fwrite(program.data(), 1, program.size(), stdout);
  return 0;
}
