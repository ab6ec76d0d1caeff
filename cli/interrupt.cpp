#include "cli/interrupt.hpp"

#include <time.h>
#include <unistd.h>

#include "cli/hook_guard.hpp"
#include "cli/limits.hpp"

namespace rigidlab::cli {
namespace {

// Whether a Ctrl-C is waiting to be raised, and since when (CLOCK_MONOTONIC).
volatile sig_atomic_t interrupt_pending = 0;
struct timespec pending_since {};
volatile sig_atomic_t prompt_interrupted = 0;
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

PromptInterrupt::PromptInterrupt() {
  prompt_interrupted = 0;
  const struct sigaction handler = action(on_sigint_at_prompt);
  sigaction(SIGINT, &handler, &previous_);
}

PromptInterrupt::~PromptInterrupt() { sigaction(SIGINT, &previous_, nullptr); }

bool PromptInterrupt::happened() const { return prompt_interrupted != 0; }

IgnoreStrayInterrupts::IgnoreStrayInterrupts() {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGINT, &ignore, &previous_);
}

IgnoreStrayInterrupts::~IgnoreStrayInterrupts() { sigaction(SIGINT, &previous_, nullptr); }

}  // namespace rigidlab::cli
