// Running a piece of work in a forked child process, so that whatever it does (a crash, a hang
// in a C function, os.exit) ends the child only. Used by `rigidlab check`: each lesson runs in
// its own child, the parent enforces the deadline and reports what happened.
#pragma once

#include <functional>
#include <string>

namespace rigidlab::cli {

struct ChildOutcome {
  enum class End {
    exited,    // `status` is the exit status
    signaled,  // `status` is the signal that ended it
    killed,    // the deadline passed: the parent killed it
    no_fork,   // fork failed: `status` is errno
  } end = End::exited;
  int status = 0;
  std::string report;  // everything the child wrote to report_fd
};

// Flushes stdout and stderr, forks, runs `work(report_fd)` in the child and ends the child
// with _exit of its result (after flushing stdio). The parent reads what the child writes to
// report_fd until the child ends; when `deadline_seconds` > 0 pass first, it kills the child
// with SIGKILL.
ChildOutcome run_in_child(const std::function<int(int report_fd)>& work, double deadline_seconds);

// Writes `line` and a newline to the report fd (nothing when it cannot).
void report_line(int report_fd, const std::string& line);

}  // namespace rigidlab::cli
