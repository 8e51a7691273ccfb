// Contract: ChildProcess starts a program (posix_spawn, no shell) with its stdout captured to a
// file, and on destruction terminates it (SIGTERM, then SIGKILL after a grace period) and reaps
// it, so no test or runner leaves processes behind.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace smart::common {

class ChildProcess {
 public:
  // `stdout_file`: where the child's stdout goes (empty: inherit). stderr is inherited.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& stdout_file = {});
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
  std::optional<int> status_;
};

// Path of the running executable (/proc/self/exe).
std::filesystem::path self_executable();

}  // namespace smart::common
