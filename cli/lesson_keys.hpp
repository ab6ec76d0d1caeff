// The keys a student presses between the steps of a lesson. In a terminal a key acts at once
// (b, q, c, r: no Enter needed): the terminal is switched to non-canonical input for the one
// key and back at once; Ctrl-C still signals and, at the prompt, counts as q. Without a
// terminal (a pipe, a file) a key is a line: "" for Enter, "b", "q".
#pragma once

#include <string>

namespace rigidlab::cli {

struct KeyPress {
  enum class Kind {
    enter,   // Enter, space, or the right arrow
    back,    // the left arrow
    letter,  // a printable key: `letter`
    other,   // any other key (an escape sequence, a control character, a longer line)
    end,     // end of input, Ctrl-D or Ctrl-C
  } kind = Kind::other;
  char letter = 0;
};

// Reads one key: at once from a terminal, else one line.
KeyPress read_key();
// Reads one line (the lesson menu's answer), however long (only the first 4096 bytes are
// kept); false at end of input or on Ctrl-C.
bool read_line(std::string& line);

}  // namespace rigidlab::cli
