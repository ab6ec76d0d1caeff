#include "cli/interrupt.hpp"

#include <poll.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>

#include "cli/hook_guard.hpp"
#include "cli/limits.hpp"

namespace rigidlab::cli {
namespace {

// Whether a Ctrl-C is waiting to be raised, and since when (CLOCK_MONOTONIC).
volatile sig_atomic_t interrupt_pending = 0;
struct timespec pending_since {};
volatile sig_atomic_t prompt_interrupted = 0;
volatile sig_atomic_t window_resized = 0;
int call_depth = 0;  // InterruptibleCalls alive

// Seconds a Ctrl-C may wait before the next one ends the process.
constexpr long stuck_seconds = 1;

double seconds_between(const struct timespec& from, const struct timespec& to) {
  return static_cast<double>(to.tv_sec - from.tv_sec) + 1e-9 * static_cast<double>(to.tv_nsec - from.tv_nsec);
}

// Only async-signal-safe calls.
void on_sigint_while_running(int) {
  struct timespec now {};
  clock_gettime(CLOCK_MONOTONIC, &now);
  if (interrupt_pending == 0) {
    pending_since = now;
    interrupt_pending = 1;
    return;
  }
  if (seconds_between(pending_since, now) < stuck_seconds) return;
  static const char message[] =
      "\nrigidlab: ended by Ctrl-C: a C function has not returned to Lua since the first one\n";
  if (write(STDERR_FILENO, message, sizeof message - 1) < 0) _exit(130);
  _exit(130);
}

void on_sigint_at_prompt(int) { prompt_interrupted = 1; }
void on_resize_at_prompt(int) { window_resized = 1; }

struct sigaction action(void (*handler)(int)) {
  struct sigaction result {};
  result.sa_handler = handler;
  sigemptyset(&result.sa_mask);
  result.sa_flags = 0;  // no SA_RESTART: a blocking read returns with EINTR
  return result;
}

MemoryBudget* budget_of(lua_State* L) {
  LimitedState* state = LimitedState::of(L);
  return state != nullptr ? &state->budget() : nullptr;
}

}  // namespace

InterruptibleCall::InterruptibleCall(lua_State* L) : charge_(budget_of(L)) {
  if (call_depth++ == 0) {
    interrupt_pending = 0;
    const struct sigaction handler = action(on_sigint_while_running);
    sigaction(SIGINT, &handler, &previous_);
  }
  guard_hooks(L);
}

InterruptibleCall::~InterruptibleCall() {
  if (--call_depth > 0) return;
  sigaction(SIGINT, &previous_, nullptr);
  interrupt_pending = 0;  // a Ctrl-C that came as the call was returning must not stop the next
}

bool interrupt_requested() { return interrupt_pending != 0; }

void clear_interrupt() { interrupt_pending = 0; }

// libedit catches SIGWINCH itself while it reads a line, but only once: its handler resizes,
// then puts back the action it found (this one) and raises the signal again. The key reader
// resizes for the later ones (wait_for_key).
PromptInterrupt::PromptInterrupt() {
  prompt_interrupted = 0;
  window_resized = 0;
  const struct sigaction handler = action(on_sigint_at_prompt);
  sigaction(SIGINT, &handler, &previous_);
  struct sigaction resize = action(on_resize_at_prompt);
  resize.sa_flags = SA_RESTART;  // a read(2) goes on (the lesson keys); ppoll(2) never does
  sigaction(SIGWINCH, &resize, &previous_resize_);
}

PromptInterrupt::~PromptInterrupt() {
  sigaction(SIGWINCH, &previous_resize_, nullptr);
  sigaction(SIGINT, &previous_, nullptr);
}

bool PromptInterrupt::happened() const { return prompt_interrupted != 0; }

KeyWait wait_for_key(int fd) {
  sigset_t signals, previous;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGWINCH);
  sigprocmask(SIG_BLOCK, &signals, &previous);
  sigset_t while_waiting = previous;
  sigdelset(&while_waiting, SIGINT);
  sigdelset(&while_waiting, SIGWINCH);
  KeyWait result = KeyWait::ready;
  for (;;) {
    if (prompt_interrupted != 0) {
      result = KeyWait::interrupted;
      break;
    }
    if (window_resized != 0) {
      window_resized = 0;
      result = KeyWait::resized;
      break;
    }
    struct pollfd input {};
    input.fd = fd;
    input.events = POLLIN;
    if (ppoll(&input, 1, nullptr, &while_waiting) >= 0 || errno != EINTR) {
      // Input: unless a Ctrl-C was taken meanwhile by another thread (no other thread should
      // take one, see Watchdog::arm; this keeps the key for the next line if one does).
      if (prompt_interrupted != 0) result = KeyWait::interrupted;
      break;
    }
    // EINTR: a flag above says which signal; another one (SIGCONT, say): wait on.
  }
  sigprocmask(SIG_SETMASK, &previous, nullptr);
  return result;
}

IgnoreStrayInterrupts::IgnoreStrayInterrupts() {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGINT, &ignore, &previous_);
}

IgnoreStrayInterrupts::~IgnoreStrayInterrupts() { sigaction(SIGINT, &previous_, nullptr); }

}  // namespace rigidlab::cli
