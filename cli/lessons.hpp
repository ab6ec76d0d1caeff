// The lesson commands: `rigidlab lessons` (the list), `rigidlab lesson [ID|FILE]` (step
// through one, or a numbered menu), `rigidlab check [ID|FILE ...]` (every expectation, no
// pausing, under limits). Lessons are files in the lesson directory: $RIGIDLAB_LESSONS if
// set, else the project's lessons/ folder; lessons/tour.txt gives their order.
#pragma once

#include <string>
#include <vector>

#include "cli/limits.hpp"

namespace rigidlab::cli {

// Defaults of `rigidlab check`: a lesson is meant to finish in well under 2 s.
Limits default_check_limits();

int list_lessons();
int run_lesson(const std::string& id_or_file);  // empty: the menu
int check_lessons(const std::vector<std::string>& ids_or_files, const Limits& limits);

}  // namespace rigidlab::cli
