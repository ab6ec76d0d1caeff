#include "present/file.hpp"

#include <cerrno>
#include <cstring>

#include "present/text.hpp"

namespace rigidlab::present {

OutputFile::OutputFile(const std::string& path) : file_(std::fopen(path.c_str(), "w")), path_(path) {
  if (file_ == nullptr)
    throw FileError("cannot open '" + printable(path, true) + "' for writing: " +
                    std::strerror(errno));
}

OutputFile::~OutputFile() {
  if (file_ != nullptr) std::fclose(file_);
}

void OutputFile::write(const char* data, std::size_t size) {
  if (error_ == 0 && size > 0 && std::fwrite(data, 1, size, file_) != size)
    error_ = errno != 0 ? errno : EIO;
}

void OutputFile::close() {
  if (file_ == nullptr) return;
  errno = 0;
  if (std::fflush(file_) != 0 && error_ == 0) error_ = errno != 0 ? errno : EIO;
  if (std::ferror(file_) && error_ == 0) error_ = EIO;
  if (std::fclose(file_) != 0 && error_ == 0) error_ = errno != 0 ? errno : EIO;
  file_ = nullptr;
  if (error_ != 0)
    throw FileError("cannot write '" + printable(path_, true) + "': " + std::strerror(error_));
}

void write_file(const std::string& path, const std::string& content) {
  OutputFile file(path);
  file.write(content);
  file.close();
}

}  // namespace rigidlab::present
