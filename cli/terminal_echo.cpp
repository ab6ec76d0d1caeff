#include "cli/terminal_echo.hpp"

#include <unistd.h>

namespace rigidlab::cli {
namespace {
constexpr tcflag_t echo_bits = ECHO | ECHONL;
}  // namespace

NoEcho::NoEcho() {
  termios modes{};
  if (tcgetattr(STDIN_FILENO, &modes) != 0) return;
  echo_ = modes.c_lflag & echo_bits;
  modes.c_lflag &= ~echo_bits;
  active_ = tcsetattr(STDIN_FILENO, TCSANOW, &modes) == 0;
}

NoEcho::~NoEcho() {
  termios modes{};
  if (!active_ || tcgetattr(STDIN_FILENO, &modes) != 0) return;
  modes.c_lflag = (modes.c_lflag & ~echo_bits) | echo_;
  tcsetattr(STDIN_FILENO, TCSANOW, &modes);
}

}  // namespace rigidlab::cli
