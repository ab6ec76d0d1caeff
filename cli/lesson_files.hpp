// Finding and running lessons, shared by the step-through runner (cli/lessons.cpp) and the
// checker (cli/check.cpp). The lesson directory is $RIGIDLAB_LESSONS if set, else the
// project's lessons/ folder; lessons/tour.txt gives their order. Lessons from anywhere else
// are untrusted: they run in the sandbox (lua/sandbox.hpp), under the check limits.
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

std::filesystem::path lesson_directory();
// Lesson files in tour order: the ids listed in tour.txt first, then the rest by name.
std::vector<std::filesystem::path> lesson_files();
// An argument naming a lesson: a file (a name with '/' or ending in .lua), or an id in the
// lesson directory. False, with the message in `error`, when there is no such lesson or it
// cannot be read.
bool resolve_lesson(const std::string& id_or_file, std::filesystem::path& path,
                    std::string& error);
// True for a file of the lesson directory.
bool trusted(const std::filesystem::path& path);
// "no lesson 'NAME'" with NAME cut to a readable length.
std::string no_lesson_message(const std::string& name);

// A lesson read from its file: what lesson{} validated, and the stack index of the list of
// its steps' run functions.
struct LoadedLesson {
  lua::LessonSpec spec;
  int runs = 0;
};

// Runs a lesson file (text only) in L and reads the lesson it returns (lua::read_lesson),
// leaving the list of run functions on the stack. Ctrl-C interrupts it. On failure returns
// false with the message in `error`.
bool load_lesson(lua_State* L, const std::filesystem::path& path, LoadedLesson& lesson,
                 std::string& error);
// Runs step `number` (1-based) of the lesson with the ctx at `ctx`, Ctrl-C interruptible.
// Returns false (message and traceback in `error`) when it raised an error.
bool run_step(lua_State* L, const LoadedLesson& lesson, int ctx, int number, std::string& error);

}  // namespace rigidlab::cli
