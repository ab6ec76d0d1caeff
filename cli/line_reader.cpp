#include "cli/line_reader.hpp"

#include <editline/readline.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cwchar>

#include "cli/completion.hpp"
#include "cli/history_file.hpp"
#include "cli/interrupt.hpp"
#include "cli/terminal_echo.hpp"

namespace rigidlab::cli {
namespace {

constexpr int history_size = 1000;  // entries kept in the file

// libedit's key reader (rl_getc_function): the next character typed, or -1 (the line ends) for
// a Ctrl-C or the end of the input. libedit's own reader blocks in read(2) at once, so a
// Ctrl-C that came while it handled the previous key was noticed only when the line was
// entered, and that line was dropped (cli/interrupt.hpp, wait_for_key). A window resize
// after the first in a line is passed on to libedit here (see PromptInterrupt). libedit's readline
// layer takes what this returns as one wide character, so the bytes of a multibyte character
// (é, →) are decoded here, in the terminal's locale; like libedit, an invalid byte is dropped.
int read_key(FILE* stream) {
  const int fd = fileno(stream);
  char bytes[MB_LEN_MAX];
  size_t count = 0;
  for (;;) {
    const KeyWait wait = wait_for_key(fd);
    if (wait == KeyWait::interrupted) return -1;
    if (wait == KeyWait::resized) {
      rl_resize_terminal();
      continue;
    }
    const ssize_t n = ::read(fd, bytes + count, 1);
    if (n < 0 && errno == EINTR) continue;  // the wait sees whether it was a Ctrl-C
    if (n <= 0) return -1;
    ++count;
    while (count > 0) {
      std::mbstate_t state{};
      wchar_t character = 0;
      const size_t used = std::mbrtowc(&character, bytes, count, &state);
      if (used == static_cast<size_t>(-2)) {  // incomplete: read on, unless it cannot end
        if (count == sizeof bytes) count = 0;
        break;
      }
      if (used != static_cast<size_t>(-1)) return static_cast<int>(character);
      // Invalid: the last byte may start a character of its own.
      if (count > 1) {
        bytes[0] = bytes[count - 1];
        count = 1;
      } else {
        count = 0;
      }
    }
  }
}

class TerminalReader final : public LineReader {
 public:
  explicit TerminalReader(lua_State* L) {
    // Before anything initialises libedit: it takes rl_getc_function only then.
    rl_getc_function = read_key;
    std::setlocale(LC_CTYPE, "");  // multibyte input (é, →) in a UTF-8 terminal
    rl_readline_name = "rigidlab";  // for conditionals in ~/.editrc
    install_completion(L);
    using_history();
    stifle_history(history_size);
    history_.load();
    if (history_length > 0) {
      if (HIST_ENTRY* last = history_get(history_base + history_length - 1)) last_ = last->line;
    }
  }

  ReadStatus read(const char* prompt, std::string& line) override {
    PromptInterrupt interrupt;
    char* text = nullptr;
    {
      const NoEcho no_echo;  // from before libedit's prompt: see terminal_echo.hpp
      text = readline(prompt);
    }
    if (interrupt.happened()) {  // Ctrl-C: drop what was typed, a fresh prompt
      std::free(text);
      std::fputs("\n", stdout);
      return ReadStatus::interrupted;
    }
    if (text == nullptr) {  // Ctrl-D: what follows starts on a line of its own
      std::fputs("\n", stdout);
      return ReadStatus::end;
    }
    line = text;
    std::free(text);
    return ReadStatus::line;
  }

  void remember(const std::string& chunk) override {
    if (chunk.find_first_not_of(" \t") == std::string::npos || chunk == last_) return;
    last_ = chunk;
    add_history(chunk.c_str());
    history_.save();
  }

 private:
  HistoryFile history_;
  std::string last_;  // the newest entry: a repeated chunk is not stored twice
};

class StreamReader final : public LineReader {
 public:
  StreamReader() = default;
  StreamReader(const StreamReader&) = delete;
  StreamReader& operator=(const StreamReader&) = delete;
  ~StreamReader() override { std::free(buffer_); }

  ReadStatus read(const char*, std::string& line) override {
    const ssize_t length = getline(&buffer_, &capacity_, stdin);
    if (length < 0) return ReadStatus::end;
    line.assign(buffer_, static_cast<size_t>(length));
    if (!line.empty() && line.back() == '\n') line.pop_back();
    return ReadStatus::line;
  }

  void remember(const std::string&) override {}

 private:
  char* buffer_ = nullptr;
  size_t capacity_ = 0;
};

}  // namespace

std::unique_ptr<LineReader> make_terminal_reader(lua_State* L) {
  return std::make_unique<TerminalReader>(L);
}

std::unique_ptr<LineReader> make_stream_reader() { return std::make_unique<StreamReader>(); }

}  // namespace rigidlab::cli
