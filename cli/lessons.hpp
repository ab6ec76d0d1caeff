// The lesson commands `rigidlab lessons` (the list) and `rigidlab lesson [ID|FILE]` (step
// through one, or a numbered menu); `rigidlab check` is cli/check.hpp. Where lessons are
// found: cli/lesson_files.hpp.
#pragma once

#include <string>

namespace rigidlab::cli {

int list_lessons();
int run_lesson(const std::string& id_or_file);  // empty: the menu

}  // namespace rigidlab::cli
