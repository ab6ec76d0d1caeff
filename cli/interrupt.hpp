// Ctrl-C (SIGINT), as Lua's own lua.c handles it: while Lua code runs, the signal handler sets
// a hook that raises "interrupted!" at the next instruction, so the computation stops with an
// ordinary Lua error and the REPL goes on; a second Ctrl-C before the hook runs (a C function
// that never returns to Lua) terminates the process. At the REPL prompt Ctrl-C only clears
// the line being typed.
//
// A signal handler can reach nothing but globals, so this file keeps the one piece of global
// state of the CLI: the state being interrupted and the flags the handlers set.
#pragma once

#include <lua.hpp>
#include <signal.h>

namespace rigidlab::cli {

// While alive, Ctrl-C interrupts the Lua code running in L (L must be the main thread: the
// hook is set on it). Restores the previous SIGINT action when destroyed.
class InterruptibleCall {
 public:
  explicit InterruptibleCall(lua_State* L);
  ~InterruptibleCall();
  InterruptibleCall(const InterruptibleCall&) = delete;
  InterruptibleCall& operator=(const InterruptibleCall&) = delete;

 private:
  struct sigaction previous_ {};
};

// True when a Ctrl-C is waiting to be raised: the state's stop check (cli/limits.hpp), which
// the engine's long loops poll where no hook can run, then calls raise_interrupt.
bool interrupt_requested();
// Raises "interrupted!" in L and puts back the hook the Ctrl-C replaced.
[[noreturn]] void raise_interrupt(lua_State* L);

// While alive, Ctrl-C sets a flag instead of ending the process, and interrupts a blocking
// read (no SA_RESTART), so the line editor returns. Used around each prompt.
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
};

}  // namespace rigidlab::cli
