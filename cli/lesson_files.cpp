#include "cli/lesson_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cli/interrupt.hpp"
#include "lua/rigidlab.hpp"
#include "lua/text_layout.hpp"
#include "lua/text_only.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

// A name as messages show it: a 300-character argument would bury the message.
std::string shown_name(const std::string& name) { return lua::truncate_to_width(name, 60); }

// The .lua files of `dir` in its tour order; false with the reason when it cannot be read.
bool tour_files(const fs::path& dir, std::vector<fs::path>& ordered, std::string& error) {
  std::vector<fs::path> all;
  std::error_code code;
  // increment(code), not ++: a folder that cannot be read is a message, it does not throw
  fs::directory_iterator it(dir, code), end;
  for (; !code && it != end; it.increment(code))
    if (it->path().extension() == ".lua") all.push_back(it->path());
  if (code) {
    error = "cannot read the lesson folder '" + shown_name(dir.string()) + "': " + code.message();
    return false;
  }
  std::sort(all.begin(), all.end());
  std::ifstream tour(dir / "tour.txt");
  for (std::string id; std::getline(tour, id);) {
    if (id.empty() || id[0] == '#') continue;
    auto found = std::find(all.begin(), all.end(), dir / (id + ".lua"));
    if (found != all.end()) {
      ordered.push_back(*found);
      all.erase(found);
    }
  }
  ordered.insert(ordered.end(), all.begin(), all.end());
  return true;
}

// The folder of `path`, resolved (symlinks, "..") for comparing folders; "" when it fails.
fs::path canonical_folder(const fs::path& path) {
  std::error_code code;
  fs::path folder = fs::weakly_canonical(path, code);
  return code ? fs::path() : folder;
}

// The index of the catalog folder that holds the file `path`, or -1.
int folder_of(const LessonCatalog& catalog, const fs::path& path) {
  const fs::path parent = canonical_folder(path).parent_path();
  if (parent.empty()) return -1;
  for (size_t i = 0; i < catalog.folders.size(); ++i)
    if (canonical_folder(catalog.folders[i].path) == parent) return static_cast<int>(i);
  return -1;
}

LessonFile make_lesson_file(const LessonCatalog& catalog, const fs::path& path) {
  LessonFile file;
  file.path = path;
  file.id = path.stem().string();
  file.folder = folder_of(catalog, path);
  file.trusted = file.folder >= 0;
  return file;
}

}  // namespace

const LessonFile* LessonCatalog::find(const std::string& id) const {
  for (const LessonFile& lesson : lessons)
    if (lesson.id == id) return &lesson;
  return nullptr;
}

const LessonFile* LessonCatalog::next(const LessonFile& lesson) const {
  if (lesson.folder < 0) return nullptr;
  for (size_t i = 0; i + 1 < lessons.size(); ++i)
    if (lessons[i].id == lesson.id && lessons[i].folder == lesson.folder) return &lessons[i + 1];
  return nullptr;
}

std::string LessonCatalog::origin(const LessonFile& lesson) const {
  if (lesson.folder < 0)
    return lesson.path.parent_path().string() + " (not a lesson folder: runs in the sandbox)";
  const LessonFolder& folder = folders[static_cast<size_t>(lesson.folder)];
  return folder.built_in ? "built-in" : folder.path.string();
}

LessonCatalog read_catalog() {
  LessonCatalog catalog;
  catalog.folders.push_back({RIGIDLAB_LESSON_DIR, true});
  if (const char* list = std::getenv("RIGIDLAB_LESSONS")) {
    std::istringstream entries(list);
    for (std::string entry; std::getline(entries, entry, ':');) {
      if (entry.empty()) continue;
      const fs::path folder = canonical_folder(entry);
      const bool repeated =
          std::any_of(catalog.folders.begin(), catalog.folders.end(), [&](const LessonFolder& f) {
            return !folder.empty() && canonical_folder(f.path) == folder;
          });
      if (!repeated) catalog.folders.push_back({entry, false});
    }
  }
  for (size_t i = 0; i < catalog.folders.size(); ++i) {
    std::vector<fs::path> files;
    std::string error;
    if (!tour_files(catalog.folders[i].path, files, error)) {
      catalog.problems.push_back(error);
      continue;
    }
    for (const fs::path& path : files) {
      LessonFile file{path, path.stem().string(), static_cast<int>(i), true, true};
      if (const LessonFile* first = catalog.find(file.id))
        catalog.problems.push_back("lesson '" + file.id + "' is defined twice: " +
                                   first->path.string() + " and " + path.string());
      else
        catalog.lessons.push_back(file);
    }
  }
  return catalog;
}

bool folder_lessons(const LessonCatalog& catalog, const fs::path& dir,
                    std::vector<LessonFile>& lessons, std::string& error) {
  std::vector<fs::path> files;
  if (!tour_files(dir, files, error)) return false;
  for (const fs::path& path : files) {
    LessonFile file = make_lesson_file(catalog, path);
    file.named_by_id = true;
    lessons.push_back(file);
  }
  return true;
}

std::string no_lesson_message(const std::string& name) {
  return "no lesson '" + shown_name(name) + "' (rigidlab lessons lists them)";
}

bool resolve_lesson(const LessonCatalog& catalog, const std::string& id_or_file, LessonFile& lesson,
                    std::string& error) {
  const bool is_file_name =
      id_or_file.find('/') != std::string::npos ||
      (id_or_file.size() > 4 && id_or_file.compare(id_or_file.size() - 4, 4, ".lua") == 0);
  if (!is_file_name) {  // an id: the catalog has it or nothing has
    if (const LessonFile* found = catalog.find(id_or_file)) {
      for (const std::string& problem : catalog.problems)
        if (problem.rfind("lesson '" + id_or_file + "' is defined twice", 0) == 0) {
          error = problem + " (rename one of them)";
          return false;
        }
      lesson = *found;
      return true;
    }
    error = no_lesson_message(id_or_file);
    return false;
  }
  const fs::path path = id_or_file;
  std::error_code code;
  const fs::file_status status = fs::status(path, code);
  if (fs::is_regular_file(status)) {
    lesson = make_lesson_file(catalog, path);
    lesson.named_by_id = lesson.folder >= 0;
    return true;
  }
  if (code && code != std::errc::no_such_file_or_directory && code != std::errc::not_a_directory)
    error = "cannot read lesson '" + shown_name(path.string()) + "': " + code.message();
  else if (fs::exists(status))
    error = "'" + shown_name(path.string()) + "' is not a lesson file (not a regular file)";
  else
    error = no_lesson_message(id_or_file);
  return false;
}

bool load_lesson(lua_State* L, const LessonFile& file, LoadedLesson& lesson, std::string& error) {
  const fs::path& path = file.path;
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
  else if (file.named_by_id && lesson.spec.id != file.id)
    problem = "its id is '" + lesson.spec.id +
              "', but a lesson's file is named after its id: " + lesson.spec.id + ".lua";
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
