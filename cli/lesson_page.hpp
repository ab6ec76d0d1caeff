// Where a lesson is shown, as the runner (cli/lessons.cpp) goes through it: its heading, each
// step's title, text and formula, what its ctx writes, errors and the summary. The terminal
// page lays them out in the terminal's width; an exported transcript (cli/lesson_export.hpp)
// writes the same parts as Markdown.
#pragma once

#include <string>

#include "lua/lesson.hpp"

namespace rigidlab::cli {

class LessonPage : public lua::LessonOutput {
 public:
  // "id — title", the source documents, the origin (a folder other than the built-in one) and
  // a lesson-wide tolerance with its reason.
  virtual void heading(const lua::LessonSpec& spec, const std::string& origin) = 0;
  // "-- Step 2/5: title ---" and the step's text and formula.
  virtual void step(const lua::LessonSpec& spec, int number) = 0;
  // An error the step raised (message and traceback).
  virtual void error(const std::string& message) = 0;
  // A line of the runner's own ("The lesson is stopped: ...", the summary).
  virtual void note(const std::string& line) = 0;
  // Columns the ctx lays its values out in.
  virtual int width() const = 0;
};

// The terminal's columns, else $COLUMNS, else 0 (unknown: output to a file or a pipe).
int terminal_width();
// The terminal's rows, else $LINES, else 0.
int terminal_rows();
// Columns a lesson is laid out in: the terminal's, at least 40 (narrower wraps every few
// words) and at most 100 (longer lines are hard to read); 80 when unknown.
int lesson_width();

class TerminalPage : public LessonPage {
 public:
  TerminalPage() : width_(lesson_width()) {}
  void write(const std::string& lines) override;
  void heading(const lua::LessonSpec& spec, const std::string& origin) override;
  void step(const lua::LessonSpec& spec, int number) override;
  void error(const std::string& message) override;
  void note(const std::string& line) override;
  int width() const override { return width_; }

 private:
  int width_;
};

}  // namespace rigidlab::cli
