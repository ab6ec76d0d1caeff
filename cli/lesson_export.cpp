#include "cli/lesson_export.hpp"

#include <cctype>
#include <sstream>

#include "present/file.hpp"
#include "present/svg_chart.hpp"

namespace rigidlab::cli {
namespace fs = std::filesystem;

namespace {

// Prose as CommonMark reads it literally: a backslash before the ASCII punctuation that could
// start emphasis, code, a link, HTML or a heading (a backslash escape shows the character).
// An underscore inside a word (003_636de12a.txt, ω_d) cannot, and stays as it is.
std::string escaped(const std::string& text) {
  std::string out;
  auto word = [&](size_t i) {
    return i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) ||
                               static_cast<unsigned char>(text[i]) >= 0x80);
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const bool inside_word = c == '_' && i > 0 && word(i - 1) && word(i + 1);
    if (std::string("\\`*_[]<>#|").find(c) != std::string::npos && !inside_word) out += '\\';
    out += c;
  }
  return out;
}

// Makes the folder of `file`; false with the reason.
bool make_folder(const fs::path& file, std::string& error) {
  const fs::path folder = file.parent_path();
  if (folder.empty()) return true;
  std::error_code code;
  fs::create_directories(folder, code);
  if (code) error = "cannot make the folder '" + folder.string() + "': " + code.message();
  return !code;
}

}  // namespace

MarkdownPage::MarkdownPage(fs::path markdown) : markdown_(std::move(markdown)) {}

void MarkdownPage::close_block() {
  if (in_block_) text_ += "```\n";
  in_block_ = false;
}

// A step's text: paragraphs as Markdown paragraphs; lines that start with a space (a formula,
// a list kept as written) in a text block.
void MarkdownPage::prose(const std::string& text) {
  std::istringstream lines(text);
  bool kept = false;  // inside a run of kept lines
  for (std::string line; std::getline(lines, line);) {
    const bool keep = !line.empty() && line[0] == ' ';
    if (keep != kept) text_ += keep ? "\n```text\n" : "```\n\n";
    kept = keep;
    if (keep)
      text_ += line + "\n";
    else if (line.find_first_not_of(" \t") == std::string::npos)
      text_ += "\n";
    else
      text_ += escaped(line) + "\n";
  }
  if (kept) text_ += "```\n";
  text_ += "\n";
}

void MarkdownPage::write(const std::string& lines) {
  if (!in_block_) text_ += "```text\n";
  in_block_ = true;
  text_ += lines;
}

void MarkdownPage::plot(const present::Chart& chart, const lua::PlotSize&) {
  close_block();
  ++charts_;
  const fs::path svg = markdown_.parent_path() /
                       (markdown_.stem().string() + "-" + std::to_string(charts_) + ".svg");
  std::string error;
  if (make_folder(svg, error)) {
    try {
      present::write_file(svg.string(), present::svg_chart(chart));
      files_.push_back(svg);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!error.empty() && problem_.empty()) problem_ = error;
  const std::string title = chart.title.empty() ? "chart " + std::to_string(charts_) : chart.title;
  text_ += "\n![" + escaped(title) + "](" + svg.filename().string() + ")\n\n";
}

// The heading of a handout: where the lesson's file lies on the teacher's machine is left out.
void MarkdownPage::heading(const lua::LessonSpec& spec, const std::string&) {
  close_block();
  text_ += "# " + escaped(spec.id) + " — " + escaped(spec.title) + "\n\n";
  text_ += "*Source:* " + escaped(spec.source) + "\n";
  if (spec.has_tolerance)
    text_ += "\n*Tolerance:* " + lua::describe_tolerance(spec.tolerance) + " — " +
             escaped(spec.tolerance.reason) + "\n";
}

void MarkdownPage::step(const lua::LessonSpec& spec, int number) {
  close_block();
  const lua::LessonStep& step = spec.steps[static_cast<size_t>(number) - 1];
  text_ += "\n## Step " + std::to_string(number) + "/" + std::to_string(spec.steps.size()) + ": " +
           escaped(step.title) + "\n\n";
  prose(step.text);
  if (!step.formula.empty()) text_ += "```text\n" + step.formula + "\n```\n\n";
}

void MarkdownPage::error(const std::string& message) { write("error: " + message + "\n"); }

void MarkdownPage::note(const std::string& line) {
  close_block();
  const size_t start = line.find_first_not_of('\n');
  text_ += "\n**" + escaped(start == std::string::npos ? "" : line.substr(start)) + "**\n";
}

bool MarkdownPage::finish(std::string& error) {
  close_block();
  if (!problem_.empty()) {
    error = problem_;
    return false;
  }
  if (!make_folder(markdown_, error)) return false;
  try {
    present::write_file(markdown_.string(), text_);
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
  files_.push_back(markdown_);
  return true;
}

}  // namespace rigidlab::cli
