// The list of lessons (`rigidlab lessons`) and the menu of `rigidlab lesson`: every lesson of
// the catalog with its id, title and source, grouped by the folder it comes from (the built-in
// lessons first); a menu that does not fit the terminal's rows is laid out in columns of
// numbers and ids, so that the prompt and what was typed stay on screen. An answer that names
// no lesson gets the closest ids ("did you mean 'dzhanibekov'?").
#pragma once

#include <string>
#include <vector>

#include "cli/lesson_files.hpp"

namespace rigidlab::cli {

struct LessonInfo {
  LessonFile file;
  std::string title, source;
  std::string error;  // why it cannot be loaded, "" when it can
};

// Loads a lesson (under the check limits) for its title and source.
LessonInfo read_lesson_info(const LessonFile& file);
// The same for every lesson of the catalog.
std::vector<LessonInfo> read_lesson_infos(const LessonCatalog& catalog);

// One row per lesson: (number), id, title and source in columns, fitted to the terminal, with a
// heading per folder when there is more than one; with `rows` > 0 and too few of them, the
// compact menu (numbers and ids in columns).
void print_lesson_list(const LessonCatalog& catalog, const std::vector<LessonInfo>& infos,
                       bool numbered, int rows);

// The lesson an answer at the menu names: its number or its id; nullptr when none. The menu
// reads no file: an answer of any length is only compared with the ids.
const LessonInfo* menu_choice(const std::vector<LessonInfo>& infos, const std::string& answer);
// "no lesson 'dzhanibekof'; did you mean 'dzhanibekov'?", or which numbers there are.
std::string no_such_choice(const std::vector<LessonInfo>& infos, const std::string& answer);

}  // namespace rigidlab::cli
