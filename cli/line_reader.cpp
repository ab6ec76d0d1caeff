#include "cli/line_reader.hpp"

#include <editline/readline.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cli/completion.hpp"
#include "cli/interrupt.hpp"

namespace rigidlab::cli {
namespace {

constexpr int history_size = 1000;  // entries kept in the file

// $HOME/.rigidlab_history, through a symbolic link to the file it names; "" without HOME.
std::string history_file() {
  const char* home = std::getenv("HOME");
  if (home == nullptr || *home == '\0') return "";
  const std::string path = std::string(home) + "/.rigidlab_history";
  char resolved[PATH_MAX];
  return realpath(path.c_str(), resolved) != nullptr ? resolved : path;
}

class TerminalReader final : public LineReader {
 public:
  explicit TerminalReader(lua_State* L) : history_path_(history_file()) {
    std::setlocale(LC_CTYPE, "");  // multibyte input (é, →) in a UTF-8 terminal
    rl_readline_name = "rigidlab";  // for conditionals in ~/.editrc
    install_completion(L);
    using_history();
    stifle_history(history_size);
    if (!history_path_.empty()) read_history(history_path_.c_str());
    if (history_length > 0) {
      if (HIST_ENTRY* last = history_get(history_base + history_length - 1)) last_ = last->line;
    }
  }

  ReadStatus read(const char* prompt, std::string& line) override {
    PromptInterrupt interrupt;
    char* text = readline(prompt);
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
    save();
  }

 private:
  // Rewrites the file through a temporary one and a rename, so an interrupted write never
  // leaves a truncated history. Says once why, when it cannot.
  void save() {
    if (history_path_.empty() || save_failed_) return;
    const std::string temporary = history_path_ + ".tmp" + std::to_string(getpid());
    int error = write_history(temporary.c_str());
    if (error == 0 && std::rename(temporary.c_str(), history_path_.c_str()) != 0) error = errno;
    if (error == 0) return;
    std::remove(temporary.c_str());
    save_failed_ = true;
    std::fprintf(stderr, "rigidlab: the history is not saved (cannot write %s: %s)\n",
                 history_path_.c_str(), std::strerror(error));
  }

  std::string history_path_;
  std::string last_;  // the newest entry: a repeated chunk is not stored twice
  bool save_failed_ = false;
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
