#include "cli/limits.hpp"

#include "lua/binding.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rigidlab::cli {
namespace {
constexpr int hook_interval = 1000;  // VM instructions between checks
}

LimitedState::LimitedState(const Limits& limits) : limits_(limits) {
  state_ = lua_newstate(&LimitedState::allocate, this);
  if (state_ == nullptr) return;
  // The hook finds this object through the state's extra space (copied into coroutines).
  LimitedState* self = this;
  std::memcpy(lua_getextraspace(state_), &self, sizeof self);
  if (limits_.max_instructions > 0 || limits_.timeout_seconds > 0.0) {
    lua_sethook(state_, &LimitedState::hook, LUA_MASKCOUNT, hook_interval);
    rigidlab::lua::set_stop_check(
        state_, [](lua_State* L, void* self) { static_cast<LimitedState*>(self)->enforce(L); },
        this);
  }
  restart();
}

LimitedState::~LimitedState() {
  if (state_ != nullptr) lua_close(state_);
}

void LimitedState::restart() {
  instructions_ = 0;
  hit_ = Hit::none;
  start_ = std::chrono::steady_clock::now();
}

std::string LimitedState::limit_hit() const {
  char text[96];
  switch (hit_) {
    case Hit::instructions:
      std::snprintf(text, sizeof text, "the instruction limit (%lld instructions)",
                    limits_.max_instructions);
      return text;
    case Hit::memory:
      std::snprintf(text, sizeof text, "the memory limit (%zu MB)",
                    limits_.max_memory_bytes >> 20);
      return text;
    case Hit::time:
      std::snprintf(text, sizeof text, "the time limit (%g s)", limits_.timeout_seconds);
      return text;
    case Hit::none:
      break;
  }
  return "";
}

void* LimitedState::allocate(void* self_pointer, void* block, std::size_t old_size,
                             std::size_t new_size) {
  auto* self = static_cast<LimitedState*>(self_pointer);
  const std::size_t old_bytes = block != nullptr ? old_size : 0;  // else old_size is a type tag
  if (new_size == 0) {
    std::free(block);
    self->used_bytes_ -= old_bytes;
    return nullptr;
  }
  if (self->limits_.max_memory_bytes > 0 && new_size > old_bytes &&
      self->used_bytes_ - old_bytes + new_size > self->limits_.max_memory_bytes) {
    self->hit_ = Hit::memory;
    return nullptr;  // Lua collects garbage and tries once more before raising
  }
  void* result = std::realloc(block, new_size);
  if (result != nullptr) self->used_bytes_ = self->used_bytes_ - old_bytes + new_size;
  return result;
}

void LimitedState::hook(lua_State* L, lua_Debug*) {
  LimitedState* self;
  std::memcpy(&self, lua_getextraspace(L), sizeof self);
  self->instructions_ += hook_interval;
  self->enforce(L);
}

void LimitedState::enforce(lua_State* L) {
  if (limits_.max_instructions > 0 && instructions_ > limits_.max_instructions) {
    hit_ = Hit::instructions;
    luaL_error(L, "stopped: %s reached", limit_hit().c_str());
  }
  if (limits_.timeout_seconds > 0.0) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
    if (elapsed.count() > limits_.timeout_seconds) {
      hit_ = Hit::time;
      luaL_error(L, "stopped: %s reached", limit_hit().c_str());
    }
  }
}

}  // namespace rigidlab::cli
