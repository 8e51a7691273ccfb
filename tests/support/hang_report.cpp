// Linked into every GoogleTest binary (tests/CMakeLists.txt, smart_add_test): a test still running
// shortly before ctest's timeout is about to be killed without a word of where it hung. Two such
// hangs in CI (both at stop 42, both a deadlock inside a `smart` child process) stayed
// unexplained for a whole stop. So, kReportBeforeS before the timeout, this prints the stack of
// every thread of the test process and of each process it started (gdb -batch, Debian's gdb, in
// scripts/install-deps.sh), or without gdb their states, to stderr, which ctest shows with the
// failure. A test that ends in time never sees it; run by hand (no SMART_TEST_TIMEOUT_S in the
// environment, which ctest sets to the test's TIMEOUT) it is off.
#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace {

constexpr int kReportBeforeS = 25;  // gdb takes a second or two per process

// The parent of process `pid` (field 4 of /proc/PID/stat, after the parenthesised name).
pid_t parent_of(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(stat.substr(close + 1));
  std::string state;
  pid_t ppid = -1;
  rest >> state >> ppid;
  return ppid;
}

// `root` and every process below it, parents first.
std::vector<pid_t> process_tree(pid_t root) {
  std::vector<pid_t> all;
  if (DIR* d = opendir("/proc")) {
    while (const dirent* e = readdir(d)) {
      const auto pid = static_cast<pid_t>(std::atoi(e->d_name));
      if (pid > 0) all.push_back(pid);
    }
    closedir(d);
  }
  std::vector<pid_t> tree{root};
  for (std::size_t i = 0; i < tree.size(); ++i) {
    for (const pid_t pid : all) {
      if (parent_of(pid) == tree[i]) tree.push_back(pid);
    }
  }
  return tree;
}

std::string first_line_of(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line, '\n');
  for (char& c : line) c = c == '\0' ? ' ' : c;
  return line;
}

std::string run(const std::string& command) {
  std::string out;
  if (FILE* f = popen(command.c_str(), "r")) {
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
    pclose(f);
  }
  return out;
}

// gdb's threads with the same stack (a server's idle workers) once, with their count: a report
// is read where CI shows only part of a test's output.
std::string collapse(const std::string& gdb_out) {
  std::vector<std::pair<std::string, int>> stacks;  // normalised stack, threads
  std::istringstream in(gdb_out);
  std::string line, stack;
  auto flush = [&] {
    if (stack.empty()) return;
    auto same =
        std::find_if(stacks.begin(), stacks.end(), [&](auto& s) { return s.first == stack; });
    if (same == stacks.end())
      stacks.emplace_back(stack, 1);
    else
      ++same->second;
    stack.clear();
  };
  while (std::getline(in, line)) {
    if (line.rfind("Thread ", 0) == 0) {
      flush();
      continue;
    }
    // Addresses and arguments differ between threads on one path; the functions do not.
    stack += std::regex_replace(line, std::regex("0x[0-9a-f]+|\\([^()]*\\)"), "") + "\n";
  }
  flush();
  std::string out;
  for (const auto& [s, n] : stacks) out += std::to_string(n) + " thread(s):\n" + s;
  return out;
}

void report(int after_s) {
  const bool gdb = !run("command -v gdb").empty();
  std::string text = "\n=== still running " + std::to_string(after_s) + " s after its start, " +
                     std::to_string(kReportBeforeS) +
                     " s before ctest's timeout: its processes' threads ===\n";
  for (const pid_t pid : process_tree(getpid())) {
    const std::string proc = "/proc/" + std::to_string(pid);
    text += "--- pid " + std::to_string(pid) + ": " +
            first_line_of(proc + "/cmdline").substr(0, 300) + "\n";
    if (!gdb) {
      text += run("grep -h '^State' " + proc + "/task/*/status 2>/dev/null | sort | uniq -c");
      continue;
    }
    text += collapse(run("timeout 20 gdb -batch -nx -p " + std::to_string(pid) +
                         " -ex 'thread apply all bt 30' 2>/dev/null | grep -E '^(Thread|#)'"));
  }
  text += "=== end of the hang report ===\n";
  std::fwrite(text.data(), 1, text.size(), stderr);
  std::fflush(stderr);
}

// Started with the binary; a detached thread that only sleeps, so an ordinary exit ends it.
[[maybe_unused]] const bool kStarted = [] {
  const char* timeout = std::getenv("SMART_TEST_TIMEOUT_S");
  const int after_s = (timeout != nullptr ? std::atoi(timeout) : 0) - kReportBeforeS;
  if (after_s <= 0) return false;
  std::thread([after_s] {
    std::this_thread::sleep_for(std::chrono::seconds(after_s));
    report(after_s);
  }).detach();
  return true;
}();

}  // namespace
