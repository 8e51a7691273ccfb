// Contract: ChildProcess starts a program (posix_spawn, no shell) with its stdout captured to a
// file, and on destruction terminates it (SIGTERM, then SIGKILL after a grace period) and reaps
// it, so no test or runner leaves processes behind.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace smart::common {

class ChildProcess {
 public:
  // `stdout_file`: where the child's stdout goes (empty: inherit). stderr is inherited.
  // `give`: descriptors the child gets as {parent fd, child fd} (e.g. a pipe's end as its stdin;
  // the parent's descriptors should be close-on-exec, so the child keeps only these).
  // `own_group`: the child leads a process group of its own, and signals go to the whole group
  // (a shell command's children too); the destructor also kills what is left of the group once
  // the leader has ended.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& stdout_file = {},
               const std::vector<std::pair<int, int>>& give = {}, bool own_group = false);
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  // Exit code once the process has ended (128 + signal if killed); nullopt on timeout.
  std::optional<int> wait(std::chrono::milliseconds timeout);
  bool running();
  void signal(int sig);
  // SIGTERM, wait `grace`, then SIGKILL; returns the exit code.
  int terminate(std::chrono::milliseconds grace = std::chrono::milliseconds(2000));

 private:
  pid_t pid_ = -1;
  bool own_group_ = false;
  std::optional<int> status_;
};

// Path of the running executable (/proc/self/exe).
std::filesystem::path self_executable();

}  // namespace smart::common
