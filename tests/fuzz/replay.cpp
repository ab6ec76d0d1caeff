// Replays fuzzer inputs through the fuzz target's harness in an ordinary build (no clang, no
// libFuzzer): fuzz_replay FILE|DIR ... runs every file (a directory's files in name order)
// under the same instruction, memory and time limits. A crash or an abort ends the process
// with a signal, which fails the CTest entry that replays tests/fuzz/corpus and regressions;
// -v prints each file's Lua error.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/harness.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  bool verbose = false;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-v") == 0) {
      verbose = true;
    } else if (fs::is_directory(argv[i])) {
      std::vector<fs::path> found;
      for (const auto& entry : fs::directory_iterator(argv[i]))
        if (entry.is_regular_file() && entry.path().filename().string()[0] != '.')
          found.push_back(entry.path());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(argv[i])) {
      files.emplace_back(argv[i]);
    } else {
      std::fprintf(stderr, "fuzz_replay: no such file or directory: %s\n", argv[i]);
      return 2;
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: fuzz_replay [-v] FILE|DIR ...  (no inputs found)\n");
    return 2;
  }
  int errors = 0;
  for (const fs::path& path : files) {
    std::ifstream file(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (verbose) std::printf("%s\n", path.c_str());
    std::fflush(stdout);  // a crash names the file it was replaying
    const std::string error =
        rigidlab::fuzz::run_input(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    if (!error.empty()) ++errors;
    if (verbose && !error.empty()) std::printf("  %s\n", error.c_str());
  }
  std::printf("%zu inputs replayed without a crash (%d ended with a Lua error)\n", files.size(),
              errors);
  return 0;
}
