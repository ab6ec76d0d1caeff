#include "cli/limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cli/interrupt.hpp"
#include "lua/binding.hpp"

namespace rigidlab::cli {
namespace {

constexpr int hook_interval = 1000;  // VM instructions between checks
const char registry_key = 0;         // the LimitedState of a state, for LimitedState::of

// Pushes "chunk:line:" of the innermost Lua function running (the line of a loop stopped by
// the hook, or the line that called w:step), or "" when none.
void push_where(lua_State* L) {
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar) != 0; ++level) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0) {
      lua_pushfstring(L, "%s:%d: ", ar.short_src, ar.currentline);
      return;
    }
  }
  lua_pushliteral(L, "");
}

}  // namespace

LimitedState::LimitedState(const Limits& limits, WhenStuck when_stuck)
    : limits_(limits),
      max_memory_bytes_(static_cast<std::size_t>(std::ceil(limits.max_memory_megabytes * (1 << 20)))) {
  // luaL_newstate for lauxlib's panic and warning functions.
  state_ = luaL_newstate();
  if (state_ == nullptr) return;
  // The hook finds this object through the state's extra space (copied into coroutines).
  LimitedState* self = this;
  std::memcpy(lua_getextraspace(state_), &self, sizeof self);
  lua_pushlightuserdata(state_, this);
  lua_rawsetp(state_, LUA_REGISTRYINDEX, &registry_key);
  rigidlab::lua::set_stop_check(state_, &LimitedState::stop_check, this);
  // Then the allocator becomes the counting one (both use realloc and free), starting from
  // what Lua has allocated: the allocations above, outside any protected call, cannot fail on
  // the cap; everything after runs in protected mode.
  used_bytes_ = static_cast<std::size_t>(lua_gc(state_, LUA_GCCOUNT)) * 1024 +
                static_cast<std::size_t>(lua_gc(state_, LUA_GCCOUNTB));
  lua_setallocf(state_, &LimitedState::allocate, this);
  if (limits_.timeout_seconds > 0.0)
    watchdog_ = std::make_unique<Watchdog>(
        deadline_passed_, stuck_grace_seconds,
        when_stuck == WhenStuck::exit ? "rigidlab: " + stuck_message() : "");
  if (limits_.max_instructions > 0 || limits_.timeout_seconds > 0.0)
    lua_sethook(state_, &LimitedState::hook, LUA_MASKCOUNT, hook_interval);
}

LimitedState::~LimitedState() {
  watchdog_.reset();  // its thread reads nothing of the state, but stop it first
  if (state_ != nullptr) lua_close(state_);
}

LimitedState* LimitedState::of(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &registry_key);
  auto* self = static_cast<LimitedState*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return self;
}

void LimitedState::begin_run() {
  instructions_ = 0;
  hit_ = Hit::none;
  deadline_passed_ = false;
  seconds_left_ = limits_.timeout_seconds;
  run_start_ = std::chrono::steady_clock::now();
  if (watchdog_) watchdog_->arm(limits_.timeout_seconds);
}

void LimitedState::end_run() {
  if (watchdog_) watchdog_->disarm();
  seconds_left_ -= std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_)
                       .count();
}

void LimitedState::resume_run() {
  run_start_ = std::chrono::steady_clock::now();
  if (watchdog_) watchdog_->arm(std::max(seconds_left_, 0.0));
}

std::string LimitedState::limit_hit() const {
  char text[96];
  switch (hit_) {
    case Hit::instructions:
      std::snprintf(text, sizeof text, "the instruction limit (%lld instructions)",
                    limits_.max_instructions);
      return text;
    case Hit::memory:
      std::snprintf(text, sizeof text, "the memory limit (%g MB)", limits_.max_memory_megabytes);
      return text;
    case Hit::time:
      std::snprintf(text, sizeof text, "the time limit (%g s)", limits_.timeout_seconds);
      return text;
    case Hit::none:
      break;
  }
  return "";
}

std::string LimitedState::explain(const std::string& message) const {
  if (hit_ == Hit::memory && message.find("not enough memory") != std::string::npos)
    return "stopped: " + limit_hit() + " reached";
  return message;
}

std::string LimitedState::stuck_message() const {
  char text[96];
  std::snprintf(text, sizeof text, "stopped: the time limit (%g s) reached in a C function",
                limits_.timeout_seconds);
  return text;
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
  if (self->max_memory_bytes_ > 0 && new_size > old_bytes &&
      self->used_bytes_ - old_bytes + new_size > self->max_memory_bytes_) {
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
  if (self->limits_.max_instructions > 0 && self->instructions_ > self->limits_.max_instructions)
    self->raise_limit(L, Hit::instructions);
  if (self->deadline_passed_.load(std::memory_order_relaxed)) self->raise_limit(L, Hit::time);
}

// The stop check of the bindings (lua/binding.hpp): two flag reads.
void LimitedState::stop_check(lua_State* L, void* self_pointer) {
  auto* self = static_cast<LimitedState*>(self_pointer);
  if (interrupt_requested()) raise_interrupt(L);
  if (self->deadline_passed_.load(std::memory_order_relaxed)) self->raise_limit(L, Hit::time);
}

void LimitedState::raise_limit(lua_State* L, Hit hit) {
  hit_ = hit;
  push_where(L);
  lua_pushfstring(L, "stopped: %s reached", limit_hit().c_str());
  lua_concat(L, 2);
  lua_error(L);
  __builtin_unreachable();
}

TimedRun::TimedRun(lua_State* L) : state_(LimitedState::of(L)) {
  if (state_ != nullptr) state_->begin_run();
}

TimedRun::~TimedRun() {
  if (state_ != nullptr) state_->end_run();
}

}  // namespace rigidlab::cli
