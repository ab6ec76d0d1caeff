#include "tests/fuzz/harness.hpp"

#include <lua.hpp>

#include <chrono>
#include <deque>
#include <cstdlib>

#include "cli/memory_budget.hpp"
#include "lua/binding.hpp"
#include "lua/lesson.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"
#include "tests/fuzz/program_generator.hpp"

namespace rigidlab::fuzz {
namespace {

constexpr int hook_interval = 1000;       // VM instructions between two checks of the limits
constexpr std::size_t max_subject = 256;  // bytes, for Lua's pattern functions
constexpr int max_quantifiers = 2;

// The limits of one run, reached from the allocator, the hook and the stop check. The memory
// limit is the CLI's budget (cli/memory_budget.hpp): Lua's allocations and the engine's C++
// ones count against it together, as under rigidlab --max-memory.
struct Run {
  explicit Run(const RunLimits& run_limits)
      : limits(run_limits), budget(run_limits.max_memory_bytes) {}
  RunLimits limits;
  cli::MemoryBudget budget;
  long long instructions = 0;
  int stop_checks = 0;
  std::chrono::steady_clock::time_point deadline;
};

Run& run_of(lua_State* L) {
  void* run = nullptr;
  lua_getallocf(L, &run);
  return *static_cast<Run*>(run);
}

// Refuses only what would pass the cap, so Lua's emergency collection runs first.
void* allocate(void* self, void* block, std::size_t old_size, std::size_t new_size) {
  Run& run = *static_cast<Run*>(self);
  const std::size_t old_bytes = block != nullptr ? old_size : 0;  // else old_size is a type tag
  if (new_size == 0) {
    std::free(block);
    run.budget.lua_changed(old_bytes, 0);
    return nullptr;
  }
  if (!run.budget.lua_may_grow(old_bytes, new_size)) return nullptr;
  void* result = std::realloc(block, new_size);
  if (result != nullptr) run.budget.lua_changed(old_bytes, new_size);
  return result;
}

void check_time(lua_State* L, Run& run) {
  if (std::chrono::steady_clock::now() > run.deadline)
    luaL_error(L, "fuzz harness: the time limit (%f s) passed", run.limits.timeout_seconds);
}

void hook(lua_State* L, lua_Debug*) {
  Run& run = run_of(L);
  run.instructions += hook_interval;
  if (run.instructions > run.limits.max_instructions)
    luaL_error(L, "fuzz harness: the instruction limit (%I) passed",
               static_cast<lua_Integer>(run.limits.max_instructions));
  check_time(L, run);
}

// The engine's long loops (w:step) poll this; reading the clock every 64th call keeps it cheap.
void stop_check(lua_State* L, void* self) {
  Run& run = *static_cast<Run*>(self);
  if (++run.stop_checks % 64 == 0) check_time(L, run);
}

int count_quantifiers(const char* pattern, std::size_t length) {
  int count = 0;
  for (std::size_t i = 0; i < length; ++i) {
    if (pattern[i] == '%') ++i;  // an escaped character is literal
    else if (pattern[i] == '*' || pattern[i] == '+' || pattern[i] == '-' || pattern[i] == '?')
      ++count;  // inside a set [...] these are literal: counting them only refuses more
  }
  return count;
}

// string.find/match/gmatch/gsub with the bounds of harness.hpp; upvalue 1 is the original,
// upvalue 2 is true for find (whose 4th argument asks for a plain, linear search).
int bounded_pattern_call(lua_State* L) {
  std::size_t subject_length = 0, pattern_length = 0;
  const bool plain = lua_toboolean(L, lua_upvalueindex(2)) && lua_toboolean(L, 4);
  if (!plain && lua_type(L, 1) == LUA_TSTRING && lua_type(L, 2) == LUA_TSTRING) {
    lua_tolstring(L, 1, &subject_length);
    const char* pattern = lua_tolstring(L, 2, &pattern_length);
    const int quantifiers = count_quantifiers(pattern, pattern_length);
    if (subject_length > max_subject || quantifiers > max_quantifiers)
      return luaL_error(L, "fuzz harness: pattern search refused (subject of %d bytes, %d "
                           "quantifiers; at most %d and %d)", static_cast<int>(subject_length),
                        quantifiers, static_cast<int>(max_subject), max_quantifiers);
  }
  const int args = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, args, LUA_MULTRET);
  return lua_gettop(L);
}

void bound_patterns(lua_State* L) {
  lua_getglobal(L, "string");
  for (const char* name : {"find", "match", "gmatch", "gsub"}) {
    lua_getfield(L, -1, name);
    lua_pushboolean(L, name[0] == 'f');
    lua_pushcclosure(L, bounded_pattern_call, 2);
    lua_setfield(L, -2, name);
  }
  lua_pop(L, 1);
}

// Opens rigidlab as the CLI does, sandboxed (generated programs write no files), with a silent
// print (plot.lines and help print through it) and bounded pattern functions.
int open_state(lua_State* L) {
  lua::open_all(L);
  lua::apply_sandbox(L);
  lua_pushcfunction(L, [](lua_State*) { return 0; });
  lua_setglobal(L, "print");
  bound_patterns(L);
  return 0;
}

// Runs the lesson at `index` as `rigidlab check` does: lesson{}'s raw reading (read_lesson), then
// each step's run(ctx) protected, with a ctx in check mode that ends with the lesson. The
// contexts outlive the state (a __gc may still use a ctx at lua_close): `contexts` keeps them.
void run_lesson(lua_State* L, int index, std::deque<lua::LessonContext>& contexts) {
  lua::LessonSpec spec;
  std::string error;
  if (!lua::read_lesson(L, index, spec, error)) return;
  const int runs = lua_gettop(L);
  lua::LessonContext& context = contexts.emplace_back();
  context.tolerance = spec.tolerance;
  lua::push_lesson_context(L, context);
  const int ctx = lua_gettop(L);
  for (lua_Integer step = 1; lua_rawgeti(L, runs, step) != LUA_TNIL; ++step) {
    if (lua_type(L, -1) != LUA_TFUNCTION) {
      lua_pop(L, 1);
      continue;
    }
    lua_pushvalue(L, ctx);
    if (lua_pcall(L, 1, 0, 0) != LUA_OK) lua_pop(L, 1);
  }
  context.ended = true;
  lua_settop(L, runs - 1);
}

// lua_CFunction: runs the lessons among the program's results (arguments): a lesson, or a list
// of lessons.
int run_returned_lessons(lua_State* L) {
  auto& contexts = *static_cast<std::deque<lua::LessonContext>*>(lua_touserdata(L, 1));
  for (int i = 2, results = lua_gettop(L); i <= results; ++i) {
    if (lua_type(L, i) != LUA_TTABLE) continue;
    run_lesson(L, i, contexts);
    for (lua_Integer k = 1; lua_rawgeti(L, i, k) == LUA_TTABLE; ++k) {
      run_lesson(L, lua_gettop(L), contexts);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_gc(L, LUA_GCCOLLECT);  // finalisers that use a ctx after its lesson
  return 0;
}

// lua_pcall with the C++ heap charged to the run's memory budget, as the CLI charges a user's
// call: inside, a std::bad_alloc past the limit becomes Lua's memory error in the bindings.
int charged_pcall(lua_State* L, int arguments, int results, Run& run) {
  const cli::ChargeHeap charge(&run.budget);
  return lua_pcall(L, arguments, results, 0);
}

std::string first_line(lua_State* L) {
  const char* message = lua_tostring(L, -1);
  if (message == nullptr) return "(error object is not a string)";
  const std::string text = message;
  return text.substr(0, text.find('\n'));
}

}  // namespace

std::string program_for(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return "";
  if (data[0] % 4 == 0) return std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  return generate_program(data + 1, size - 1);
}

std::string run_input(const std::uint8_t* data, std::size_t size, const RunLimits& limits) {
  if (size == 0) return "";
  Run run(limits);
  run.deadline = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(limits.timeout_seconds));
  std::deque<lua::LessonContext> contexts;  // declared before the state: they outlive it
  lua_State* L = lua_newstate(allocate, &run);
  if (L == nullptr) return "cannot create a state";
  lua_sethook(L, hook, LUA_MASKCOUNT, hook_interval);
  lua::set_stop_check(L, stop_check, &run);
  std::string result;
  lua_pushcfunction(L, open_state);
  if (charged_pcall(L, 0, 0, run) != LUA_OK) {
    result = "cannot open the libraries: " + first_line(L);
  } else {
    const std::string program = program_for(data, size);
    lua_pushcfunction(L, run_returned_lessons);
    lua_pushlightuserdata(L, &contexts);
    if (luaL_loadbufferx(L, program.data(), program.size(), "=fuzz", "t") != LUA_OK ||
        charged_pcall(L, 0, LUA_MULTRET, run) != LUA_OK ||
        charged_pcall(L, lua_gettop(L) - 1, 0, run) != LUA_OK)
      result = first_line(L);
  }
  lua_close(L);
  return result;
}

}  // namespace rigidlab::fuzz
