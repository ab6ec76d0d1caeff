// Limits on what Lua code may consume: instructions, memory and wall-clock time
// (`rigidlab --max-instructions N --max-memory MB --timeout S`, and `rigidlab check`'s
// defaults for every lesson), so a script or lesson that loops forever, allocates without
// bound or hangs in a long call is stopped with a message naming the limit.
//
// - Instructions: counted by a count hook (every 1000 VM instructions), installed on every
//   thread even without limits (it also raises Ctrl-C's interruption, cli/interrupt.hpp), and
//   kept in place whatever a script does with debug.sethook (cli/hook_guard.hpp).
// - Memory: one budget (cli/memory_budget.hpp) for Lua's allocator and for the C++ heap of the
//   engine. Lua's allocator returns NULL only when the budget would be exceeded, so Lua's
//   emergency collection runs before the allocation fails; operator new throws std::bad_alloc
//   there, which the bindings turn into the same "not enough memory" error.
// - Time: a watchdog thread (cli/watchdog.hpp) raises a flag at the deadline; the count hook
//   and the state's stop check, which the engine's long loops poll (w:step of any size),
//   raise the error there. A C function that does not return to Lua in the grace period after
//   that ends the process (scripts), or its child process (`rigidlab check`).
#pragma once

#include <lua.hpp>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

#include "cli/memory_budget.hpp"
#include "cli/watchdog.hpp"

namespace rigidlab::cli {

struct Limits {
  long long max_instructions = 0;    // 0: unlimited
  double max_memory_megabytes = 0.0;  // MB of 2^20 bytes; 0: unlimited
  double timeout_seconds = 0.0;      // 0: unlimited
};

// What the watchdog does when a C function does not return in the grace period.
enum class WhenStuck {
  exit,         // print "rigidlab: stopped: the time limit (1 s) reached in a C function", _exit(1)
  leave_to_parent,  // nothing: the process is a child of `rigidlab check`, which kills it
};

// Seconds between the deadline and giving up on a C function that does not return.
constexpr double stuck_grace_seconds = 1.0;

// A Lua state created with the limits' allocator, hook and stop check. It closes the state in
// its destructor.
// Why a LimitedState with these limits could not be created, for "cannot create the Lua
// state: ...".
const char* state_failure_reason(const Limits& limits);

class LimitedState {
 public:
  LimitedState(const Limits& limits, WhenStuck when_stuck);
  ~LimitedState();
  LimitedState(const LimitedState&) = delete;
  LimitedState& operator=(const LimitedState&) = delete;

  // The object that created L, or nullptr for a state made otherwise.
  static LimitedState* of(lua_State* L);

  lua_State* get() const { return state_; }  // nullptr if the state could not be created
  MemoryBudget& budget() { return budget_; }
  // The timed run begins (a script, a REPL chunk, a lesson): restarts the clock and the
  // instruction count. end_run: it has ended, the clock stops (the REPL's prompt is not timed).
  void begin_run();
  void end_run();
  // Goes on with the run that end_run paused (a lesson waiting at its prompt between steps):
  // the clock with the time that was left, the instruction count where it was.
  void resume_run();
  // Which limit stopped the code, in words ("the memory limit (64 MB)"), or "" if none.
  std::string limit_hit() const;
  // Whether `message` is the error of a limit that stopped the code (or of Ctrl-C): the
  // message handler then adds no traceback. Allocates nothing.
  bool is_stop(const char* message) const;
  // Whether `message` carries the error of a limit or of Ctrl-C that this state raised in
  // the current run (code that catches errors to show them must let those through).
  bool stopped_by(const char* message) const;
  // The message to show for an error `message` of the code: "stopped: the memory limit
  // (64 MB) reached" for Lua's "not enough memory" when the budget refused an allocation;
  // a limit's or Ctrl-C's error with the position of the code it stopped once (an error
  // crossing coroutine.wrap gets the position of the call prepended again).
  std::string explain(const std::string& message) const;
  // "stopped: the time limit (1 s) reached in a C function": what is said when the watchdog
  // or a parent process gives up on a call.
  std::string stuck_message() const;

 private:
  enum class Hit { none, instructions, memory, time };
  static void* allocate(void* self, void* block, std::size_t old_size, std::size_t new_size);
  static void hook(lua_State* L, lua_Debug* ar);
  static void stop_check(lua_State* L, void* self);
  void check(lua_State* L);
  void collect_engine_garbage(lua_State* L);
  [[noreturn]] void raise_stop(lua_State* L, Hit hit);
  // The words of limit_hit, written into `text` (no allocation: the hook writes them).
  void describe(Hit hit, char* text, std::size_t size) const;
  Hit hit() const;

  Limits limits_;
  MemoryBudget budget_;
  lua_State* state_ = nullptr;
  long long instructions_ = 0;
  Hit hit_ = Hit::none;
  std::size_t heap_after_collection_ = 0;  // the heap's growth after the last full collection
  char stop_message_[256] = "";  // the last limit's or Ctrl-C's error, position included
  std::atomic<bool> deadline_passed_{false};
  double seconds_left_ = 0.0;  // of the time limit, for resume_run
  std::chrono::steady_clock::time_point run_start_;
  std::unique_ptr<Watchdog> watchdog_;  // when there is a time limit
};

// While alive, `L`'s run is timed (LimitedState::begin_run/end_run); nothing for a state
// without limits.
class TimedRun {
 public:
  explicit TimedRun(lua_State* L);
  ~TimedRun();
  TimedRun(const TimedRun&) = delete;
  TimedRun& operator=(const TimedRun&) = delete;

 private:
  LimitedState* state_;
};

}  // namespace rigidlab::cli
