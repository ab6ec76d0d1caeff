#include "cli/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>

namespace rigidlab::cli {
namespace {

// Reads what the child reports until it closes the pipe (it ended) or the deadline passes.
// False at the deadline.
bool read_until_end(int fd, double deadline_seconds, std::string& report) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(deadline_seconds));
  char buffer[4096];
  for (;;) {
    int wait_ms = -1;
    if (deadline_seconds > 0.0) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (left.count() <= 0) return false;
      wait_ms = static_cast<int>(std::min<long long>(left.count() + 1, 1 << 30));
    }
    pollfd watched{fd, POLLIN, 0};
    const int ready = poll(&watched, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;  // the deadline check above decides
    const ssize_t count = read(fd, buffer, sizeof buffer);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) return true;  // end of file: the child has ended (or closed it)
    report.append(buffer, static_cast<std::size_t>(count));
  }
}

}  // namespace

ChildOutcome run_in_child(const std::function<int(int report_fd)>& work, double deadline_seconds) {
  ChildOutcome outcome;
  int fds[2];
  if (pipe(fds) != 0) {
    outcome.end = ChildOutcome::End::no_fork;
    outcome.status = errno;
    return outcome;
  }
  std::fflush(stdout);  // nothing buffered may be written twice, by parent and child
  std::fflush(stderr);
  const pid_t child = fork();
  if (child < 0) {
    outcome.end = ChildOutcome::End::no_fork;
    outcome.status = errno;
    close(fds[0]);
    close(fds[1]);
    return outcome;
  }
  if (child == 0) {
    close(fds[0]);
    fcntl(fds[1], F_SETFD, FD_CLOEXEC);  // programs the work starts do not keep it open
    const int result = work(fds[1]);
    std::fflush(stdout);
    std::fflush(stderr);
    _exit(result);
  }
  close(fds[1]);
  const bool ended = read_until_end(fds[0], deadline_seconds, outcome.report);
  close(fds[0]);
  if (!ended) kill(child, SIGKILL);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (!ended) {
    outcome.end = ChildOutcome::End::killed;
  } else if (WIFSIGNALED(status)) {
    outcome.end = ChildOutcome::End::signaled;
    outcome.status = WTERMSIG(status);
  } else {
    outcome.end = ChildOutcome::End::exited;
    outcome.status = WEXITSTATUS(status);
  }
  return outcome;
}

void report_line(int report_fd, const std::string& line) {
  const std::string text = line + "\n";
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t count = write(report_fd, text.data() + written, text.size() - written);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) return;
    written += static_cast<std::size_t>(count);
  }
}

}  // namespace rigidlab::cli
