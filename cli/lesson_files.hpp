// Finding and running lessons, shared by the step-through runner (cli/lessons.cpp) and the
// checker (cli/check.cpp). The lesson directory is $RIGIDLAB_LESSONS if set, else the
// project's lessons/ folder; lessons/tour.txt gives their order. Lessons from anywhere else
// are untrusted: they run in the sandbox (lua/sandbox.hpp), under the check limits.
#pragma once

#include <lua.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace rigidlab::cli {

std::filesystem::path lesson_directory();
// Lesson files in tour order: the ids listed in tour.txt first, then the rest by name.
std::vector<std::filesystem::path> lesson_files();
// An argument naming a lesson: an existing file (a name with '/' or ending in .lua), or an
// id in the lesson directory. False when there is no such file.
bool resolve_lesson(const std::string& id_or_file, std::filesystem::path& path);
// True for a file of the lesson directory.
bool trusted(const std::filesystem::path& path);

// Loads a lesson file (text only) in L and leaves the lesson table on the stack. On failure
// returns false with the message in `error`.
bool load_lesson(lua_State* L, const std::filesystem::path& path, std::string& error);
// Runs step `number` (1-based) of the lesson table at `lesson` with the ctx at `ctx`, Ctrl-C
// interruptible. Returns false (message and traceback in `error`) when it raised an error.
bool run_step(lua_State* L, int lesson, int ctx, int number, std::string& error);
int steps_count(lua_State* L, int lesson);
// Field `name` of the table at `table` if it is a string (or number), else "".
std::string field_string(lua_State* L, int table, const char* name);

}  // namespace rigidlab::cli
