#include "cli/lesson_keys.hpp"

#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "cli/interrupt.hpp"

namespace rigidlab::cli {
namespace {

// While alive, the terminal on stdin delivers each key at once, without echo; ISIG stays on,
// so Ctrl-C still signals. Does nothing (ok() is false) when stdin is not a terminal.
class SingleKeys {
 public:
  SingleKeys() {
    if (!isatty(STDIN_FILENO) || tcgetattr(STDIN_FILENO, &saved_) != 0) return;
    termios raw = saved_;
    raw.c_lflag &= static_cast<tcflag_t>(~(ICANON | ECHO));
    raw.c_cc[VMIN] = 1;
    raw.c_cc[VTIME] = 0;
    ok_ = tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
  }
  ~SingleKeys() {
    if (ok_) tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
  }
  SingleKeys(const SingleKeys&) = delete;
  SingleKeys& operator=(const SingleKeys&) = delete;
  bool ok() const { return ok_; }

  // The rest of an escape sequence: what arrives within 0.1 s.
  std::string pending() const {
    termios wait = saved_;
    wait.c_lflag &= static_cast<tcflag_t>(~(ICANON | ECHO));
    wait.c_cc[VMIN] = 0;
    wait.c_cc[VTIME] = 1;
    tcsetattr(STDIN_FILENO, TCSANOW, &wait);
    std::string rest;
    char c;
    while (rest.size() < 16 && ::read(STDIN_FILENO, &c, 1) == 1) rest += c;
    return rest;
  }

 private:
  termios saved_{};
  bool ok_ = false;
};

KeyPress from_byte(unsigned char c) {
  if (c == '\r' || c == '\n' || c == ' ') return {KeyPress::Kind::enter, 0};
  if (c == 4) return {KeyPress::Kind::end, 0};  // Ctrl-D
  if (c > ' ' && c < 127) return {KeyPress::Kind::letter, static_cast<char>(c)};
  return {KeyPress::Kind::other, 0};
}

KeyPress key_from_terminal(const SingleKeys& keys) {
  const PromptInterrupt interrupt;  // Ctrl-C ends the read (EINTR) instead of the process
  unsigned char c;
  for (;;) {
    const ssize_t n = ::read(STDIN_FILENO, &c, 1);
    if (n == 1) break;
    if (n < 0 && errno == EINTR && !interrupt.happened()) continue;
    return {KeyPress::Kind::end, 0};
  }
  if (c != 27) return from_byte(c);
  const std::string rest = keys.pending();  // ESC [ C and ESC O C: right; D: left
  if (rest == "[C" || rest == "OC") return {KeyPress::Kind::enter, 0};
  if (rest == "[D" || rest == "OD") return {KeyPress::Kind::back, 0};
  return {KeyPress::Kind::other, 0};
}

}  // namespace

bool read_line(std::string& line) {
  const PromptInterrupt interrupt;
  line.clear();
  bool any = false;
  for (int c; (c = std::fgetc(stdin)) != EOF;) {
    any = true;
    if (c == '\n') return true;
    if (line.size() < 4096) line += static_cast<char>(c);  // the rest is read, not kept
  }
  std::clearerr(stdin);  // a Ctrl-C interrupts fgetc: not the end of the input for later reads
  return any && !interrupt.happened();
}

KeyPress read_key() {
  {
    const SingleKeys keys;
    if (keys.ok()) return key_from_terminal(keys);
  }
  std::string line;
  if (!read_line(line)) return {KeyPress::Kind::end, 0};
  while (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.empty()) return {KeyPress::Kind::enter, 0};
  if (line.size() == 1) return from_byte(static_cast<unsigned char>(line[0]));
  return {KeyPress::Kind::other, 0};
}

}  // namespace rigidlab::cli
