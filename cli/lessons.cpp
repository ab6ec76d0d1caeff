#include "cli/lessons.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>

#include "cli/check.hpp"
#include "cli/lesson_export.hpp"
#include "cli/lesson_files.hpp"
#include "cli/lesson_keys.hpp"
#include "cli/lesson_menu.hpp"
#include "cli/lesson_page.hpp"
#include "cli/limit_options.hpp"
#include "cli/limits.hpp"
#include "cli/terminal_echo.hpp"
#include "cli/usage.hpp"
#include "cli/view.hpp"
#include "lua/binding.hpp"
#include "lua/lesson.hpp"
#include "lua/render.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"
#include "lua/text_layout.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

bool interactive() { return isatty(STDIN_FILENO) && isatty(STDOUT_FILENO); }

struct LessonOptions {
  const Limits* limits = nullptr;  // the command line's, else the defaults for the lesson
  int from_step = 1;               // --from
  std::string export_path;         // --export FILE.md
};

// What the student chose at the end of a lesson (or by m or q in it).
enum class Next { next_lesson, menu, quit };

// The latest run of a step: `b` and `r` run a step again and its new result replaces the old.
struct StepResult {
  bool ran = false;
  bool error = false;
  int passed = 0, failed = 0;
};

// A lesson being shown, and how it went. It lives outside the Lua state: the ctx points to its
// context (lua/lesson.hpp).
struct LessonRun {
  const LessonFile* file = nullptr;
  const LessonCatalog* catalog = nullptr;
  const LessonOptions* options = nullptr;
  bool interactive = false;
  LessonPage* page = nullptr;  // the terminal, or a transcript (--export)
  lua::LessonContext context;
  std::vector<StepResult> steps;
  bool loaded = false;
  bool usage_error = false;  // --from past the last step
  bool stopped = false;      // a limit ended the lesson
  Next next = Next::quit;

  bool failed() const {
    return std::any_of(steps.begin(), steps.end(),
                       [](const StepResult& s) { return s.error || s.failed > 0; });
  }
};

// The limits of a lesson's run. Untrusted lessons run under the check limits, counted over the
// whole lesson: its loading, and every step, but not the wait at the prompt.
class LessonClock {
 public:
  explicit LessonClock(lua_State* L) : state_(LimitedState::of(L)) {
    if (state_ != nullptr) state_->begin_run();
  }
  ~LessonClock() { pause(); }
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

// print() in a lesson writes to its page, as ctx:say does (upvalue 1: the LessonPage).
int page_print(lua_State* L) {
  auto* page = static_cast<LessonPage*>(lua_touserdata(L, lua_upvalueindex(1)));
  std::string line;
  for (int i = 1, n = lua_gettop(L); i <= n; ++i) {
    size_t length = 0;
    const char* text = luaL_tolstring(L, i, &length);
    line += (i > 1 ? "\t" : "") + std::string(text, length);
    lua_pop(L, 1);
  }
  page->write(line + "\n");
  return 0;
}

// page_print with a std::bad_alloc (the lesson's C++ memory is charged to its limit) raised as
// Lua's memory error.
int guarded_print(lua_State* L) {
  return lua::protect(L, [L] { return page_print(L); });
}

// ---- c: a step's code ------------------------------------------------------------------------

// A number as Lua source that reads back as the same double (the shortest of %.15g..%.17g).
std::string exact_number(double x) {
  char text[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    if (std::strtod(text, nullptr) == x) break;
  }
  return text;
}

std::string exact_list(const double* x, int n) {
  std::string text;
  for (int i = 0; i < n; ++i) text += (i ? ", " : "") + exact_number(x[i]);
  return text;
}

// An upvalue of a step's run function as `c` shows it: a line to paste into the REPL for a
// value, a comment for a function or a table (no __tostring runs: the lesson's clock is paused
// at the prompt).
std::string upvalue_line(lua_State* L, const char* name, int index) {
  const std::string assign = std::string(name) + " = ";
  if (lua_type(L, index) == LUA_TNUMBER)
    return assign + (lua_isinteger(L, index) ? std::to_string(lua_tointeger(L, index))
                                             : exact_number(lua_tonumber(L, index)));
  if (lua_type(L, index) == LUA_TSTRING || lua_type(L, index) == LUA_TBOOLEAN)
    return assign + lua::format_value(L, index, "", true);
  if (const Vec3* v = lua::test_vec3(L, index))
    return assign + "vec3(" + exact_list(v->data(), 3) + ")";
  if (const Quat* q = lua::test_quat(L, index)) {
    const double wxyz[] = {q->w(), q->x(), q->y(), q->z()};
    return assign + "quat(" + exact_list(wxyz, 4) + ")";
  }
  if (const Mat3* m = lua::test_mat3(L, index)) {
    double entries[9];
    for (int k = 0; k < 9; ++k) entries[k] = (*m)(k / 3, k % 3);
    return assign + "mat3(" + exact_list(entries, 9) + ")";
  }
  if (lua_type(L, index) == LUA_TFUNCTION) {
    lua_Debug ar;
    lua_pushvalue(L, index);
    lua_getinfo(L, ">S", &ar);
    if (ar.linedefined > 0)
      return "-- " + std::string(name) + ": the function of lines " +
             std::to_string(ar.linedefined) + " to " + std::to_string(ar.lastlinedefined) +
             " (paste it too)";
  }
  return "-- " + std::string(name) + ": " + lua::a_type_name(L, index) + " of the file";
}

// Lines first to last of a file, the first from its "function", the last up to its "end" (the
// run function's own text, without "run = " and "},").
std::vector<std::string> function_lines(const fs::path& path, int first, int last) {
  std::vector<std::string> lines;
  std::ifstream file(path);
  int number = 0;
  for (std::string line; number < last && std::getline(file, line);)
    if (++number >= first) lines.push_back(line);
  if (lines.empty()) return lines;
  if (const size_t at = lines.front().find("function"); at != std::string::npos)
    lines.front() =
        std::string(lines.front().find_first_not_of(' '), ' ') + lines.front().substr(at);
  if (const size_t at = lines.back().rfind("end"); at != std::string::npos)
    lines.back().resize(at + 3);
  size_t indent = std::string::npos;  // the code's own indentation, removed
  for (const std::string& line : lines)
    if (line.find_first_not_of(' ') != std::string::npos)
      indent = std::min(indent, line.find_first_not_of(' '));
  for (std::string& line : lines) line.erase(0, std::min(indent, line.size()));
  return lines;
}

// What a step's code needs in the REPL: the values it uses from the rest of the file, and the
// file's functions it calls with what they use in turn (dependencies first).
struct PasteLines {
  std::vector<std::string> values, functions;
  std::set<std::string> names;
};

// The text of a function of the lesson's file: "function name(...) ... end" as written, or
// "name = function(...) ... end".
std::string function_text(const fs::path& path, const std::string& name, const lua_Debug& ar) {
  std::vector<std::string> lines = function_lines(path, ar.linedefined, ar.lastlinedefined);
  if (lines.empty()) return "-- " + name + ": (the file cannot be read)\n";
  if (lines.front().rfind("function " + name + "(", 0) != 0)
    lines.front() = name + " = " + lines.front();
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

void collect_uses(lua_State* L, int function, const fs::path& path, PasteLines& paste, int depth) {
  for (int i = 1; const char* name = lua_getupvalue(L, function, i); ++i) {
    const int value = lua_gettop(L);
    const std::string key = name;
    if (key != "_ENV" && !key.empty() && paste.names.insert(key).second) {
      lua_Debug ar;
      bool in_file = false;
      if (lua_type(L, value) == LUA_TFUNCTION) {
        lua_pushvalue(L, value);
        lua_getinfo(L, ">S", &ar);
        in_file = ar.source[0] == '@' && fs::path(ar.source + 1) == path && ar.linedefined > 0;
      }
      if (in_file && depth < 8 && paste.names.size() < 40) {
        collect_uses(L, value, path, paste, depth + 1);
        paste.functions.push_back(function_text(path, key, ar));
      } else {
        paste.values.push_back(upvalue_line(L, name, value));
      }
    }
    lua_settop(L, value - 1);
  }
}

// `c`: the source of step `number`'s run function, from the lesson's file, with the values and
// functions it uses from the rest of the file, as lines to paste into the REPL and a call with a
// ctx.
void show_code(lua_State* L, LessonRun& run, const LoadedLesson& lesson, int number) {
  const int top = lua_gettop(L);
  if (lua_rawgeti(L, lesson.runs, number) != LUA_TFUNCTION) {
    run.page->note("  (this step has no code: it only explains)");
    lua_settop(L, top);
    return;
  }
  const int function = lua_gettop(L);
  lua_Debug ar;
  lua_pushvalue(L, function);
  lua_getinfo(L, ">S", &ar);
  PasteLines paste;
  collect_uses(L, function, run.file->path, paste, 0);
  std::string text = lua::fit_words("-- the code of step " + std::to_string(number) + " (" +
                                        run.file->path.filename().string() + ", lines " +
                                        std::to_string(ar.linedefined) + " to " +
                                        std::to_string(ar.lastlinedefined) +
                                        "); to try it, paste these lines into the REPL "
                                        "(rigidlab):",
                                    "  ", static_cast<size_t>(run.page->width()));
  std::string code;
  for (const std::string& line : paste.values) code += line + "\n";
  for (const std::string& f : paste.functions) code += f;
  code += function_text(run.file->path, "run", ar) + "run(lesson_context())\n";
  for (size_t start = 0; start < code.size();) {  // indented like the rest of the lesson
    const size_t end = code.find('\n', start);
    text += "  " + code.substr(start, end - start) + "\n";
    start = end + 1;
  }
  run.page->write("\n" + text);
  lua_settop(L, top);
}

// ---- stepping through ------------------------------------------------------------------------

// Shows step `number` and runs it; its result replaces the step's last one.
void show_step(lua_State* L, LessonRun& run, const LoadedLesson& lesson, int ctx, int number,
               const LessonClock& clock) {
  run.page->step(lesson.spec, number);
  const int passed = run.context.passed, failed = run.context.failed;
  std::string error;
  StepResult& result = run.steps[static_cast<size_t>(number) - 1];
  result.ran = true;
  lua::forget_motion(L);  // a strip the step draws (ctx:motion) can be watched live: key v
  result.error = !run_step(L, lesson, ctx, number, error);
  result.passed = run.context.passed - passed;
  result.failed = run.context.failed - failed;
  if (!result.error) return;
  run.page->error(clock.explain(error));
  if (clock.limit_reached()) {  // the limits are the whole lesson's: no step would run
    run.page->note("\nThe lesson is stopped: its limits count all of its steps.");
    run.stopped = true;
  }
}

// "4 of 4 checks passed ✓"; "2 of 2 checks passed in 2 of 5 steps" when some did not run.
std::string summary(const LessonRun& run) {
  int passed = 0, total = 0, ran = 0;
  for (const StepResult& step : run.steps) {
    passed += step.passed;
    total += step.passed + step.failed;
    ran += step.ran ? 1 : 0;
  }
  std::string text = std::to_string(passed) + " of " + std::to_string(total) + " checks passed";
  const int count = static_cast<int>(run.steps.size());
  if (ran < count) text += " in " + std::to_string(ran) + " of " + std::to_string(count) + " steps";
  return text + (run.failed() || ran < count ? "" : " ✓");
}

void key_help(LessonRun& run, bool at_end) {
  const std::string keys =
      at_end ? "keys: Enter next lesson, m menu, q quit; b back to the last step, r run it "
               "again, c show its code"
             : "keys: Enter (or →) next step, b (or ←) back, r run this step again, c show "
               "its code, m menu, q quit";
  run.page->write(lua::fit_words(keys, "  ", static_cast<size_t>(run.page->width())));
}

// After the last step: the summary, the next lesson's title and its prompt.
void end_screen(LessonRun& run) {
  run.page->note("\n" + summary(run));
  const LessonFile* next = run.catalog->next(*run.file);
  if (next != nullptr && run.file->folder >= 0) {
    const LessonInfo info = read_lesson_info(*next);
    const std::string title = info.error.empty() ? " — " + info.title : "";
    run.page->write(lua::fit_words_after("\nNext: ", next->id + title,
                                         static_cast<size_t>(run.page->width())));
  } else if (run.file->folder >= 0)
    run.page->note("\nThat was the last lesson of the tour.");
}

std::string prompt(const LessonRun& run, bool at_end, bool can_watch) {
  const bool has_next = run.file->folder >= 0 && run.catalog->next(*run.file) != nullptr;
  const std::string watch = can_watch ? "v watch   " : "";
  if (at_end)
    return has_next ? "[Enter] next lesson   " + watch + "m menu   q quit > "
                    : "[Enter] quit   " + watch + "m menu > ";
  return run.page->width() >= 60 + static_cast<int>(watch.size())
             ? "[Enter] next step   b back   c code   r again   " + watch + "q quit > "
             : "[Enter] next   b back   " + watch + "q quit   ? keys > ";
}

// Steps through the lesson with the student: a key after each step (see key_help).
void step_with_keys(lua_State* L, LessonRun& run, const LoadedLesson& lesson, int ctx, int number,
                    LessonClock& clock) {
  const int count = static_cast<int>(lesson.spec.steps.size());
  bool show_end = true;
  for (;;) {
    const bool at_end = number == count || run.stopped;
    if (at_end && show_end) end_screen(run);
    show_end = false;
    const bool can_watch = run.interactive && has_lesson_motion(L);
    run.page->write("\n" + prompt(run, at_end, can_watch));
    clock.pause();
    const KeyPress key = read_key();
    clock.resume();
    run.page->write(key.kind == KeyPress::Kind::letter ? std::string(1, key.letter) + "\n" : "\n");
    const char letter = key.kind == KeyPress::Kind::letter ? key.letter : 0;
    if (key.kind == KeyPress::Kind::end || letter == 'q') {
      if (!at_end) run.page->note("\n" + summary(run));
      run.next = Next::quit;
      return;
    }
    if (letter == 'm') {
      if (!at_end) run.page->note("\n" + summary(run));
      run.next = Next::menu;
      return;
    }
    if (letter == 'v' && can_watch) {  // the live view: the lesson's clock waits, as at the prompt
      std::string error;
      clock.pause();
      if (!view_lesson_motion(L, error)) run.page->error(clock.explain(error));
      clock.resume();
    } else if (letter == 'c') {
      show_code(L, run, lesson, number);
    } else if (run.stopped &&
               (letter == 'b' || letter == 'r' || key.kind == KeyPress::Kind::back)) {
      run.page->note("  (the lesson was stopped by its limits: no step runs again)");
    } else if (key.kind == KeyPress::Kind::enter) {
      if (at_end) {
        run.next =
            run.file->folder >= 0 && run.catalog->next(*run.file) ? Next::next_lesson : Next::quit;
        return;
      }
      show_step(L, run, lesson, ctx, ++number, clock);
      show_end = true;
    } else if (letter == 'b' || key.kind == KeyPress::Kind::back) {
      number = std::max(1, number - 1);
      show_step(L, run, lesson, ctx, number, clock);
      show_end = true;
    } else if (letter == 'r') {
      show_step(L, run, lesson, ctx, number, clock);
      show_end = true;
    } else {
      key_help(run, at_end);
    }
  }
}

// Shows the lesson of the LessonRun (argument 1), in protected mode: an error anywhere is
// reported, not fatal.
int present_protected(lua_State* L) {
  LessonRun& run = *static_cast<LessonRun*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  LessonClock clock(L);
  lua::open_all(L);
  if (!run.file->trusted) lua::apply_sandbox(L);
  lua_pushlightuserdata(L, run.page);
  lua_pushcclosure(L, guarded_print, 1);
  lua_setglobal(L, "print");
  LoadedLesson lesson;
  std::string error;
  if (!load_lesson(L, *run.file, lesson, error)) {
    std::fflush(stdout);
    std::fprintf(stderr, "rigidlab: %s\n", clock.explain(error).c_str());
    return 0;
  }
  const int count = static_cast<int>(lesson.spec.steps.size());
  if (run.options->from_step > count) {
    std::fprintf(stderr, "rigidlab: --from %d: lesson '%s' has %d step%s\n", run.options->from_step,
                 lesson.spec.id.c_str(), count, count == 1 ? "" : "s");
    run.usage_error = true;
    return 0;
  }
  run.loaded = true;
  run.steps.assign(static_cast<size_t>(count), StepResult{});
  run.context.output = run.page;
  run.context.width = run.page->width();
  run.context.tolerance = lesson.spec.tolerance;
  lua::push_lesson_context(L, run.context);
  const int ctx = lua_gettop(L);
  const LessonFolder* folder = run.file->folder >= 0
                                   ? &run.catalog->folders[static_cast<size_t>(run.file->folder)]
                                   : nullptr;
  run.page->heading(lesson.spec,
                    folder != nullptr && folder->built_in ? "" : run.catalog->origin(*run.file));
  int number = run.options->from_step;
  // What the student types while a step runs, or as its prompt appears, is read as keys and
  // never echoed into the lesson's text by the terminal (terminal_echo.hpp).
  const NoEcho no_echo;
  show_step(L, run, lesson, ctx, number, clock);
  if (run.interactive) {
    step_with_keys(L, run, lesson, ctx, number, clock);
  } else {
    while (number < count && !run.stopped) show_step(L, run, lesson, ctx, ++number, clock);
    run.page->note("\n" + summary(run));
  }
  run.context.ended = true;
  return 0;
}

// Writes the transcript and says where: "wrote FILE.md and 2 charts beside it (FILE-1.svg,
// FILE-2.svg)" and the summary. The exit status: 1 for a check that failed or a file that could
// not be written.
int export_transcript(MarkdownPage& transcript, const std::string& summary, bool failed) {
  std::string error;
  if (!transcript.finish(error)) {
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    return 1;
  }
  const auto& files = transcript.files();
  std::string charts;
  for (size_t i = 0; i + 1 < files.size(); ++i)
    charts += (i ? ", " : "") + files[i].filename().string();
  std::printf("wrote %s", files.back().string().c_str());
  if (files.size() > 1)
    std::printf(" and %zu chart%s beside it (%s)", files.size() - 1, files.size() > 2 ? "s" : "",
                charts.c_str());
  std::printf("\n%s\n", summary.c_str());
  return failed ? 1 : 0;
}

struct Outcome {
  int status = 0;  // 0 when every check held, 1 otherwise, 2 for a usage error
  Next next = Next::quit;
};

// Shows one lesson: in a terminal step by step with keys, else straight through. Ctrl-C stops
// the step that is running (its error is shown) and the lesson goes on. Untrusted lessons run
// under the check limits (or the command line's).
Outcome present_lesson(const LessonCatalog& catalog, const LessonFile& file,
                       const LessonOptions& options) {
  TerminalPage terminal;
  MarkdownPage transcript(options.export_path);
  LessonRun run;  // before the state: its context outlives the ctx
  run.file = &file;
  run.catalog = &catalog;
  run.options = &options;
  const bool exporting = !options.export_path.empty();
  run.page = exporting ? static_cast<LessonPage*>(&transcript) : &terminal;
  run.interactive = !exporting && interactive();
  const Limits limits = options.limits != nullptr ? *options.limits
                        : file.trusted            ? Limits{}
                                                  : default_check_limits();
  LimitedState state(limits, WhenStuck::exit);
  lua_State* L = state.get();
  if (L == nullptr) {
    std::fprintf(stderr, "rigidlab: cannot create the Lua state: %s\n",
                 state_failure_reason(limits));
    return {1, Next::quit};
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
    return {1, Next::quit};
  }
  if (run.usage_error) return {exit_usage, Next::quit};
  if (!run.loaded) return {1, run.interactive ? Next::menu : Next::quit};
  if (exporting) return {export_transcript(transcript, summary(run), run.failed()), Next::quit};
  return {run.failed() ? 1 : 0, run.next};
}

// The menu: the list and a prompt, until an answer names a lesson (nullptr: q or the end of
// the input). A wrong answer is answered under it, the list is not printed again, so the
// message and the prompt stay on screen.
const LessonInfo* menu(const LessonCatalog& catalog, const std::vector<LessonInfo>& infos) {
  std::printf("rigidlab lessons — the worked examples of the course, step by step\n\n");
  print_lesson_list(catalog, infos, true, interactive() ? terminal_rows() : 0);
  for (const std::string& problem : catalog.problems) std::printf("\n! %s", problem.c_str());
  std::printf("\nlesson number or id (q quits) > ");
  for (;;) {
    std::fflush(stdout);
    std::string answer;
    if (!read_line(answer) || answer == "q") {
      std::printf("\n");
      return nullptr;
    }
    if (const LessonInfo* choice = menu_choice(infos, answer)) return choice;
    if (!answer.empty()) std::printf("%s\n", no_such_choice(infos, answer).c_str());
    std::printf("lesson number or id (q quits) > ");
  }
}

// The tour: `first` (or the menu when nullptr), then what the student chooses after each
// lesson: the next one in tour order, the menu, or the end.
int tour(const LessonCatalog& catalog, const LessonFile* first, LessonOptions options) {
  std::vector<LessonInfo> infos;
  const LessonFile* current = first;
  bool from_menu = first == nullptr;
  int status = 0;
  for (;;) {
    if (current == nullptr) {
      if (infos.empty()) infos = read_lesson_infos(catalog);
      if (infos.empty()) {
        std::fprintf(stderr, "rigidlab: no lessons\n");
        return 1;
      }
      const LessonInfo* choice = menu(catalog, infos);
      if (choice == nullptr) return status;
      current = &choice->file;
      from_menu = true;
    }
    const Outcome outcome = present_lesson(catalog, *current, options);
    options.from_step = 1;  // --from is for the first lesson
    if (outcome.status == exit_usage) return exit_usage;
    status = std::max(status, outcome.status);
    Next next = outcome.next;
    if (!interactive()) next = from_menu ? Next::menu : Next::quit;
    if (next == Next::quit) return status;
    current = next == Next::next_lesson ? catalog.next(*current) : nullptr;
    if (next == Next::menu) std::printf("\n");
  }
}

}  // namespace

int list_lessons() {
  const LessonCatalog catalog = read_catalog();
  for (const std::string& problem : catalog.problems)
    std::fprintf(stderr, "rigidlab: %s\n", problem.c_str());
  const auto infos = read_lesson_infos(catalog);
  if (infos.empty()) {
    std::fprintf(stderr, "rigidlab: no lessons\n");
    return 1;
  }
  print_lesson_list(catalog, infos, false, 0);
  const bool all_loaded = std::all_of(infos.begin(), infos.end(),
                                      [](const LessonInfo& info) { return info.error.empty(); });
  return all_loaded && catalog.problems.empty() ? 0 : 1;
}

int lesson_command(const std::vector<std::string>& arguments) {
  Limits limits = default_check_limits();
  bool limits_given = false;
  LessonOptions options;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string error;
    if (take_limit_option(arguments, i, limits, error)) {
      if (!error.empty()) return usage_error(error);
      limits_given = true;
    } else if (arguments[i] == "--from" || arguments[i].rfind("--from=", 0) == 0) {
      const bool inline_value = arguments[i].size() > 6;
      if (!inline_value && i + 1 == arguments.size())
        return usage_error("'--from' needs a step number");
      const std::string value = inline_value ? arguments[i].substr(7) : arguments[++i];
      if (value.empty() || value.size() > 6 ||
          value.find_first_not_of("0123456789") != std::string::npos || std::stoi(value) < 1)
        return usage_error("'--from' needs a step number >= 1, got '" +
                           lua::truncate_to_width(value, 60) + "'");
      options.from_step = std::stoi(value);
    } else if (arguments[i] == "--export" || arguments[i].rfind("--export=", 0) == 0) {
      const bool inline_value = arguments[i].size() > 8;
      if (!inline_value && i + 1 == arguments.size())
        return usage_error("'--export' needs a file name (FILE.md)");
      options.export_path = inline_value ? arguments[i].substr(9) : arguments[++i];
      if (options.export_path.empty()) return usage_error("'--export' needs a file name (FILE.md)");
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
  if (limits_given) options.limits = &limits;
  const LessonCatalog catalog = read_catalog();
  if (names.empty()) {
    if (options.from_step > 1) return usage_error("'--from' needs a lesson id or file");
    if (!options.export_path.empty()) return usage_error("'--export' needs a lesson id or file");
    return tour(catalog, nullptr, options);
  }
  LessonFile file;
  std::string error;
  if (!resolve_lesson(catalog, names[0], file, error)) {
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    return exit_usage;
  }
  return tour(catalog, &file, options);
}

}  // namespace rigidlab::cli
