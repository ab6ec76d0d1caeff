// The wall-clock watchdog of the time limit: a thread that watches a deadline, because the
// code being timed may be stuck where no hook runs. At the deadline it raises a flag, which
// the state's stop check reads (from the count hook and from the engine's long loops): the
// Lua code and w:step stop there with a Lua error. A C function that neither returns to Lua
// nor polls (a backtracking string.find) cannot be stopped that way: if the deadline is still
// armed `grace` seconds later, the watchdog prints its message on stderr and ends the process
// with _exit(1) (or, for `rigidlab check`'s children, leaves that to the parent).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace rigidlab::cli {

class Watchdog {
 public:
  // `passed` is raised at each deadline. With `stuck_message` empty the watchdog never ends
  // the process.
  Watchdog(std::atomic<bool>& passed, double grace_seconds, std::string stuck_message);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  // Sets the deadline `seconds` from now (the thread starts on the first call).
  void arm(double seconds);
  // The timed code has ended: no deadline until the next arm.
  void disarm();

 private:
  using Clock = std::chrono::steady_clock;
  void start_thread();
  void watch();
  [[noreturn]] void give_up();

  std::atomic<bool>& passed_;
  const Clock::duration grace_;
  const std::string stuck_message_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool armed_ = false;
  bool quit_ = false;
  Clock::time_point deadline_;
  std::thread thread_;
};

}  // namespace rigidlab::cli
