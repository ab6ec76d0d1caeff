#include "cli/lesson_page.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "lua/text_layout.hpp"

namespace rigidlab::cli {
using lua::display_width;

int terminal_width() {
  winsize size{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) return std::max(0, std::atoi(columns));
  return 0;
}

int terminal_rows() {
  winsize size{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_row > 0) return size.ws_row;
  if (const char* lines = std::getenv("LINES")) return std::max(0, std::atoi(lines));
  return 0;
}

int lesson_width() {
  const int columns = terminal_width();
  return columns == 0 ? 80 : std::clamp(columns, 40, 100);
}

void TerminalPage::write(const std::string& lines) {
  std::fwrite(lines.data(), 1, lines.size(), stdout);
  std::fflush(stdout);
}

// "id — title" and the source, one document per line (a source lists them split by "; "),
// each wrapped to the width under its start.
void TerminalPage::heading(const lua::LessonSpec& spec, const std::string& origin) {
  std::string text = lua::fit_words_after(spec.id + " — ", spec.title, width_);
  const char* label = "  source: ";
  for (size_t start = 0; start <= spec.source.size();) {
    size_t end = spec.source.find("; ", start);
    if (end == std::string::npos) end = spec.source.size();
    text += lua::fit_words_after(label, spec.source.substr(start, end - start), width_);
    label = "          ";
    start = end + 2;
  }
  if (!origin.empty()) text += lua::fit_words_after("  from:   ", origin, width_);
  if (spec.has_tolerance)
    text += lua::fit_words_after(
        "  tolerance: ", lua::describe_tolerance(spec.tolerance) + " — " + spec.tolerance.reason,
        width_);
  write(text);
}

void TerminalPage::step(const lua::LessonSpec& spec, int number) {
  const lua::LessonStep& step = spec.steps[static_cast<size_t>(number) - 1];
  const std::string title = "-- Step " + std::to_string(number) + "/" +
                            std::to_string(spec.steps.size()) + ": " + step.title;
  // "-- Step 2/5: title -----" filled to the width; a title too long for one line is wrapped
  const int rule = width_ - static_cast<int>(display_width(title)) - 1;
  std::string text = rule >= 3 ? "\n" + title + " " + std::string(rule, '-') + "\n\n"
                               : "\n" + lua::fit_words_after("-- ", title.substr(3), width_) + "\n";
  text += lua::fit_paragraphs(step.text, "  ", width_);
  if (!step.formula.empty()) {
    text += "\n";
    std::istringstream lines(step.formula);
    for (std::string line; std::getline(lines, line);) text += "      " + line + "\n";
  }
  write(text + "\n");
}

void TerminalPage::error(const std::string& message) { write("  error: " + message + "\n"); }

void TerminalPage::note(const std::string& line) { write(line + "\n"); }

}  // namespace rigidlab::cli
