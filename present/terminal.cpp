#include "present/terminal.hpp"

#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>

namespace rigidlab::present {
namespace {

// Show the cursor, leave the alternate screen (xterm's private mode 1049), reset colours.
constexpr char restore_sequence[] = "\x1b[0m\x1b[?25h\x1b[?1049l";

// The active session, for the atexit handler (os.exit skips destructors).
int active_out = -1, active_in = -1;
termios active_saved{};

void restore_active() {
  if (active_out < 0) return;
  [[maybe_unused]] ssize_t n = ::write(active_out, restore_sequence, sizeof restore_sequence - 1);
  tcsetattr(active_in, TCSAFLUSH, &active_saved);
  active_out = active_in = -1;
}

// The key of an xterm cursor sequence's final byte, plain or with shift: → and ← step, with
// shift they orbit; ↑ and ↓ orbit with or without shift (nothing else uses them).
bool arrow(char final, bool shift, Key& key) {
  switch (final) {
    case 'C': key = shift ? Key::orbit_right : Key::step_forward; return true;
    case 'D': key = shift ? Key::orbit_left : Key::step_back; return true;
    case 'A': key = Key::orbit_up; return true;
    case 'B': key = Key::orbit_down; return true;
  }
  return false;
}

}  // namespace

std::vector<Key> decode_keys(std::string& input) {
  std::vector<Key> keys;
  std::size_t i = 0;
  while (i < input.size()) {
    const char c = input[i];
    if (c == '\x1b') {
      if (i + 1 >= input.size()) break;  // wait for the rest
      const char kind = input[i + 1];
      if (kind != '[' && kind != 'O') {  // a lone Escape, then another key
        ++i;
        continue;
      }
      // CSI: parameters and intermediates (0x20 to 0x3F), then a final byte (0x40 to 0x7E).
      std::size_t end = i + 2;
      while (end < input.size() && input[end] >= 0x20 && input[end] <= 0x3F) ++end;
      if (end >= input.size()) break;  // cut short: wait
      const std::string parameters = input.substr(i + 2, end - i - 2);
      Key key;
      // Shift is modifier 2: "1;2C" (xterm); a bare "C" or "OC" is the plain arrow.
      const bool shift = parameters == "1;2";
      if ((parameters.empty() || shift) && arrow(input[end], shift, key)) keys.push_back(key);
      i = end + 1;
      continue;
    }
    switch (c) {
      case 'q': case 'Q': keys.push_back(Key::quit); break;
      case ' ': keys.push_back(Key::pause); break;
      case '+': case '=': keys.push_back(Key::faster); break;
      case '-': case '_': keys.push_back(Key::slower); break;
      case 'a': keys.push_back(Key::orbit_left); break;
      case 'd': keys.push_back(Key::orbit_right); break;
      case 'w': keys.push_back(Key::orbit_up); break;
      case 's': keys.push_back(Key::orbit_down); break;
      case 'o': case 'O': keys.push_back(Key::overlays); break;
      default: break;
    }
    ++i;
  }
  input.erase(0, i);
  return keys;
}

TerminalSession::TerminalSession(int in, int out) : in_(in), out_(out) {
  if (active_out >= 0) throw std::runtime_error("a live view is already running");
  if (!isatty(in) || !isatty(out))
    throw std::runtime_error("a live view needs a terminal (use w:render for single frames)");
  if (tcgetattr(in, &saved_) != 0) throw std::runtime_error("cannot read the terminal's settings");
  termios raw = saved_;
  raw.c_lflag &= ~(ICANON | ECHO);  // ISIG kept: Ctrl-C interrupts as everywhere else
  raw.c_iflag &= ~(IXON | ICRNL);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  if (tcsetattr(in, TCSAFLUSH, &raw) != 0) throw std::runtime_error("cannot set the terminal up");
  active_in = in;
  active_out = out;
  active_saved = saved_;
  static bool registered = false;
  if (!registered) registered = std::atexit(restore_active) == 0;
  write("\x1b[?1049h\x1b[?25l\x1b[2J");
}

TerminalSession::~TerminalSession() { restore_active(); }

bool TerminalSession::size(int& columns, int& rows) const {
  winsize w{};
  if (ioctl(out_, TIOCGWINSZ, &w) != 0 || w.ws_col == 0 || w.ws_row == 0) return false;
  columns = w.ws_col;
  rows = w.ws_row;
  return true;
}

bool TerminalSession::read(std::string& input, int timeout_ms) {
  pollfd p{in_, POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) return errno != EINTR;
  if (ready == 0) return true;
  char buffer[256];
  const ssize_t n = ::read(in_, buffer, sizeof buffer);
  if (n > 0) input.append(buffer, static_cast<std::size_t>(n));
  return !(n < 0 && errno == EINTR);
}

void TerminalSession::write(const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(out_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the terminal went away: nothing more to show
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace rigidlab::present
