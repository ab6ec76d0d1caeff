// Finding and running lessons, shared by the step-through runner (cli/lessons.cpp) and the
// checker (cli/check.cpp).
//
// Lessons live in lesson folders: the built-in lessons/ first, then each folder of
// $RIGIDLAB_LESSONS (a ':'-separated list, added to the built-in ones), each in the order of
// its tour.txt (ids one a line; the rest after, by name). A lesson's file is named after its
// id (spring.lua holds lesson "spring"), so an id is found without loading every lesson, and
// an id in two folders is an error that names both files. Lessons of these folders are
// trusted: the user chose the folders. A lesson file from anywhere else (named on the command
// line, or in a folder given to `rigidlab check DIR`) is untrusted: it runs in the sandbox
// (lua/sandbox.hpp), under the check limits.
//
// No function here throws: every filesystem error (a name too long, a symlink loop, a folder
// that cannot be read) becomes a message.
#pragma once

#include <lua.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "lua/lesson.hpp"

namespace rigidlab::cli {

struct LessonFolder {
  std::filesystem::path path;
  bool built_in = false;
};

struct LessonFile {
  std::filesystem::path path;
  std::string id;            // the file's name without .lua
  int folder = -1;           // index in LessonCatalog::folders; -1: not in a lesson folder
  bool trusted = false;      // in a lesson folder: runs without the sandbox
  bool named_by_id = false;  // found in a folder: its lesson's id must be `id`
};

// Every lesson folder and the lessons in them, in tour order.
struct LessonCatalog {
  std::vector<LessonFolder> folders;
  std::vector<LessonFile> lessons;    // each id once (the first of a duplicate)
  std::vector<std::string> problems;  // ids defined twice, folders that cannot be read

  const LessonFile* find(const std::string& id) const;
  // The lesson after `lesson` in the tour, or nullptr.
  const LessonFile* next(const LessonFile& lesson) const;
  // "built-in" or the folder's path, for the list and the menu.
  std::string origin(const LessonFile& lesson) const;
};

// The built-in folder, then the folders of RIGIDLAB_LESSONS (empty entries and repeats skipped).
LessonCatalog read_catalog();

// The lessons of the folder `dir` in its tour order (tour.txt, then by name): the catalog's
// (trusted) when it is one of its folders, else untrusted ones. False with the message in
// `error` when the folder cannot be read.
bool folder_lessons(const LessonCatalog& catalog, const std::filesystem::path& dir,
                    std::vector<LessonFile>& lessons, std::string& error);

// An argument naming a lesson: a file (a name with '/' or ending in .lua) or an id of the
// catalog. False, with the message in `error`, when there is no such lesson, it cannot be
// read, or its id is defined twice.
bool resolve_lesson(const LessonCatalog& catalog, const std::string& id_or_file, LessonFile& lesson,
                    std::string& error);
// "no lesson 'NAME'" with NAME cut to a readable length.
std::string no_lesson_message(const std::string& name);

// A lesson read from its file: what lesson{} validated, and the stack index of the list of
// its steps' run functions.
struct LoadedLesson {
  lua::LessonSpec spec;
  int runs = 0;
};

// Runs a lesson file (text only) in L and reads the lesson it returns (lua::read_lesson),
// leaving the list of run functions on the stack. A lesson of a folder must carry the id of
// its file name. Ctrl-C interrupts it. On failure returns false with the message in `error`.
bool load_lesson(lua_State* L, const LessonFile& file, LoadedLesson& lesson, std::string& error);
// Runs step `number` (1-based) of the lesson with the ctx at `ctx`, Ctrl-C interruptible.
// Returns false (message and traceback in `error`) when it raised an error.
bool run_step(lua_State* L, const LoadedLesson& lesson, int ctx, int number, std::string& error);

}  // namespace rigidlab::cli
