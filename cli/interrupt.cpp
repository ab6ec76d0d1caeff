#include "cli/interrupt.hpp"

namespace rigidlab::cli {
namespace {

// The state whose code Ctrl-C interrupts, and whether a Ctrl-C is waiting to be raised.
lua_State* volatile running_state = nullptr;
volatile sig_atomic_t interrupt_pending = 0;
volatile sig_atomic_t prompt_interrupted = 0;

// The hook in place before Ctrl-C replaced it (none today; a limit's count hook later): it
// is put back once the interruption has been raised.
struct SavedHook {
  lua_Hook hook = nullptr;
  int mask = 0;
  int count = 0;
};
SavedHook saved_hook;

void restore_hook() {
  interrupt_pending = 0;
  if (running_state != nullptr)
    lua_sethook(running_state, saved_hook.hook, saved_hook.mask, saved_hook.count);
}

[[noreturn]] void interrupt_hook(lua_State* L, lua_Debug*) { raise_interrupt(L); }

// lua.c's laction: lua_sethook is safe to call from a signal handler (lua.h, 5.4).
void on_sigint_while_running(int signal_number) {
  ::signal(signal_number, SIG_DFL);  // a second Ctrl-C terminates the process
  lua_State* L = running_state;
  if (L == nullptr) return;
  if (lua_gethook(L) != interrupt_hook)
    saved_hook = SavedHook{lua_gethook(L), lua_gethookmask(L), lua_gethookcount(L)};
  interrupt_pending = 1;
  lua_sethook(L, interrupt_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT, 1);
}

void on_sigint_at_prompt(int) { prompt_interrupted = 1; }

struct sigaction action(void (*handler)(int)) {
  struct sigaction result {};
  result.sa_handler = handler;
  sigemptyset(&result.sa_mask);
  result.sa_flags = 0;  // no SA_RESTART: a blocking read returns with EINTR
  return result;
}

}  // namespace

InterruptibleCall::InterruptibleCall(lua_State* L) {
  running_state = L;
  interrupt_pending = 0;
  const struct sigaction handler = action(on_sigint_while_running);
  sigaction(SIGINT, &handler, &previous_);
}

InterruptibleCall::~InterruptibleCall() {
  sigaction(SIGINT, &previous_, nullptr);
  // A Ctrl-C that came as the call was returning must not stop the next one.
  if (interrupt_pending) restore_hook();
  running_state = nullptr;
}

bool interrupt_requested() { return interrupt_pending != 0; }

void raise_interrupt(lua_State* L) {
  restore_hook();
  luaL_error(L, "interrupted!");
  __builtin_unreachable();
}

PromptInterrupt::PromptInterrupt() {
  prompt_interrupted = 0;
  const struct sigaction handler = action(on_sigint_at_prompt);
  sigaction(SIGINT, &handler, &previous_);
}

PromptInterrupt::~PromptInterrupt() { sigaction(SIGINT, &previous_, nullptr); }

bool PromptInterrupt::happened() const { return prompt_interrupted != 0; }

}  // namespace rigidlab::cli
