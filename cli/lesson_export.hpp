// `rigidlab lesson ID --export FILE.md`: the lesson's transcript as Markdown, so a teacher can
// hand it out and a student hand in their own: the heading and source, each step's title,
// text and formula, the values and checks as the lesson shows them (in text blocks, laid out
// in 80 columns), and each ctx:plot as an SVG file beside FILE.md (FILE-1.svg, FILE-2.svg,
// ...), linked by its name. The files are written by the runner, never by the lesson, and only
// there: a sandboxed lesson exports the same way and writes nothing else.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cli/lesson_page.hpp"

namespace rigidlab::cli {

class MarkdownPage : public LessonPage {
 public:
  explicit MarkdownPage(std::filesystem::path markdown);
  void write(const std::string& lines) override;
  void plot(const present::Chart& chart, const lua::PlotSize& size) override;
  void heading(const lua::LessonSpec& spec, const std::string& origin) override;
  void step(const lua::LessonSpec& spec, int number) override;
  void error(const std::string& message) override;
  void note(const std::string& line) override;
  int width() const override { return 80; }

  // Writes the Markdown file (its folder made if need be). False with the reason in `error`
  // when it, or a chart before it, could not be written.
  bool finish(std::string& error);
  // The files written so far (the charts; the Markdown after finish).
  const std::vector<std::filesystem::path>& files() const { return files_; }

 private:
  void close_block();
  void prose(const std::string& text);

  std::filesystem::path markdown_;
  std::string text_;
  bool in_block_ = false;
  int charts_ = 0;
  std::string problem_;  // the first file that could not be written
  std::vector<std::filesystem::path> files_;
};

}  // namespace rigidlab::cli
