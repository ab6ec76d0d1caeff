#include "cli/lessons.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "cli/check.hpp"
#include "cli/lesson_files.hpp"
#include "cli/limit_options.hpp"
#include "cli/limits.hpp"
#include "cli/usage.hpp"
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

// Reads one line of the user's answer, however long; false at end of input.
bool read_answer(std::string& answer) {
  answer.clear();
  for (int c; (c = std::fgetc(stdin)) != EOF;) {
    if (c == '\n') return true;
    if (answer.size() < 4096) answer += static_cast<char>(c);  // the rest is read, not kept
  }
  return !answer.empty();
}

void print_step_header(const lua::LessonSpec& spec, int number) {
  const lua::LessonStep& step = spec.steps[number - 1];
  const int width = lesson_width();
  const std::string title = "-- Step " + std::to_string(number) + "/" +
                            std::to_string(spec.steps.size()) + ": " + step.title;
  // "-- Step 2/5: title -----" filled to the width; a title too long for one line is wrapped
  const int rule = width - static_cast<int>(display_width(title)) - 1;
  if (rule >= 3)
    std::printf("\n%s %s\n\n", title.c_str(), std::string(rule, '-').c_str());
  else
    std::printf("\n%s\n", lua::fit_words_after("-- ", title.substr(3), width).c_str());
  std::fputs(lua::fit_paragraphs(step.text, "  ", width).c_str(), stdout);
  if (!step.formula.empty()) {
    std::printf("\n");
    std::istringstream lines(step.formula);
    for (std::string line; std::getline(lines, line);) std::printf("      %s\n", line.c_str());
  }
  std::printf("\n");
}

// "id — title" and the source, one document per line (a source lists them split by "; "),
// each wrapped to the width under its start; a lesson-wide tolerance with its reason.
void print_lesson_heading(const lua::LessonSpec& spec, int width) {
  std::fputs(lua::fit_words_after(spec.id + " — ", spec.title, width).c_str(), stdout);
  const char* label = "  source: ";
  for (size_t start = 0; start <= spec.source.size();) {
    size_t end = spec.source.find("; ", start);
    if (end == std::string::npos) end = spec.source.size();
    const std::string document = spec.source.substr(start, end - start);
    std::fputs(lua::fit_words_after(label, document, width).c_str(), stdout);
    label = "          ";
    start = end + 2;
  }
  if (spec.has_tolerance)
    std::fputs(lua::fit_words_after("  tolerance: ", lua::describe_tolerance(spec.tolerance) +
                                                         " — " + spec.tolerance.reason, width)
                   .c_str(),
               stdout);
}

// The ctx writes to the terminal.
class TerminalOutput : public lua::LessonOutput {
 public:
  void write(const std::string& lines) override {
    std::fwrite(lines.data(), 1, lines.size(), stdout);
    std::fflush(stdout);
  }
};

// A lesson being stepped through, and how it went. The context outlives the Lua state (the
// ctx userdata points to it; see lua/lesson.hpp).
struct LessonRun {
  const fs::path* path = nullptr;
  TerminalOutput output;
  lua::LessonContext context;
  bool loaded = false;
  bool failed = false;
};

// The limits of a lesson's run. Untrusted lessons run under the check limits, counted over the
// whole lesson: its loading, and every step, but not the wait at the prompt.
class LessonClock {
 public:
  explicit LessonClock(lua_State* L) : state_(LimitedState::of(L)) {
    if (state_ != nullptr) state_->begin_run();
  }
  ~LessonClock() {
    if (state_ != nullptr && running_) state_->end_run();
  }
  LessonClock(const LessonClock&) = delete;
  LessonClock& operator=(const LessonClock&) = delete;
  void pause() {
    if (state_ != nullptr && running_) state_->end_run();
    running_ = false;
  }
  void resume() {
    if (state_ != nullptr && !running_) state_->resume_run();
    running_ = true;
  }
  bool limit_reached() const { return state_ != nullptr && !state_->limit_hit().empty(); }
  std::string explain(const std::string& error) const {
    return state_ != nullptr ? state_->explain(error) : error;
  }

 private:
  LimitedState* state_;
  bool running_ = true;
};

// Steps through the lesson of the LessonRun (argument 1), in protected mode: an error anywhere
// is reported, not fatal.
int present_protected(lua_State* L) {
  LessonRun& run = *static_cast<LessonRun*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  LessonClock clock(L);
  lua::open_all(L);
  if (!trusted(*run.path)) lua::apply_sandbox(L);
  LoadedLesson lesson;
  std::string error;
  if (!load_lesson(L, *run.path, lesson, error)) {
    std::fflush(stdout);
    std::fprintf(stderr, "rigidlab: %s\n", clock.explain(error).c_str());
    run.failed = true;
    return 0;
  }
  run.loaded = true;
  lua::LessonContext& context = run.context;
  context.output = &run.output;
  context.width = lesson_width();
  context.tolerance = lesson.spec.tolerance;
  lua::push_lesson_context(L, context);
  const int ctx = lua_gettop(L);
  print_lesson_heading(lesson.spec, context.width);
  const int count = static_cast<int>(lesson.spec.steps.size());
  for (int number = 1; number <= count;) {
    print_step_header(lesson.spec, number);
    if (!run_step(L, lesson, ctx, number, error)) {
      std::printf("  error: %s\n", clock.explain(error).c_str());
      run.failed = true;
      if (clock.limit_reached()) {  // the limits are the whole lesson's: no step would run
        std::printf("\nThe lesson is stopped: its limits count all of its steps.\n");
        break;
      }
    }
    std::fflush(stdout);
    if (!interactive() || number == count) {
      ++number;
      continue;
    }
    std::printf("\n[Enter] next step   b back   q quit > ");
    std::fflush(stdout);
    std::string answer;
    clock.pause();
    const bool answered = read_answer(answer);
    clock.resume();
    if (!answered || answer == "q") break;
    number = answer == "b" ? std::max(1, number - 1) : number + 1;
  }
  context.ended = true;
  return 0;
}

// Steps through one lesson: pauses after each step in a terminal, runs straight through
// otherwise. Ctrl-C stops the step that is running (its error is shown) and the lesson goes
// on. Lessons from outside the lesson directory run under the check limits (or `limits`, when
// given). Returns 0 when every expectation held.
int present_lesson(const fs::path& path, const Limits* limits) {
  LessonRun run;  // before the state: its context outlives the ctx
  run.path = &path;
  const Limits chosen = limits != nullptr ? *limits
                        : trusted(path)   ? Limits{}
                                          : default_check_limits();
  LimitedState state(chosen, WhenStuck::exit);
  lua_State* L = state.get();
  if (L == nullptr) {
    std::fprintf(stderr, "rigidlab: cannot create the Lua state: not enough memory\n");
    return 1;
  }
  lua_pushcfunction(L, present_protected);
  lua_pushlightuserdata(L, &run);
  const int status = lua_pcall(L, 1, 0, 0);
  run.context.ended = true;
  if (status != LUA_OK) {
    const char* message = lua_tostring(L, -1);
    std::fflush(stdout);
    std::fprintf(stderr, "rigidlab: %s\n",
                 state.explain(message != nullptr ? message : "error").c_str());
    return 1;
  }
  if (!run.loaded) return 1;
  const int total = run.context.passed + run.context.failed;
  const bool failed = run.failed || run.context.failed > 0;
  std::printf("\n%d of %d checks passed%s\n", run.context.passed, total, failed ? "" : " ✓");
  return failed ? 1 : 0;
}

struct LessonInfo {
  fs::path path;
  std::string id, title, source, error;
};

// Opens the libraries and loads the lesson of the LessonInfo (argument 1), in protected mode.
int read_info_protected(lua_State* L) {
  auto& info = *static_cast<LessonInfo*>(lua_touserdata(L, 1));
  lua::open_all(L);
  if (!trusted(info.path)) lua::apply_sandbox(L);
  LoadedLesson lesson;
  if (load_lesson(L, info.path, lesson, info.error)) {
    info.id = lesson.spec.id;
    info.title = lesson.spec.title;
    info.source = lesson.spec.source;
  }
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
    if (L == nullptr) {
      info.error = "cannot create the Lua state: not enough memory";
    } else {
      const TimedRun timed(L);
      lua_pushcfunction(L, read_info_protected);
      lua_pushlightuserdata(L, &info);
      if (lua_pcall(L, 1, 0, 0) != LUA_OK)
        info.error = state.explain(lua_tostring(L, -1) ? lua_tostring(L, -1) : "error");
      else
        info.error = state.explain(info.error);
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
  const bool all_loaded = std::all_of(infos.begin(), infos.end(),
                                      [](const LessonInfo& info) { return info.error.empty(); });
  return all_loaded ? 0 : 1;
}

namespace {

// The menu's answer: a number in the list, or an id in it (the menu reads no file: an answer
// of any length is only compared with the ids).
const LessonInfo* menu_choice(const std::vector<LessonInfo>& infos, const std::string& answer) {
  if (!answer.empty() && answer.size() <= 9 &&
      answer.find_first_not_of("0123456789") == std::string::npos) {
    const size_t number = std::stoul(answer);
    return number >= 1 && number <= infos.size() ? &infos[number - 1] : nullptr;
  }
  for (const LessonInfo& info : infos)
    if (info.id == answer) return &info;
  return nullptr;
}

int run_menu() {
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
    const LessonInfo* choice = menu_choice(infos, answer);
    if (choice == nullptr) {
      std::printf("no lesson '%s'\n\n", lua::truncate_to_width(answer, 60).c_str());
      continue;
    }
    present_lesson(choice->path, nullptr);
    std::printf("\n");
  }
}

}  // namespace

int lesson_command(const std::vector<std::string>& arguments) {
  Limits limits = default_check_limits();
  bool limits_given = false;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string error;
    if (take_limit_option(arguments, i, limits, error)) {
      if (!error.empty()) return usage_error(error);
      limits_given = true;
    } else if (arguments[i] == "--") {
      names.insert(names.end(), arguments.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                   arguments.end());
      break;
    } else if (arguments[i].size() > 1 && arguments[i][0] == '-') {
      return usage_error("unrecognized option '" + lua::truncate_to_width(arguments[i], 60) +
                         "' for 'lesson'");
    } else {
      names.push_back(arguments[i]);
    }
  }
  if (names.size() > 1) return usage_error("'lesson' takes one lesson id or file");
  if (names.empty()) return run_menu();
  fs::path path;
  std::string error;
  if (!resolve_lesson(names[0], path, error)) {
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    return exit_usage;
  }
  return present_lesson(path, limits_given ? &limits : nullptr);
}

}  // namespace rigidlab::cli
