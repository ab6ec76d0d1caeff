// libFuzzer target: the first byte chooses between running the input as raw Lua text and
// turning it into a program of rigidlab API calls (program_generator.cpp). Both run under
// instruction, memory and time limits, like `rigidlab check`. Any crash, sanitizer report or
// leak is a finding; a Lua error is not.
#include <cstddef>
#include <cstdint>
#include <string>

#include "cli/limits.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"
#include "tests/fuzz/program_generator.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  rigidlab::cli::Limits limits;
  limits.max_instructions = 2'000'000;
  limits.max_memory_bytes = std::size_t(64) << 20;
  limits.timeout_seconds = 2.0;
  rigidlab::cli::LimitedState state(limits);
  lua_State* L = state.get();
  if (L == nullptr) return 0;
  lua_pushcfunction(L, [](lua_State* L) {
    rigidlab::lua::open_all(L);
    rigidlab::lua::apply_sandbox(L);  // no files written or removed by generated programs
    lua_pushcfunction(L, [](lua_State*) { return 0; });
    lua_setglobal(L, "print");
    return 0;
  });
  if (lua_pcall(L, 0, 0, 0) != LUA_OK) return 0;
  const std::string program =
      data[0] % 4 == 0 ? std::string(reinterpret_cast<const char*>(data + 1), size - 1)
                       : rigidlab::fuzz::generate_program(data + 1, size - 1);
  if (luaL_loadbufferx(L, program.data(), program.size(), "=fuzz", "t") == LUA_OK)
    lua_pcall(L, 0, 0, 0);
  return 0;
}
