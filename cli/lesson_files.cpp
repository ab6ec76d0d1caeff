#include "cli/lesson_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "cli/interrupt.hpp"
#include "lua/rigidlab.hpp"
#include "lua/text_only.hpp"
#include "lua/text_layout.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

// A name as messages show it: a 300-character argument would bury the message.
std::string shown_name(const std::string& name) { return lua::truncate_to_width(name, 60); }

bool is_lesson_id(const std::string& name) {
  return !name.empty() && name.size() <= 100 &&
         name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") == std::string::npos;
}

}  // namespace

std::string no_lesson_message(const std::string& name) {
  return "no lesson '" + shown_name(name) + "' (rigidlab lessons lists them)";
}

fs::path lesson_directory() {
  if (const char* dir = std::getenv("RIGIDLAB_LESSONS"); dir != nullptr && *dir != '\0')
    return dir;
  return RIGIDLAB_LESSON_DIR;
}

std::vector<fs::path> lesson_files() {
  const fs::path dir = lesson_directory();
  std::vector<fs::path> all;
  std::error_code error;
  // increment(error), not ++: a folder that cannot be read ends the list, it does not throw
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error))
    if (it->path().extension() == ".lua") all.push_back(it->path());
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

bool resolve_lesson(const std::string& id_or_file, fs::path& path, std::string& error) {
  const bool is_file_name = id_or_file.find('/') != std::string::npos ||
                            (id_or_file.size() > 4 &&
                             id_or_file.compare(id_or_file.size() - 4, 4, ".lua") == 0);
  if (!is_file_name && !is_lesson_id(id_or_file)) {  // no file can have that name
    error = no_lesson_message(id_or_file);
    return false;
  }
  path = is_file_name ? fs::path(id_or_file) : lesson_directory() / (id_or_file + ".lua");
  std::error_code code;
  const fs::file_status status = fs::status(path, code);
  if (fs::is_regular_file(status)) return true;
  if (code && code != std::errc::no_such_file_or_directory && code != std::errc::not_a_directory)
    error = "cannot read lesson '" + shown_name(path.string()) + "': " + code.message();
  else if (fs::exists(status))
    error = "'" + shown_name(path.string()) + "' is not a lesson file (not a regular file)";
  else
    error = no_lesson_message(id_or_file);
  return false;
}

bool trusted(const fs::path& path) {
  std::error_code error;
  const fs::path file = fs::weakly_canonical(path, error);
  if (error) return false;
  const fs::path dir = fs::weakly_canonical(lesson_directory(), error);
  return !error && file.parent_path() == dir;
}

bool load_lesson(lua_State* L, const fs::path& path, LoadedLesson& lesson, std::string& error) {
  lua_pushcfunction(L, lua::traceback_handler);
  const int handler = lua_gettop(L);
  int status = luaL_loadfilex(L, path.c_str(), "t");
  if (status == LUA_OK) {
    const InterruptibleCall interruptible(L);
    status = lua_pcall(L, 0, 1, handler);
  }
  if (status != LUA_OK) {
    rigidlab::lua::explain_text_only(L, path.c_str());
    error = lua_tostring(L, -1) != nullptr ? lua_tostring(L, -1) : "error";
    lua_settop(L, handler - 1);
    return false;
  }
  std::string problem;
  if (lua_type(L, -1) != LUA_TTABLE)
    problem = std::string("got ") + lua_typename(L, lua_type(L, -1));
  else if (!lua::read_lesson(L, -1, lesson.spec, problem))
    problem = problem.empty() ? "not a lesson" : problem;
  if (!problem.empty()) {
    error = path.string() + ": the file must return lesson{...} (" + problem + ")";
    lua_settop(L, handler - 1);
    return false;
  }
  lua_replace(L, handler);  // the runs list where the handler was; the lesson table goes
  lua_settop(L, handler);
  lesson.runs = handler;
  return true;
}

bool run_step(lua_State* L, const LoadedLesson& lesson, int ctx, int number, std::string& error) {
  const int top = lua_gettop(L);
  if (lua_rawgeti(L, lesson.runs, number) != LUA_TFUNCTION) {
    lua_settop(L, top);
    return true;
  }
  lua_pushcfunction(L, lua::traceback_handler);
  lua_insert(L, -2);
  lua_pushvalue(L, ctx);
  int status;
  {
    const InterruptibleCall interruptible(L);
    status = lua_pcall(L, 1, 0, -3);
  }
  if (status != LUA_OK) error = lua_tostring(L, -1) != nullptr ? lua_tostring(L, -1) : "error";
  lua_settop(L, top);
  return status == LUA_OK;
}

}  // namespace rigidlab::cli
