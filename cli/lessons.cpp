#include "cli/lessons.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "cli/check.hpp"
#include "cli/lesson_files.hpp"
#include "cli/limits.hpp"
#include "lua/lesson.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

int terminal_width() {
  winsize size{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col >= 20) return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) return std::max(20, std::atoi(columns));
  return 80;
}

// Display width of UTF-8 text: counts code points, not bytes.
size_t display_width(const std::string& text) {
  size_t width = 0;
  for (unsigned char c : text) width += (c & 0xC0) != 0x80;
  return width;
}

// Wraps each paragraph of `text` to `width` columns with `indent`; blank lines separate
// paragraphs and lines starting with spaces are kept as they are (formulas, lists).
std::string wrap(const std::string& text, size_t width, const std::string& indent) {
  std::string out;
  std::istringstream lines(text);
  std::string line, paragraph;
  auto flush = [&] {
    std::istringstream words(paragraph);
    std::string word, current;
    for (; words >> word;) {
      if (!current.empty() && display_width(indent + current + " " + word) > width) {
        out += indent + current + "\n";
        current.clear();
      }
      current += (current.empty() ? "" : " ") + word;
    }
    if (!current.empty()) out += indent + current + "\n";
    paragraph.clear();
  };
  while (std::getline(lines, line)) {
    if (line.find_first_not_of(" \t") == std::string::npos) {
      flush();
      out += "\n";
    } else if (line[0] == ' ') {
      flush();
      out += indent + line + "\n";
    } else {
      paragraph += " " + line;
    }
  }
  flush();
  return out;
}

bool interactive() { return isatty(STDIN_FILENO) && isatty(STDOUT_FILENO); }

// Reads one line of the user's answer; false at end of input.
bool read_answer(std::string& answer) {
  char buffer[256];
  if (std::fgets(buffer, sizeof buffer, stdin) == nullptr) return false;
  answer = buffer;
  while (!answer.empty() && (answer.back() == '\n' || answer.back() == '\r')) answer.pop_back();
  return true;
}

void print_step_header(lua_State* L, int lesson, int number, int count) {
  lua_getfield(L, lesson, "steps");
  lua_geti(L, -1, number);
  const int step = lua_gettop(L);
  const int width = std::min(terminal_width(), 100);
  const std::string title = "Step " + std::to_string(number) + "/" + std::to_string(count) +
                            ": " + field_string(L, step, "title");
  std::string rule(std::max<int>(3, width - static_cast<int>(display_width(title)) - 4), '-');
  std::printf("\n-- %s %s\n\n", title.c_str(), rule.c_str());
  std::fputs(wrap(field_string(L, step, "text"), width, "  ").c_str(), stdout);
  const std::string formula = field_string(L, step, "formula");
  if (!formula.empty()) {
    std::printf("\n");
    std::istringstream lines(formula);
    for (std::string line; std::getline(lines, line);) std::printf("      %s\n", line.c_str());
  }
  std::printf("\n");
  lua_pop(L, 2);
}

// A lesson being stepped through, and how it went.
struct LessonRun {
  const fs::path* path;
  bool loaded = false;
  bool failed = false;
  int passed = 0, total = 0;
};

// Untrusted lessons are timed per step (the wait at the prompt is not timed).
void run_timed_step(lua_State* L, int lesson, int ctx, int number, LessonRun& run) {
  std::string error;
  const TimedRun timed(L);
  if (!run_step(L, lesson, ctx, number, error)) {
    if (const LimitedState* limits = LimitedState::of(L)) error = limits->explain(error);
    std::printf("  error: %s\n", error.c_str());
    run.failed = true;
  }
}

// Steps through the lesson of the LessonRun (argument 1), in protected mode: an error anywhere,
// even in the lesson table's metamethods, is reported, not fatal.
int present_protected(lua_State* L) {
  LessonRun& run = *static_cast<LessonRun*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  rigidlab::lua::open_all(L);
  if (!trusted(*run.path)) rigidlab::lua::apply_sandbox(L);
  std::string error;
  if (!load_lesson(L, *run.path, error)) {
    std::fflush(stdout);
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    run.failed = true;
    return 0;
  }
  run.loaded = true;
  const int lesson = lua_gettop(L);
  rigidlab::lua::LessonTally& tally = rigidlab::lua::push_lesson_context(L, false);
  const int ctx = lua_gettop(L);
  std::printf("%s — %s\n  source: %s\n", field_string(L, lesson, "id").c_str(),
              field_string(L, lesson, "title").c_str(), field_string(L, lesson, "source").c_str());
  const int count = steps_count(L, lesson);
  for (int number = 1; number <= count;) {
    print_step_header(L, lesson, number, count);
    run_timed_step(L, lesson, ctx, number, run);
    std::fflush(stdout);
    if (!interactive() || number == count) {
      ++number;
      continue;
    }
    std::printf("\n[Enter] next step   b back   q quit > ");
    std::fflush(stdout);
    std::string answer;
    if (!read_answer(answer) || answer == "q") break;
    number = answer == "b" ? std::max(1, number - 1) : number + 1;
  }
  run.passed = tally.passed;
  run.total = tally.passed + tally.failed;
  run.failed = run.failed || tally.failed > 0;
  return 0;
}

// Steps through one lesson: pauses after each step in a terminal, runs straight through
// otherwise. Ctrl-C stops the step that is running (its error is shown) and the lesson goes
// on. Lessons from outside the lesson directory run under the check limits. Returns 0 when
// every expectation held.
int present_lesson(const fs::path& path) {
  const Limits limits = trusted(path) ? Limits{} : default_check_limits();
  LimitedState state(limits, WhenStuck::exit);
  lua_State* L = state.get();
  if (L == nullptr) {
    std::fprintf(stderr, "rigidlab: cannot create the Lua state: not enough memory\n");
    return 1;
  }
  LessonRun run{&path};
  lua_pushcfunction(L, present_protected);
  lua_pushlightuserdata(L, &run);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
    const char* message = lua_tostring(L, -1);
    std::fflush(stdout);
    std::fprintf(stderr, "rigidlab: %s\n",
                 state.explain(message != nullptr ? message : "error").c_str());
    return 1;
  }
  if (!run.loaded) return 1;
  std::printf("\n%d of %d checks passed%s\n", run.passed, run.total, run.failed ? "" : " ✓");
  return run.failed ? 1 : 0;
}

struct LessonInfo {
  fs::path path;
  std::string id, title, source, error;
};

// Reads the id, title and source of a loaded lesson (lua_pcall'd: the fields may be anything).
int read_fields(lua_State* L) {
  auto& info = *static_cast<LessonInfo*>(lua_touserdata(L, 2));
  info.id = field_string(L, 1, "id");
  info.title = field_string(L, 1, "title");
  info.source = field_string(L, 1, "source");
  return 0;
}

// Loading a lesson runs its file: under the check limits, so that a file that loops cannot
// hang the list.
std::vector<LessonInfo> read_lesson_infos() {
  std::vector<LessonInfo> infos;
  for (const fs::path& path : lesson_files()) {
    LessonInfo info;
    info.path = path;
    info.id = path.stem().string();
    LimitedState state(default_check_limits(), WhenStuck::exit);
    lua_State* L = state.get();
    const TimedRun timed(L);
    lua_pushcfunction(L, [](lua_State* L) {
      rigidlab::lua::open_all(L);
      return 0;
    });
    if (lua_pcall(L, 0, 0, 0) != LUA_OK) {
      info.error = "cannot open the libraries: not enough memory";
    } else if (load_lesson(L, path, info.error)) {
      lua_pushcfunction(L, read_fields);
      lua_insert(L, -2);
      lua_pushlightuserdata(L, &info);
      if (lua_pcall(L, 2, 0, 0) != LUA_OK) info.error = lua_tostring(L, -1);
    }
    infos.push_back(info);
  }
  return infos;
}

void print_lesson_table(const std::vector<LessonInfo>& infos, bool numbered) {
  size_t id_width = 2, title_width = 5;
  for (const auto& info : infos) {
    id_width = std::max(id_width, display_width(info.id));
    title_width = std::max(title_width, display_width(info.title));
  }
  int number = 0;
  for (const auto& info : infos) {
    if (numbered) std::printf("%3d  ", ++number);
    std::string id = info.id + std::string(id_width - display_width(info.id), ' ');
    if (!info.error.empty()) {
      std::printf("%s  (cannot load: %s)\n", id.c_str(), info.error.c_str());
      continue;
    }
    std::string title = info.title + std::string(title_width - display_width(info.title), ' ');
    std::printf("%s  %s  %s\n", id.c_str(), title.c_str(), info.source.c_str());
  }
}

}  // namespace

int list_lessons() {
  const auto infos = read_lesson_infos();
  if (infos.empty()) {
    std::fprintf(stderr, "rigidlab: no lessons in %s\n", lesson_directory().c_str());
    return 1;
  }
  print_lesson_table(infos, false);
  return 0;
}

int run_lesson(const std::string& id_or_file) {
  if (!id_or_file.empty()) {
    fs::path path;
    if (!resolve_lesson(id_or_file, path)) {
      std::fprintf(stderr, "rigidlab: no lesson '%s' (rigidlab lessons lists them)\n",
                   id_or_file.c_str());
      return 2;
    }
    return present_lesson(path);
  }
  const auto infos = read_lesson_infos();
  if (infos.empty()) {
    std::fprintf(stderr, "rigidlab: no lessons in %s\n", lesson_directory().c_str());
    return 1;
  }
  for (;;) {
    std::printf("rigidlab lessons — the worked examples of the course, step by step\n\n");
    print_lesson_table(infos, true);
    std::printf("\nlesson number or id (q quits) > ");
    std::fflush(stdout);
    std::string answer;
    if (!read_answer(answer) || answer == "q") {
      std::printf("\n");
      return 0;
    }
    if (answer.empty()) continue;
    fs::path path;
    const int number = std::atoi(answer.c_str());
    if (number >= 1 && number <= static_cast<int>(infos.size()))
      path = infos[number - 1].path;
    else if (!resolve_lesson(answer, path)) {
      std::printf("no lesson '%s'\n\n", answer.c_str());
      continue;
    }
    present_lesson(path);
    std::printf("\n");
  }
}

}  // namespace rigidlab::cli
