// Writing the files rigidlab makes (SVG charts, CSV data, HTML pages) with every failure
// reported, including the ones a buffered write only shows at the end (a full disk, /dev/full).
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace rigidlab::present {

// "cannot open 'PATH' for writing: REASON" or "cannot write 'PATH': REASON", REASON as
// strerror gives it; the path is shown printable (present/text.hpp).
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file opened for writing (created or truncated); every failure is kept until close().
class OutputFile {
 public:
  explicit OutputFile(const std::string& path);  // throws FileError
  ~OutputFile();                                  // closes, ignoring errors (after a throw)
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(const char* data, std::size_t size);
  void write(const std::string& text) { write(text.data(), text.size()); }
  // Flushes and closes; throws FileError when any write, the flush or the close failed.
  void close();

 private:
  std::FILE* file_;
  std::string path_;
  int error_ = 0;  // the first errno seen
};

// Writes `content` to `path` (replaced), or throws FileError.
void write_file(const std::string& path, const std::string& content);

}  // namespace rigidlab::present
