// Ctrl-C (SIGINT) while Lua code runs: the signal handler only raises a flag, which the limits'
// count hook (cli/limits.hpp, installed on every thread of the state, coroutines included,
// every 1000 instructions at most) and the stop check that the engine's long loops poll turn
// into the error "interrupted!": the computation stops with an ordinary Lua error and the REPL
// goes on. (lua.c sets a hook from the signal handler instead; hooks are per thread, so that
// misses a loop inside a coroutine.) More Ctrl-Cs while the first one waits change nothing;
// once one has waited for a second, a C function is not returning (a backtracking
// string.find): the next Ctrl-C ends the process, the only way out there. At the REPL prompt
// Ctrl-C only clears the line being typed.
//
// A signal handler can reach nothing but globals, so this file keeps the flags the handlers
// set.
#pragma once

#include <lua.hpp>
#include <signal.h>

#include "cli/memory_budget.hpp"

namespace rigidlab::cli {

// While alive, the Lua code called in L is the user's: Ctrl-C interrupts it, the C++ memory it
// allocates (the engine's) is charged to the memory limit of L's LimitedState, and the limits'
// hook is guarded against debug.sethook (cli/hook_guard.hpp). Restores the previous SIGINT
// action when destroyed. Nests.
class InterruptibleCall {
 public:
  explicit InterruptibleCall(lua_State* L);
  ~InterruptibleCall();
  InterruptibleCall(const InterruptibleCall&) = delete;
  InterruptibleCall& operator=(const InterruptibleCall&) = delete;

 private:
  struct sigaction previous_ {};
  ChargeHeap charge_;
};

// True when a Ctrl-C is waiting to be raised; clear_interrupt forgets it (it is being raised).
bool interrupt_requested();
void clear_interrupt();

// While alive, Ctrl-C sets a flag instead of ending the process, and interrupts a blocking
// read (no SA_RESTART), so the line editor returns; a window resize (SIGWINCH) sets another,
// for wait_for_key. Used around each prompt.
class PromptInterrupt {
 public:
  PromptInterrupt();
  ~PromptInterrupt();
  PromptInterrupt(const PromptInterrupt&) = delete;
  PromptInterrupt& operator=(const PromptInterrupt&) = delete;
  // True when Ctrl-C was pressed since construction.
  bool happened() const;

 private:
  struct sigaction previous_ {};
  struct sigaction previous_resize_ {};
};

// For the line editor's key reader, under a PromptInterrupt: waits until `fd` has input (or an
// end or error for read(2) to report), a Ctrl-C comes, also one that came before the wait
// began, while the previous key was being handled (a Tab completion, a redisplay), or the
// window is resized. Checking the flag and then calling read(2) would miss a Ctrl-C that comes
// between the two; ppoll unblocks SIGINT and waits in one system call.
enum class KeyWait { ready, interrupted, resized };
KeyWait wait_for_key(int fd);

// While alive, a Ctrl-C that comes outside a call and a prompt (while the REPL reports an error,
// say: a second Ctrl-C just after the one that stopped a loop) is ignored instead of ending
// the process. For the REPL's whole session.
class IgnoreStrayInterrupts {
 public:
  IgnoreStrayInterrupts();
  ~IgnoreStrayInterrupts();
  IgnoreStrayInterrupts(const IgnoreStrayInterrupts&) = delete;
  IgnoreStrayInterrupts& operator=(const IgnoreStrayInterrupts&) = delete;

 private:
  struct sigaction previous_ {};
};

}  // namespace rigidlab::cli
