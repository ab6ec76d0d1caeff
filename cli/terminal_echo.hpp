// Echo off on the terminal of stdin while the program, not the terminal, shows what is typed.
// A program that writes a prompt and only then switches the terminal to raw input (libedit
// does: it waits for the prompt to drain first) leaves a moment in which a key is echoed by
// the terminal itself in cooked mode: an arrow key left "^[[A" behind the REPL's line (which
// libedit, not knowing of it, partly overwrote: "> 1+2A" for "1+2"), and a lesson key showed
// twice ("> cc"). With echo off from before the prompt, what is typed then waits, unechoed,
// for the program to read it.
#pragma once

#include <termios.h>

namespace rigidlab::cli {

// While alive, the terminal on stdin does not echo (ECHO and ECHONL off; canonical input and
// signals as they were). Only those bits are touched, and put back as they were at
// construction, whatever else changed in between, and at exit() if that comes first. Does
// nothing when stdin is not a terminal.
class NoEcho {
 public:
  NoEcho();
  ~NoEcho();
  NoEcho(const NoEcho&) = delete;
  NoEcho& operator=(const NoEcho&) = delete;

 private:
  tcflag_t echo_ = 0;
  bool active_ = false;
  bool outermost_ = false;  // the one whose bits exit() puts back
};

}  // namespace rigidlab::cli
