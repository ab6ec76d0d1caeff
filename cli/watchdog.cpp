#include "cli/watchdog.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstdio>

namespace rigidlab::cli {

Watchdog::Watchdog(std::atomic<bool>& passed, double grace_seconds, std::string stuck_message)
    : passed_(passed),
      grace_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(grace_seconds))),
      stuck_message_(std::move(stuck_message)) {}

Watchdog::~Watchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Watchdog::arm(double seconds) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    armed_ = true;
    // Past ~10⁹ s the duration would overflow the clock: no deadline in practice.
    deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(seconds < 1e9 ? seconds : 1e9));
    passed_ = false;
  }
  if (!thread_.joinable()) start_thread();
  changed_.notify_all();
}

void Watchdog::disarm() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    armed_ = false;
  }
  changed_.notify_all();
}

// The watchdog's thread takes no signal. A thread starts with its creator's signal mask, and
// the kernel may give a process's signal to any thread that does not block it: a Ctrl-C taken
// here would set the REPL's flag without waking the main thread from its wait for a key
// (cli/interrupt.hpp, wait_for_key), and the line would be cleared a key late.
void Watchdog::start_thread() {
  sigset_t all, previous;
  sigfillset(&all);
  pthread_sigmask(SIG_SETMASK, &all, &previous);
  try {
    thread_ = std::thread(&Watchdog::watch, this);
  } catch (...) {
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    throw;
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

// Sleeps until the deadline (or a change of it); raises the flag there, and gives up when the
// same deadline is still armed after the grace period.
void Watchdog::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!quit_) {
    if (!armed_) {
      changed_.wait(lock);
      continue;
    }
    const Clock::time_point deadline = deadline_;
    const bool past_grace = Clock::now() >= deadline + grace_;
    if (past_grace && !stuck_message_.empty()) give_up();
    if (Clock::now() >= deadline) passed_ = true;
    changed_.wait_until(lock, Clock::now() >= deadline ? deadline + grace_ : deadline);
  }
}

// The main thread is stuck in a C function: say so and end the process. Only async-signal-safe
// calls, except the flush of stdout, which is tried without waiting for its lock.
void Watchdog::give_up() {
  if (ftrylockfile(stdout) == 0) {
    std::fflush(stdout);
    funlockfile(stdout);
  }
  const std::string line = stuck_message_ + "\n";
  if (write(STDERR_FILENO, line.data(), line.size()) < 0) _exit(1);
  _exit(1);
}

}  // namespace rigidlab::cli
