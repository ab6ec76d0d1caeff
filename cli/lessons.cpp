#include "cli/lessons.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lua/lesson.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

fs::path lesson_directory() {
  if (const char* dir = std::getenv("RIGIDLAB_LESSONS"); dir != nullptr && *dir != '\0')
    return dir;
  return RIGIDLAB_LESSON_DIR;
}

// Lesson files in tour order: the ids listed in tour.txt first, then the rest by name.
std::vector<fs::path> lesson_files() {
  const fs::path dir = lesson_directory();
  std::vector<fs::path> all;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error))
    if (entry.path().extension() == ".lua") all.push_back(entry.path());
  std::sort(all.begin(), all.end());
  std::vector<fs::path> ordered;
  std::ifstream tour(dir / "tour.txt");
  for (std::string id; std::getline(tour, id);) {
    if (id.empty() || id[0] == '#') continue;
    auto it = std::find(all.begin(), all.end(), dir / (id + ".lua"));
    if (it != all.end()) {
      ordered.push_back(*it);
      all.erase(it);
    }
  }
  ordered.insert(ordered.end(), all.begin(), all.end());
  return ordered;
}

// An argument naming a lesson: an existing file, or an id in the lesson directory.
bool resolve_lesson(const std::string& id_or_file, fs::path& path) {
  const bool is_file_name = id_or_file.find('/') != std::string::npos ||
                            (id_or_file.size() > 4 &&
                             id_or_file.compare(id_or_file.size() - 4, 4, ".lua") == 0);
  if (is_file_name) {
    path = id_or_file;
    return fs::is_regular_file(path);
  }
  path = lesson_directory() / (id_or_file + ".lua");
  return fs::is_regular_file(path);
}

// Lessons outside the lesson directory may come from anyone: they run in the sandbox.
bool trusted(const fs::path& path) {
  std::error_code error;
  return fs::weakly_canonical(path, error).parent_path() ==
         fs::weakly_canonical(lesson_directory(), error);
}

int traceback(lua_State* L) {
  const char* message = lua_tostring(L, 1);
  luaL_traceback(L, L, message != nullptr ? message : "(error object is not a string)", 1);
  return 1;
}

// Loads a lesson file (text only) in L and leaves the lesson table on the stack. On failure
// returns false with the message in `error`.
bool load_lesson(lua_State* L, const fs::path& path, std::string& error) {
  lua_pushcfunction(L, traceback);
  const int handler = lua_gettop(L);
  int status = luaL_loadfilex(L, path.c_str(), "t");
  if (status == LUA_OK) status = lua_pcall(L, 0, 1, handler);
  if (status != LUA_OK) {
    error = lua_tostring(L, -1) != nullptr ? lua_tostring(L, -1) : "error";
    lua_settop(L, handler - 1);
    return false;
  }
  lua_remove(L, handler);
  if (lua_type(L, -1) != LUA_TTABLE || lua_getfield(L, -1, "steps") != LUA_TTABLE) {
    error = path.string() + ": the file must return lesson{...}";
    lua_settop(L, handler - 1);
    return false;
  }
  lua_pop(L, 1);
  return true;
}

std::string field_string(lua_State* L, int table, const char* name) {
  lua_getfield(L, table, name);
  std::string value = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  return value;
}

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

// Runs step `number` (1-based) of the lesson table at `lesson` with the ctx at `ctx`.
// Returns false (message in `error`) when the step raised an error.
bool run_step(lua_State* L, int lesson, int ctx, int number, std::string& error) {
  lua_getfield(L, lesson, "steps");
  lua_geti(L, -1, number);
  lua_remove(L, -2);
  const int step = lua_gettop(L);
  if (lua_getfield(L, step, "run") != LUA_TFUNCTION) {
    lua_settop(L, step - 1);
    return true;
  }
  lua_pushcfunction(L, traceback);
  lua_insert(L, -2);
  lua_pushvalue(L, ctx);
  const int status = lua_pcall(L, 1, 0, -3);
  if (status != LUA_OK) error = lua_tostring(L, -1) != nullptr ? lua_tostring(L, -1) : "error";
  lua_settop(L, step - 1);
  return status == LUA_OK;
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

int steps_count(lua_State* L, int lesson) {
  lua_getfield(L, lesson, "steps");
  const int count = static_cast<int>(luaL_len(L, -1));
  lua_pop(L, 1);
  return count;
}

// Steps through one lesson: pauses after each step in a terminal, runs straight through
// otherwise. Returns 0 when every expectation held.
int present_lesson(const fs::path& path) {
  lua_State* L = luaL_newstate();
  rigidlab::lua::open_all(L);
  if (!trusted(path)) rigidlab::lua::apply_sandbox(L);
  std::string error;
  if (!load_lesson(L, path, error)) {
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    lua_close(L);
    return 1;
  }
  const int lesson = lua_gettop(L);
  rigidlab::lua::LessonTally& tally = rigidlab::lua::push_lesson_context(L, false);
  const int ctx = lua_gettop(L);
  std::printf("%s — %s\n  source: %s\n", field_string(L, lesson, "id").c_str(),
              field_string(L, lesson, "title").c_str(), field_string(L, lesson, "source").c_str());
  const int count = steps_count(L, lesson);
  bool failed = false;
  for (int number = 1; number <= count;) {
    print_step_header(L, lesson, number, count);
    if (!run_step(L, lesson, ctx, number, error)) {
      std::printf("  error: %s\n", error.c_str());
      failed = true;
    }
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
  std::printf("\n%d of %d checks passed%s\n", tally.passed, tally.passed + tally.failed,
              tally.failed == 0 && !failed ? " ✓" : "");
  const int result = tally.failed == 0 && !failed ? 0 : 1;
  lua_close(L);
  return result;
}

struct LessonInfo {
  fs::path path;
  std::string id, title, source, error;
};

std::vector<LessonInfo> read_lesson_infos() {
  std::vector<LessonInfo> infos;
  for (const fs::path& path : lesson_files()) {
    LessonInfo info;
    info.path = path;
    lua_State* L = luaL_newstate();
    rigidlab::lua::open_all(L);
    if (load_lesson(L, path, info.error)) {
      info.id = field_string(L, -1, "id");
      info.title = field_string(L, -1, "title");
      info.source = field_string(L, -1, "source");
    } else {
      info.id = path.stem().string();
    }
    lua_close(L);
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

// Runs every step of one lesson quietly under the limits; prints one line (and the failures).
bool check_one(const fs::path& path, const Limits& limits) {
  const auto start = std::chrono::steady_clock::now();
  LimitedState state(limits);
  lua_State* L = state.get();
  std::string error, id = path.stem().string();
  int passed = 0, failed = 0;
  std::vector<std::string> failures;
  lua_pushcfunction(L, [](lua_State* L) {
    rigidlab::lua::open_all(L);
    if (lua_toboolean(L, 1)) rigidlab::lua::apply_sandbox(L);
    // Check mode prints one line per lesson: the lesson's own printing is silenced.
    lua_pushcfunction(L, [](lua_State*) { return 0; });
    lua_setglobal(L, "print");
    return 0;
  });
  lua_pushboolean(L, !trusted(path));
  bool ok = lua_pcall(L, 1, 0, 0) == LUA_OK;
  if (!ok) error = "cannot open the libraries: out of memory";
  if (ok && (ok = load_lesson(L, path, error))) {
    id = field_string(L, -1, "id");
    const int lesson = lua_gettop(L);
    rigidlab::lua::LessonTally& tally = rigidlab::lua::push_lesson_context(L, true);
    const int ctx = lua_gettop(L);
    const int count = steps_count(L, lesson);
    for (int number = 1; number <= count && ok; ++number) {
      if (!run_step(L, lesson, ctx, number, error)) {
        ok = false;
        error = "step " + std::to_string(number) + ": " + error;
      }
    }
    passed = tally.passed;
    failed = tally.failed;
    failures = tally.failures;
  }
  if (!ok && !state.limit_hit().empty() && error.find("stopped:") == std::string::npos &&
      error.find("not enough memory") != std::string::npos)
    error = "stopped: " + state.limit_hit() + " reached";
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  const bool success = ok && failed == 0 && passed > 0;
  const std::string count = std::to_string(passed) + "/" + std::to_string(passed + failed);
  std::printf("%s %-24s %7s checks  %6.3f s\n", success ? "ok  " : "FAIL", id.c_str(),
              count.c_str(), elapsed.count());
  for (const std::string& f : failures) std::printf("       ✗ %s\n", f.c_str());
  if (!ok) {
    const std::string first_line = error.substr(0, error.find('\n'));
    std::printf("       error: %s\n", first_line.c_str());
  } else if (passed + failed == 0) {
    std::printf("       error: the lesson checks nothing (no ctx:expect)\n");
  }
  std::fflush(stdout);
  return success;
}

}  // namespace

Limits default_check_limits() {
  Limits limits;
  limits.max_instructions = 500'000'000;
  limits.max_memory_bytes = std::size_t(256) << 20;
  limits.timeout_seconds = 10.0;
  return limits;
}

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

int check_lessons(const std::vector<std::string>& ids_or_files, const Limits& limits) {
  std::vector<fs::path> paths;
  if (ids_or_files.empty()) {
    paths = lesson_files();
  } else {
    for (const std::string& name : ids_or_files) {
      fs::path path;
      if (!resolve_lesson(name, path)) {
        std::fprintf(stderr, "rigidlab: no lesson '%s' (rigidlab lessons lists them)\n",
                     name.c_str());
        return 2;
      }
      paths.push_back(path);
    }
  }
  int passed = 0, failed = 0;
  for (const fs::path& path : paths) (check_one(path, limits) ? passed : failed)++;
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}

}  // namespace rigidlab::cli
