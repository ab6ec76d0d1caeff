#include "cli/terminal_echo.hpp"

#include <unistd.h>

#include <cstdlib>

namespace rigidlab::cli {
namespace {

constexpr tcflag_t echo_bits = ECHO | ECHONL;

// The echo bits from before the outermost live NoEcho, put back at exit as well: a trusted
// lesson may end the process with os.exit while one is alive, and the shell must not be left
// without echo.
tcflag_t echo_at_exit = 0;
bool restore_at_exit = false;

void set_echo_bits(tcflag_t bits) {
  termios modes{};
  if (tcgetattr(STDIN_FILENO, &modes) != 0) return;
  modes.c_lflag = (modes.c_lflag & ~echo_bits) | bits;
  tcsetattr(STDIN_FILENO, TCSANOW, &modes);
}

void restore_echo_at_exit() {
  if (restore_at_exit) set_echo_bits(echo_at_exit);
}

}  // namespace

NoEcho::NoEcho() {
  termios modes{};
  if (tcgetattr(STDIN_FILENO, &modes) != 0) return;
  echo_ = modes.c_lflag & echo_bits;
  modes.c_lflag &= ~echo_bits;
  active_ = tcsetattr(STDIN_FILENO, TCSANOW, &modes) == 0;
  if (active_ && !restore_at_exit) {
    static const bool registered = std::atexit(restore_echo_at_exit) == 0;
    (void)registered;
    echo_at_exit = echo_;
    restore_at_exit = outermost_ = true;
  }
}

NoEcho::~NoEcho() {
  if (!active_) return;
  set_echo_bits(echo_);
  if (outermost_) restore_at_exit = false;
}

}  // namespace rigidlab::cli
