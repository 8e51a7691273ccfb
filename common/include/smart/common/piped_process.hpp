// Contract: a child process spoken to in lines over its stdin and stdout (an external lifelong
// planner, docs/planner-protocol.md). The command runs under /bin/sh -c; stderr is inherited.
// Nothing blocks past a deadline: write_line and read_line poll the pipes. A line longer than
// `max_line_bytes` is read and dropped, never stored (kTooLong), so a child that floods costs
// bounded memory. A closed pipe (the child exited or closed it) is kClosed; writing to it never
// raises SIGPIPE (the constructor ignores that signal process-wide if it had its default, the
// usual choice of servers). The destructor closes the pipes and terminates the command's whole
// process group (the shell and what it started).
#pragma once

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "smart/common/child_process.hpp"

namespace smart::common {

class PipedProcess {
 public:
  using Deadline = std::chrono::steady_clock::time_point;
  enum class Io { kOk, kTimeout, kClosed, kTooLong };

  explicit PipedProcess(const std::string& shell_command);
  PipedProcess(const PipedProcess&) = delete;
  PipedProcess& operator=(const PipedProcess&) = delete;
  ~PipedProcess();

  // Writes `line` and a newline. On a timeout part of the line may be written: the pipe to the
  // child is closed then (it reads the end of its input) and later writes are kClosed.
  Io write_line(std::string_view line, Deadline deadline);
  // The next line, without its newline.
  Io read_line(std::string& line, std::size_t max_line_bytes, Deadline deadline);
  // The exit code once the child has ended (128 + signal if killed), waiting at most `wait`.
  std::optional<int> exit_code(std::chrono::milliseconds wait = std::chrono::milliseconds(0));
  // Bytes held for a line not yet complete (tests: bounded by max_line_bytes).
  std::size_t buffered() const { return buffer_.size(); }

 private:
  static int milliseconds_to(Deadline deadline);
  int to_child_ = -1;
  int from_child_ = -1;
  std::optional<ChildProcess> child_;
  std::string buffer_;     // bytes read after the last whole line
  bool skipping_ = false;  // inside a line too long to keep
};

}  // namespace smart::common
