// The lesson commands `rigidlab lessons` (the list) and `rigidlab lesson [ID|FILE]` (step
// through one, or a numbered menu); `rigidlab check` is cli/check.hpp. Where lessons are
// found: cli/lesson_files.hpp.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::cli {

int list_lessons();
// `rigidlab lesson [LIMITS] [ID|FILE]`: steps through one lesson, or offers the menu. LIMITS
// (the options of `check`) apply to any lesson; without them a lesson from outside the lesson
// directory runs under the check limits, counted over the whole lesson.
int lesson_command(const std::vector<std::string>& arguments);

}  // namespace rigidlab::cli
