#include "cli/lesson_menu.hpp"

#include <algorithm>
#include <cstdio>

#include "cli/check.hpp"
#include "cli/lesson_page.hpp"
#include "cli/limits.hpp"
#include "lua/rigidlab.hpp"
#include "lua/sandbox.hpp"
#include "lua/text_layout.hpp"

namespace rigidlab::cli {
using lua::display_width;

namespace {

// Opens the libraries and loads the lesson of the LessonInfo (argument 1), in protected mode.
int read_info_protected(lua_State* L) {
  auto& info = *static_cast<LessonInfo*>(lua_touserdata(L, 1));
  lua::open_all(L);
  if (!info.file.trusted) lua::apply_sandbox(L);
  LoadedLesson lesson;
  if (load_lesson(L, info.file, lesson, info.error)) {
    info.title = lesson.spec.title;
    info.source = lesson.spec.source;
  }
  return 0;
}

std::string folder_heading(const LessonCatalog& catalog, int folder) {
  const LessonFolder& f = catalog.folders[static_cast<size_t>(folder)];
  return f.built_in ? "built-in lessons (" + f.path.string() + ")"
                    : "lessons from " + f.path.string() + " (RIGIDLAB_LESSONS)";
}

// The rows of the full list: id, title and source in columns, fitted to the terminal: the
// source column, cut short, when at least 20 columns are left beside the titles, else none (a
// lesson shows its source in full at the top); titles are cut only when they alone do not
// fit. Written to a file or a pipe (width unknown) nothing is cut.
std::vector<std::string> table_rows(const std::vector<LessonInfo>& infos, bool numbered) {
  size_t id_width = 2, title_width = 5;
  for (const auto& info : infos) {
    id_width = std::max(id_width, display_width(info.file.id));
    title_width = std::max(title_width, display_width(info.title));
  }
  const size_t columns = static_cast<size_t>(terminal_width());
  size_t source_width = std::string::npos;
  if (columns > 0) {
    const size_t before_title = (numbered ? 5 : 0) + id_width + 2;  // "%3d  " id "  "
    const size_t left = columns > before_title ? columns - before_title : 0;
    title_width = std::min(title_width, std::max<size_t>(left, 12));
    source_width = left >= title_width + 2 + 20 ? left - title_width - 2 : 0;
  }
  std::vector<std::string> rows;
  int number = 0;
  for (const auto& info : infos) {
    char prefix[16] = "";
    if (numbered) std::snprintf(prefix, sizeof prefix, "%3d  ", ++number);
    std::string row =
        prefix + info.file.id + std::string(id_width - display_width(info.file.id), ' ');
    if (!info.error.empty()) {
      rows.push_back(row + "  (cannot load: " + info.error + ")");
      continue;
    }
    std::string title = lua::truncate_to_width(info.title, title_width);
    if (source_width == 0) {
      rows.push_back(row + "  " + title);
      continue;
    }
    title += std::string(title_width - display_width(title), ' ');
    rows.push_back(row + "  " + title + "  " + lua::truncate_to_width(info.source, source_width));
  }
  return rows;
}

// The compact menu of one folder's lessons: "%3d  id" cells in columns, filled down first.
void print_compact(const std::vector<LessonInfo>& infos, size_t first, size_t count) {
  size_t id_width = 2;
  for (size_t i = first; i < first + count; ++i)
    id_width = std::max(id_width, display_width(infos[i].file.id));
  const size_t cell = 5 + id_width;
  const size_t width = static_cast<size_t>(std::max(terminal_width(), 40));
  const size_t columns = std::max<size_t>(1, (width + 2) / (cell + 2));
  const size_t rows = (count + columns - 1) / columns;
  for (size_t row = 0; row < rows; ++row) {
    std::string line;
    for (size_t column = 0; column < columns; ++column) {
      const size_t i = column * rows + row;
      if (i >= count) break;
      const LessonInfo& info = infos[first + i];
      char number[16];
      std::snprintf(number, sizeof number, "%3zu  ", first + i + 1);
      std::string text = number + info.file.id + (info.error.empty() ? "" : " (!)");
      if (column + 1 < columns && (column + 1) * rows + row < count)
        text +=
            std::string(cell + 2 > display_width(text) ? cell + 2 - display_width(text) : 1, ' ');
      line += text;
    }
    std::printf("%s\n", line.c_str());
  }
}

// Optimal string alignment distance (Levenshtein with adjacent transpositions).
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

LessonInfo read_lesson_info(const LessonFile& file) {
  LessonInfo info;
  info.file = file;
  // Loading a lesson runs its file: under the check limits, so that a file that loops cannot
  // hang the list.
  LimitedState state(default_check_limits(), WhenStuck::exit);
  lua_State* L = state.get();
  if (L == nullptr) {
    info.error = "cannot create the Lua state: not enough memory";
    return info;
  }
  const TimedRun timed(L);
  lua_pushcfunction(L, read_info_protected);
  lua_pushlightuserdata(L, &info);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK)
    info.error = state.explain(lua_tostring(L, -1) ? lua_tostring(L, -1) : "error");
  else
    info.error = state.explain(info.error);
  return info;
}

std::vector<LessonInfo> read_lesson_infos(const LessonCatalog& catalog) {
  std::vector<LessonInfo> infos;
  for (const LessonFile& file : catalog.lessons) infos.push_back(read_lesson_info(file));
  return infos;
}

void print_lesson_list(const LessonCatalog& catalog, const std::vector<LessonInfo>& infos,
                       bool numbered, int rows) {
  const bool headings = catalog.folders.size() > 1;
  size_t lines = infos.size() + 6;  // the menu's title, blank lines and prompt
  if (headings) lines += 2 * catalog.folders.size();
  const bool compact = numbered && rows > 0 && lines > static_cast<size_t>(rows);
  const std::vector<std::string> table = table_rows(infos, numbered);
  for (size_t first = 0; first < infos.size();) {
    size_t count = 1;
    while (first + count < infos.size() &&
           infos[first + count].file.folder == infos[first].file.folder)
      ++count;
    if (headings)
      std::printf("%s%s\n", first > 0 ? "\n" : "",
                  folder_heading(catalog, infos[first].file.folder).c_str());
    if (compact) {
      print_compact(infos, first, count);
    } else {
      for (size_t i = first; i < first + count; ++i) std::printf("%s\n", table[i].c_str());
    }
    first += count;
  }
}

const LessonInfo* menu_choice(const std::vector<LessonInfo>& infos, const std::string& answer) {
  if (!answer.empty() && answer.size() <= 9 &&
      answer.find_first_not_of("0123456789") == std::string::npos) {
    const size_t number = std::stoul(answer);
    return number >= 1 && number <= infos.size() ? &infos[number - 1] : nullptr;
  }
  for (const LessonInfo& info : infos)
    if (info.file.id == answer) return &info;
  return nullptr;
}

std::string no_such_choice(const std::vector<LessonInfo>& infos, const std::string& answer) {
  const std::string shown = lua::truncate_to_width(answer, 60);
  if (!answer.empty() && answer.find_first_not_of("0123456789") == std::string::npos)
    return "no lesson " + shown + ": the lessons are numbered 1 to " + std::to_string(infos.size());
  // The closest ids: a few edits away (a typo), or holding the answer (a part of the id).
  std::vector<std::pair<size_t, const LessonInfo*>> close;
  if (answer.size() <= 100) {
    const size_t most = std::max<size_t>(1, std::min<size_t>(3, answer.size() / 3));
    for (const LessonInfo& info : infos) {
      size_t distance = edit_distance(answer, info.file.id);
      if (answer.size() >= 3 && info.file.id.find(answer) != std::string::npos)
        distance = std::min(distance, most);
      if (distance <= most) close.emplace_back(distance, &info);
    }
  }
  std::stable_sort(close.begin(), close.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  if (close.size() > 3) close.resize(3);
  std::string message = "no lesson '" + shown + "'";
  if (close.empty())
    return message + " (a number from 1 to " + std::to_string(infos.size()) + ", or an id)";
  message += "; did you mean ";
  for (size_t i = 0; i < close.size(); ++i)
    message += (i == 0                  ? ""
                : i + 1 == close.size() ? " or "
                                        : ", ") +
               ("'" + close[i].second->file.id + "'");
  return message + "?";
}

}  // namespace rigidlab::cli
