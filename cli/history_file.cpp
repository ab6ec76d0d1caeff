#include "cli/history_file.hpp"

#include <editline/readline.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rigidlab::cli {
namespace {

constexpr int max_links = 40;  // as the kernel's own limit on a path's symbolic links

// The file that the symbolic links from `path` lead to, whether it exists or not. Sets
// `error` when they loop.
std::string follow_links(std::string path, std::string& error) {
  for (int hop = 0; hop < max_links; ++hop) {
    struct stat info {};
    if (lstat(path.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return path;
    std::string target(static_cast<std::size_t>(info.st_size > 0 ? info.st_size : 4096), '\0');
    const ssize_t length = readlink(path.c_str(), target.data(), target.size());
    if (length < 0) return path;
    target.resize(static_cast<std::size_t>(length));
    const std::size_t slash = path.rfind('/');
    path = target[0] == '/' || slash == std::string::npos ? target
                                                          : path.substr(0, slash + 1) + target;
  }
  error = std::strerror(ELOOP);
  return path;
}

// Whether the file at `path` may be read and replaced: a regular file, or nothing yet.
bool regular_or_absent(const std::string& path, struct stat& info, bool& exists) {
  exists = stat(path.c_str(), &info) == 0;
  return exists ? S_ISREG(info.st_mode) : errno == ENOENT;
}

}  // namespace

HistoryFile::HistoryFile() {
  const char* home = std::getenv("HOME");
  if (home == nullptr || *home == '\0') return;
  path_ = follow_links(std::string(home) + "/.rigidlab_history", error_);
}

void HistoryFile::load() const {
  struct stat info {};
  bool exists = false;
  if (!path_.empty() && error_.empty() && regular_or_absent(path_, info, exists) && exists)
    read_history(path_.c_str());
}

void HistoryFile::save() {
  if (path_.empty() || failed_) return;
  struct stat info {};
  bool exists = false;
  std::string reason = error_;
  if (reason.empty()) {
    if (!regular_or_absent(path_, info, exists)) {
      if (exists) return;  // a device, a FIFO, a directory: left alone
      reason = std::strerror(errno);
    }
  }
  if (reason.empty()) {
    const std::string temporary = path_ + ".tmp" + std::to_string(getpid());
    int error = write_history(temporary.c_str());
    if (error == 0 && exists) chmod(temporary.c_str(), info.st_mode & 07777);  // keep its mode
    if (error == 0 && std::rename(temporary.c_str(), path_.c_str()) != 0) error = errno;
    if (error == 0) return;
    std::remove(temporary.c_str());
    reason = std::strerror(error);
  }
  failed_ = true;
  std::fprintf(stderr, "rigidlab: the history is not saved (cannot write %s: %s)\n",
               path_.c_str(), reason.c_str());
}

}  // namespace rigidlab::cli
