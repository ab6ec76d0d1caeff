// The terminal of a live view (w:view, rigidlab view): raw keyboard input, the alternate
// screen, the cursor hidden, and the window's size; and the keys of the view decoded from the
// bytes a terminal sends (ECMA-48 control sequences, xterm's modifier parameter for shift).
// The session restores the terminal when it ends however it ends: the destructor (normal
// return, a Lua error unwinding, Ctrl-C raised as an error) and, for os.exit, an atexit
// handler.
#pragma once

#include <termios.h>

#include <string>
#include <vector>

namespace rigidlab::present {

enum class Key {
  quit,          // q
  pause,         // space
  step_forward,  // right arrow
  step_back,     // left arrow
  faster,        // + (or =)
  slower,        // - (or _)
  orbit_left,    // shift + left arrow (or a)
  orbit_right,   // shift + right arrow (or d)
  orbit_up,      // up arrow, with or without shift (or w)
  orbit_down,    // down arrow, with or without shift (or s)
  overlays,      // o
};

// Decodes the keys at the front of `input` and removes the bytes it used. An escape
// sequence cut short stays in `input` for the next read; bytes of no key are dropped.
std::vector<Key> decode_keys(std::string& input);

class TerminalSession {
 public:
  // Switches the terminal on `in` / `out` to raw input (no echo, no line editing; Ctrl-C still
  // signals), the alternate screen and a hidden cursor. Throws std::runtime_error when they
  // are not terminals, or when a session is already active.
  TerminalSession(int in, int out);
  ~TerminalSession();
  TerminalSession(const TerminalSession&) = delete;
  TerminalSession& operator=(const TerminalSession&) = delete;

  // The window's size in cells; false when unknown.
  bool size(int& columns, int& rows) const;
  // Waits at most `timeout_ms` for input and appends what came. Returns early (false) when a
  // signal interrupted the wait: the caller then checks for Ctrl-C.
  bool read(std::string& input, int timeout_ms);
  // Writes all of `text` (retrying short writes).
  void write(const std::string& text);

 private:
  int in_, out_;
  termios saved_{};
};

}  // namespace rigidlab::present
