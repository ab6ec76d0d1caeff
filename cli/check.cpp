#include "cli/check.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "cli/child_process.hpp"
#include "cli/lesson_files.hpp"
#include "cli/limit_options.hpp"
#include "cli/usage.hpp"
#include "lua/lesson.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What the check of one lesson found.
struct CheckResult {
  std::string id;
  int passed = 0, failed = 0;
  std::vector<std::string> failures;
  std::string error;  // what stopped the lesson, "" if nothing did
  double seconds = 0.0;
  bool success() const { return error.empty() && failed == 0 && passed > 0; }
};

// The lesson's line, its failed expectations and the first line of its error.
void print_result(const CheckResult& r) {
  const std::string count = std::to_string(r.passed) + "/" + std::to_string(r.passed + r.failed);
  std::printf("%s %-24s %7s checks  %6.3f s\n", r.success() ? "ok  " : "FAIL", r.id.c_str(),
              count.c_str(), r.seconds);
  for (const std::string& f : r.failures) std::printf("       ✗ %s\n", f.c_str());
  if (!r.error.empty())
    std::printf("       error: %s\n", r.error.substr(0, r.error.find('\n')).c_str());
  else if (r.passed + r.failed == 0)
    std::printf("       error: the lesson checks nothing (no ctx:expect)\n");
  std::fflush(stdout);
}

// ---- in the child process --------------------------------------------------------------------

// The child tells the parent how far it got ("id ID", "tally PASSED FAILED" after each step)
// and "done" once it has printed its result; without "done" the parent reports the lesson.
struct ChildJob {
  const LessonFile* file;
  LimitedState* state;
  int report_fd;
  CheckResult* result;
  rigidlab::lua::LessonContext* context;  // outlives the state (the ctx points to it)
};

// Runs every step of the lesson quietly; in protected mode (lua_pcall), so that an error
// anywhere is the lesson's error. The limits cover the whole lesson: loading and every step.
int check_protected(lua_State* L) {
  ChildJob& job = *static_cast<ChildJob*>(lua_touserdata(L, 1));
  CheckResult& result = *job.result;
  lua_settop(L, 0);
  rigidlab::lua::open_all(L);
  if (!job.file->trusted) rigidlab::lua::apply_sandbox(L);
  lua_pushcfunction(L, [](lua_State*) { return 0; });  // one line per lesson: print is silenced
  lua_setglobal(L, "print");
  lua_pushnil(L);  // and a ctx of its own would print and count outside the lesson's
  lua_setglobal(L, "lesson_context");
  LoadedLesson lesson;
  std::string error;
  if (!load_lesson(L, *job.file, lesson, error)) {
    result.error = job.state->explain(error);
    return 0;
  }
  result.id = lesson.spec.id;
  report_line(job.report_fd, "id " + result.id);
  rigidlab::lua::LessonContext& context = *job.context;
  context.tolerance = lesson.spec.tolerance;
  rigidlab::lua::push_lesson_context(L, context);
  const int ctx = lua_gettop(L);
  const int count = static_cast<int>(lesson.spec.steps.size());
  for (int number = 1; number <= count && result.error.empty(); ++number) {
    if (!run_step(L, lesson, ctx, number, error))
      result.error = "step " + std::to_string(number) + ": " + job.state->explain(error);
    report_line(job.report_fd,
                "tally " + std::to_string(context.passed) + " " + std::to_string(context.failed));
  }
  context.ended = true;
  result.passed = context.passed;
  result.failed = context.failed;
  result.failures = context.failures;
  return 0;
}

int check_in_child(const LessonFile& file, const Limits& limits, int report_fd) {
  const Clock::time_point start = Clock::now();
  CheckResult result;
  result.id = file.id;
  rigidlab::lua::LessonContext context;  // before the state: the ctx points to it
  {
    LimitedState state(limits, WhenStuck::leave_to_parent);
    if (lua_State* L = state.get()) {
      state.begin_run();
      ChildJob job{&file, &state, report_fd, &result, &context};
      lua_pushcfunction(L, check_protected);
      lua_pushlightuserdata(L, &job);
      if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
        const char* message = lua_tostring(L, -1);
        result.error = state.explain(message != nullptr ? message : "error");
      }
      context.ended = true;
      state.end_run();
    } else {
      result.error = std::string("cannot create the Lua state: ") + state_failure_reason(limits);
    }
  }
  result.seconds = seconds_since(start);
  print_result(result);
  report_line(report_fd, "done");
  return result.success() ? 0 : 1;
}

// ---- in the parent ---------------------------------------------------------------------------

// Why a child ended without reporting "done", for the lesson's error line.
std::string abnormal_end(const ChildOutcome& outcome, const Limits& limits) {
  char text[160];
  switch (outcome.end) {
    case ChildOutcome::End::killed:
      std::snprintf(text, sizeof text, "stopped: the time limit (%g s) reached in a C function",
                    limits.timeout_seconds);
      break;
    case ChildOutcome::End::signaled:
      std::snprintf(text, sizeof text, "crashed: signal %d (%s)", outcome.status,
                    strsignal(outcome.status));
      break;
    case ChildOutcome::End::exited:
      std::snprintf(text, sizeof text, "the lesson ended the process (exit status %d)",
                    outcome.status);
      break;
    case ChildOutcome::End::no_fork:
      std::snprintf(text, sizeof text, "cannot start a process for the lesson: %s",
                    std::strerror(outcome.status));
      break;
  }
  return text;
}

// Checks one lesson in a child process; prints its result. True when it passed.
bool check_one(const LessonFile& file, const Limits& limits) {
  const Clock::time_point start = Clock::now();
  const double deadline =
      limits.timeout_seconds > 0.0 ? limits.timeout_seconds + stuck_grace_seconds : 0.0;
  const ChildOutcome outcome = run_in_child(
      [&](int report_fd) { return check_in_child(file, limits, report_fd); }, deadline);
  CheckResult result;
  result.id = file.id;
  bool done = false;
  std::istringstream lines(outcome.report);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("id ", 0) == 0)
      result.id = line.substr(3);
    else if (line.rfind("tally ", 0) == 0)
      std::istringstream(line.substr(6)) >> result.passed >> result.failed;
    else if (line == "done")
      done = true;
  }
  if (done && outcome.end == ChildOutcome::End::exited && outcome.status <= 1)
    return outcome.status == 0;  // the child printed its own result
  result.error = abnormal_end(outcome, limits);
  result.seconds = seconds_since(start);
  print_result(result);
  return false;
}

// A lesson that could not be checked (an id defined twice, a folder that cannot be read): a
// failed lesson with its reason.
void print_problem(const std::string& problem) {
  CheckResult result;
  const size_t quote = problem.find('\'');
  result.id = problem.rfind("lesson '", 0) == 0
                  ? problem.substr(quote + 1, problem.find('\'', quote + 1) - quote - 1)
                  : "(folder)";
  result.error = problem;
  print_result(result);
}

// The lessons an argument names: a folder's (DIR), or one (ID, FILE). A name without a slash
// is a folder when it is one and no lesson has it as id (a teacher in the folder above writes
// `rigidlab check course`). False after a usage error's message.
bool add_lessons(const LessonCatalog& catalog, const std::string& name,
                 std::vector<LessonFile>& lessons) {
  std::error_code code;
  const bool slash = name.find('/') != std::string::npos;
  if ((slash || catalog.find(name) == nullptr) && fs::is_directory(name, code)) {
    std::string error;
    if (folder_lessons(catalog, name, lessons, error)) return true;
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    return false;
  }
  LessonFile file;
  std::string error;
  if (!resolve_lesson(catalog, name, file, error)) {
    std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
    return false;
  }
  lessons.push_back(file);
  return true;
}

int check_lessons(const std::vector<std::string>& names, const Limits& limits) {
  const LessonCatalog catalog = read_catalog();
  std::vector<LessonFile> lessons;
  int passed = 0, failed = 0;
  if (names.empty()) {
    lessons = catalog.lessons;
    for (const std::string& problem : catalog.problems) {
      print_problem(problem);
      ++failed;
    }
  } else {
    for (const std::string& name : names)
      if (!add_lessons(catalog, name, lessons)) return exit_usage;
  }
  for (const LessonFile& file : lessons) (check_one(file, limits) ? passed : failed)++;
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}

}  // namespace

Limits default_check_limits() {
  Limits limits;
  limits.max_instructions = 500'000'000;
  limits.max_memory_megabytes = 256;
  limits.timeout_seconds = 10.0;
  return limits;
}

int check_command(const std::vector<std::string>& arguments) {
  Limits limits = default_check_limits();
  std::vector<std::string> names;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string error;
    if (take_limit_option(arguments, i, limits, error)) {
      if (!error.empty()) return usage_error(error);
      continue;
    }
    if (arguments[i] == "--") {  // the rest are lessons, whatever they look like
      names.insert(names.end(), arguments.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                   arguments.end());
      break;
    }
    if (arguments[i].size() > 1 && arguments[i][0] == '-')
      return usage_error("unrecognized option '" + arguments[i] + "' for 'check'");
    names.push_back(arguments[i]);
  }
  return check_lessons(names, limits);
}

}  // namespace rigidlab::cli
