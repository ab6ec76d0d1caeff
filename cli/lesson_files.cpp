#include "cli/lesson_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "cli/interrupt.hpp"
#include "lua/rigidlab.hpp"
#include "lua/text_only.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

fs::path lesson_directory() {
  if (const char* dir = std::getenv("RIGIDLAB_LESSONS"); dir != nullptr && *dir != '\0')
    return dir;
  return RIGIDLAB_LESSON_DIR;
}

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

bool trusted(const fs::path& path) {
  std::error_code error;
  return fs::weakly_canonical(path, error).parent_path() ==
         fs::weakly_canonical(lesson_directory(), error);
}

bool load_lesson(lua_State* L, const fs::path& path, std::string& error) {
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
  lua_remove(L, handler);
  if (lua_type(L, -1) != LUA_TTABLE || lua_getfield(L, -1, "steps") != LUA_TTABLE) {
    error = path.string() + ": the file must return lesson{...}";
    lua_settop(L, handler - 1);
    return false;
  }
  lua_pop(L, 1);
  return true;
}

bool run_step(lua_State* L, int lesson, int ctx, int number, std::string& error) {
  lua_getfield(L, lesson, "steps");
  lua_geti(L, -1, number);
  lua_remove(L, -2);
  const int step = lua_gettop(L);
  if (lua_getfield(L, step, "run") != LUA_TFUNCTION) {
    lua_settop(L, step - 1);
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
  lua_settop(L, step - 1);
  return status == LUA_OK;
}

int steps_count(lua_State* L, int lesson) {
  lua_getfield(L, lesson, "steps");
  const int count = static_cast<int>(luaL_len(L, -1));
  lua_pop(L, 1);
  return count;
}

std::string field_string(lua_State* L, int table, const char* name) {
  lua_getfield(L, table, name);
  std::string value = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  return value;
}

}  // namespace rigidlab::cli
