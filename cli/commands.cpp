#include "cli/commands.hpp"

#include <sys/stat.h>

#include <cstring>

#include "cli/check.hpp"
#include "cli/lessons.hpp"
#include "cli/usage.hpp"
#include "cli/view.hpp"

namespace rigidlab::cli {
namespace {

int lessons_command(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return usage_error("'lessons' takes no arguments");
  return list_lessons();
}

bool is_regular_file(const char* path) {
  struct stat info {};
  return stat(path, &info) == 0 && S_ISREG(info.st_mode);
}

}  // namespace

const Subcommand subcommands[] = {
    {"lessons", "", "list the lessons: id, title, source", lessons_command},
    {"lesson", "[ID|FILE] [OPTIONS]",
     "step through a lesson (no ID: a menu); OPTIONS are LIMITS, --from STEP and "
     "--export FILE.md (its transcript)",
     lesson_command},
    {"check", "[LIMITS] [ID|FILE ...]",
     "run the checks of lessons (default: all; a FILE that is a folder: its lessons) under "
     "limits",
     check_command},
    {"view", "[LIMITS] FILE.lua [ARG ...]",
     "show the world (or articulation) the script returns, live in the terminal; <- rewinds",
     view_command},
    {nullptr, nullptr, nullptr, nullptr},
};

const Subcommand* find_subcommand(int argc, char** argv) {
  if (argc < 2) return nullptr;
  for (const Subcommand* command = subcommands; command->name != nullptr; ++command)
    if (std::strcmp(argv[1], command->name) == 0)
      return is_regular_file(argv[1]) ? nullptr : command;
  return nullptr;
}

}  // namespace rigidlab::cli
