// Limits on what a Lua chunk may consume: instructions, memory and wall-clock time. Used by
// `rigidlab check` for every lesson, so a lesson that loops forever or allocates without bound
// fails within seconds and the remaining lessons still run.
//
// The instruction count and the clock are checked from a count hook (every 1000 VM
// instructions); the memory cap lives in the allocator, which returns NULL only when the cap
// would be exceeded, so Lua's emergency collection runs before the allocation fails.
#pragma once

#include <lua.hpp>

#include <chrono>
#include <cstddef>
#include <string>

namespace rigidlab::cli {

struct Limits {
  long long max_instructions = 0;  // 0: unlimited
  std::size_t max_memory_bytes = 0;  // 0: unlimited
  double timeout_seconds = 0.0;    // 0: unlimited
};

// A Lua state created with the limits' allocator and hook. The object must outlive nothing it
// created: it closes the state in its destructor.
class LimitedState {
 public:
  explicit LimitedState(const Limits& limits);
  ~LimitedState();
  LimitedState(const LimitedState&) = delete;
  LimitedState& operator=(const LimitedState&) = delete;

  lua_State* get() const { return state_; }
  // Restarts the clock and the instruction count (e.g. before each lesson).
  void restart();
  // Which limit stopped the last chunk, in words ("the memory limit (64 MB)"), or "" if none.
  std::string limit_hit() const;
  std::size_t memory_in_use() const { return used_bytes_; }

 private:
  static void* allocate(void* self, void* block, std::size_t old_size, std::size_t new_size);
  static void hook(lua_State* L, lua_Debug* ar);
  // Raises a Lua error when a limit has been passed; called by the hook and, through
  // rigidlab::lua::check_stop, from long loops inside bindings.
  void enforce(lua_State* L);

  Limits limits_;
  lua_State* state_ = nullptr;
  std::size_t used_bytes_ = 0;
  long long instructions_ = 0;
  std::chrono::steady_clock::time_point start_;
  enum class Hit { none, instructions, memory, time } hit_ = Hit::none;
};

}  // namespace rigidlab::cli
