#include "cli/limits.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cli/hook_guard.hpp"
#include "cli/interrupt.hpp"
#include "lua/binding.hpp"

namespace rigidlab::cli {
namespace {

const char registry_key = 0;  // the LimitedState of a state, for LimitedState::of
// Engine memory (bytes) that may be allocated past twice what was held after the last full
// collection before the hook runs another (LimitedState::collect_engine_garbage).
constexpr std::size_t collection_slack_bytes = 1 << 20;

std::size_t bytes_of(double megabytes) {
  return static_cast<std::size_t>(std::ceil(megabytes * (1 << 20)));
}

// Writes "chunk:line: " of the innermost Lua function running (the line of a loop stopped by
// the hook, or the line that called w:step) into `text`, or "" when none.
void write_where(lua_State* L, char* text, std::size_t size) {
  text[0] = '\0';
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar) != 0; ++level) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0) {
      std::snprintf(text, size, "%s:%d: ", ar.short_src, ar.currentline);
      return;
    }
  }
}

}  // namespace

LimitedState::LimitedState(const Limits& limits, WhenStuck when_stuck)
    : limits_(limits), budget_(bytes_of(limits.max_memory_megabytes)) {
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
  budget_.set_lua_bytes(static_cast<std::size_t>(lua_gc(state_, LUA_GCCOUNT)) * 1024 +
                        static_cast<std::size_t>(lua_gc(state_, LUA_GCCOUNTB)));
  lua_setallocf(state_, &LimitedState::allocate, this);
  if (limits_.timeout_seconds > 0.0)
    watchdog_ = std::make_unique<Watchdog>(
        deadline_passed_, stuck_grace_seconds,
        when_stuck == WhenStuck::exit ? "rigidlab: " + stuck_message() : "");
  // Always: Ctrl-C is raised by this hook too.
  install_limits_hook(state_, &LimitedState::hook);
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
  budget_.set_refused(false);
  stop_message_[0] = '\0';
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

LimitedState::Hit LimitedState::hit() const {
  return hit_ == Hit::none && budget_.refused() ? Hit::memory : hit_;
}

void LimitedState::describe(Hit hit, char* text, std::size_t size) const {
  text[0] = '\0';
  switch (hit) {
    case Hit::instructions:
      std::snprintf(text, size, "the instruction limit (%lld instructions)",
                    limits_.max_instructions);
      break;
    case Hit::memory:
      std::snprintf(text, size, "the memory limit (%g MB)", limits_.max_memory_megabytes);
      break;
    case Hit::time:
      std::snprintf(text, size, "the time limit (%g s)", limits_.timeout_seconds);
      break;
    case Hit::none:
      break;
  }
}

std::string LimitedState::limit_hit() const {
  char text[96];
  describe(hit(), text, sizeof text);
  return text;
}

bool LimitedState::is_stop(const char* message) const {
  return std::strstr(stop_message_, "stopped: ") != nullptr &&
         std::strstr(message, stop_message_) != nullptr;
}

bool LimitedState::stopped_by(const char* message) const {
  return stop_message_[0] != '\0' && std::strstr(message, stop_message_) != nullptr;
}

std::string LimitedState::explain(const std::string& message) const {
  if (hit() == Hit::memory && message.find("not enough memory") != std::string::npos)
    return "stopped: " + limit_hit() + " reached";
  const std::size_t stop = stop_message_[0] != '\0' ? message.find(stop_message_) : std::string::npos;
  if (stop != std::string::npos && stop > 0) return message.substr(stop);
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
    self->budget_.lua_changed(old_bytes, 0);
    return nullptr;
  }
  if (!self->budget_.lua_may_grow(old_bytes, new_size)) {
    self->hit_ = Hit::memory;
    return nullptr;  // Lua collects garbage and tries once more before raising
  }
  void* result = std::realloc(block, new_size);
  if (result != nullptr) self->budget_.lua_changed(old_bytes, new_size);
  return result;
}

// The limits' hook, on every thread: counts instructions, checks the limits and Ctrl-C at each
// count event, then runs the script's own hook of the thread, if it set one.
void LimitedState::hook(lua_State* L, lua_Debug* ar) {
  LimitedState* self;
  std::memcpy(&self, lua_getextraspace(L), sizeof self);
  if (ar->event == LUA_HOOKCOUNT) {
    self->instructions_ += lua_gethookcount(L);
    self->check(L);
    self->collect_engine_garbage(L);
  }
  run_script_hook(L, ar);
}

void LimitedState::check(lua_State* L) {
  if (interrupt_requested()) raise_stop(L, Hit::none);
  if (limits_.max_instructions > 0 && instructions_ > limits_.max_instructions)
    raise_stop(L, Hit::instructions);
  if (deadline_passed_.load(std::memory_order_relaxed)) raise_stop(L, Hit::time);
}

// Lua's collector sees a world as its small userdata, not the engine memory it holds, and in
// generational mode a garbage world that has grown old waits for a major collection, which
// only Lua's own growth triggers: a loop that makes big worlds would reach the memory limit
// with garbage. So when the C++ heap has grown past twice what it held after the last full
// collection (plus a slack), a full collection runs here, finalisers included (the hook is
// a safe point for them, as any allocation in Lua code is). Its cost stays proportional to
// what is allocated, as with Lua's own major collections.
void LimitedState::collect_engine_garbage(lua_State* L) {
  const std::size_t growth = budget_.heap_growth();
  heap_after_collection_ = std::min(heap_after_collection_, growth);
  if (growth - heap_after_collection_ <= heap_after_collection_ + collection_slack_bytes) return;
  lua_gc(L, LUA_GCCOLLECT);
  heap_after_collection_ = budget_.heap_growth();
}

// The stop check of the bindings (lua/binding.hpp): two flag reads.
void LimitedState::stop_check(lua_State* L, void* self_pointer) {
  auto* self = static_cast<LimitedState*>(self_pointer);
  if (interrupt_requested()) self->raise_stop(L, Hit::none);
  if (self->deadline_passed_.load(std::memory_order_relaxed)) self->raise_stop(L, Hit::time);
}

// Raises "chunk:line: stopped: the time limit (1 s) reached", or "chunk:line: interrupted!"
// for Ctrl-C (Hit::none), and keeps the message for is_stop and explain.
void LimitedState::raise_stop(lua_State* L, Hit hit) {
  char where[160], limit[96];
  write_where(L, where, sizeof where);
  if (hit == Hit::none) {
    clear_interrupt();
    std::snprintf(stop_message_, sizeof stop_message_, "%sinterrupted!", where);
  } else {
    hit_ = hit;
    describe(hit, limit, sizeof limit);
    std::snprintf(stop_message_, sizeof stop_message_, "%sstopped: %s reached", where, limit);
  }
  lua_pushstring(L, stop_message_);
  lua_error(L);
  __builtin_unreachable();
}

TimedRun::TimedRun(lua_State* L) : state_(LimitedState::of(L)) {
  if (state_ != nullptr) state_->begin_run();
}

TimedRun::~TimedRun() {
  if (state_ != nullptr) state_->end_run();
}

const char* state_failure_reason(const Limits& limits) {
  return limits.max_memory_megabytes > 0 ? "the memory limit is too small" : "not enough memory";
}

}  // namespace rigidlab::cli
