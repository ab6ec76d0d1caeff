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
#include "lua/text_layout.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;
using lua::display_width;

namespace {

// The terminal's columns, else $COLUMNS, else 0 (unknown: output to a file or a pipe).
int terminal_width() {
  winsize size{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) return std::max(0, std::atoi(columns));
  return 0;
}

// Columns a lesson is laid out in: the terminal's, at least 40 (narrower wraps every few
// words) and at most 100 (longer lines are hard to read); 80 when unknown.
int lesson_width() {
  const int columns = terminal_width();
  return columns == 0 ? 80 : std::clamp(columns, 40, 100);
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
  const int width = lesson_width();
  const std::string title = "-- Step " + std::to_string(number) + "/" + std::to_string(count) +
                            ": " + field_string(L, step, "title");
  // "-- Step 2/5: title -----" filled to the width; a title too long for one line is wrapped
  const int rule = width - static_cast<int>(display_width(title)) - 1;
  if (rule >= 3)
    std::printf("\n%s %s\n\n", title.c_str(), std::string(rule, '-').c_str());
  else
    std::printf("\n%s\n", lua::fit_words_after("-- ", title.substr(3), width).c_str());
  std::fputs(lua::fit_paragraphs(field_string(L, step, "text"), "  ", width).c_str(),
             stdout);
  const std::string formula = field_string(L, step, "formula");
  if (!formula.empty()) {
    std::printf("\n");
    std::istringstream lines(formula);
    for (std::string line; std::getline(lines, line);) std::printf("      %s\n", line.c_str());
  }
  std::printf("\n");
  lua_pop(L, 2);
}

// "id — title" and the source, one document per line (a source lists them split by "; "),
// each wrapped to the width under its start.
void print_lesson_heading(lua_State* L, int lesson, int width) {
  const std::string id = field_string(L, lesson, "id") + " — ";
  std::fputs(lua::fit_words_after(id, field_string(L, lesson, "title"), width).c_str(), stdout);
  const std::string source = field_string(L, lesson, "source");
  const char* label = "  source: ";
  for (size_t start = 0; start <= source.size();) {
    size_t end = source.find("; ", start);
    if (end == std::string::npos) end = source.size();
    const std::string document = source.substr(start, end - start);
    std::fputs(lua::fit_words_after(label, document, width).c_str(), stdout);
    label = "          ";
    start = end + 2;
  }
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
  lua::open_all(L);
  if (!trusted(*run.path)) lua::apply_sandbox(L);
  std::string error;
  if (!load_lesson(L, *run.path, error)) {
    std::fflush(stdout);
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    run.failed = true;
    return 0;
  }
  run.loaded = true;
  const int lesson = lua_gettop(L);
  lua::LessonTally& tally = lua::push_lesson_context(L, false);
  const int ctx = lua_gettop(L);
  tally.width = lesson_width();
  print_lesson_heading(L, lesson, tally.width);
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
      lua::open_all(L);
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

// One row per lesson: id, title and source in columns, fitted to the terminal: the source
// column, cut short, when at least 20 columns are left beside the titles, else none (a lesson
// shows its source in full at the top); titles are cut only when they alone do not fit.
// Written to a file or a pipe (width unknown) nothing is cut.
void print_lesson_table(const std::vector<LessonInfo>& infos, bool numbered) {
  size_t id_width = 2, title_width = 5;
  for (const auto& info : infos) {
    id_width = std::max(id_width, display_width(info.id));
    title_width = std::max(title_width, display_width(info.title));
  }
  const size_t columns = static_cast<size_t>(terminal_width());
  size_t source_width = std::string::npos;
  if (columns > 0) {
    const size_t before_title = (numbered ? 5 : 0) + id_width + 2;  // "%3d  " id "  "
    const size_t left = columns > before_title ? columns - before_title : 0;
    title_width = std::min(title_width, std::max<size_t>(left, 12));
    source_width = left >= title_width + 2 + 20 ? left - title_width - 2 : 0;
  }
  int number = 0;
  for (const auto& info : infos) {
    if (numbered) std::printf("%3d  ", ++number);
    std::string id = info.id + std::string(id_width - display_width(info.id), ' ');
    if (!info.error.empty()) {
      std::printf("%s  (cannot load: %s)\n", id.c_str(), info.error.c_str());
      continue;
    }
    std::string title = lua::truncate_to_width(info.title, title_width);
    if (source_width == 0) {
      std::printf("%s  %s\n", id.c_str(), title.c_str());
      continue;
    }
    title += std::string(title_width - display_width(title), ' ');
    const std::string source = lua::truncate_to_width(info.source, source_width);
    std::printf("%s  %s  %s\n", id.c_str(), title.c_str(), source.c_str());
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
