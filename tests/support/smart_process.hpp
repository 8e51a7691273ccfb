// Runs the real `smart` executable as a child process and collects its stdout.
#pragma once

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "smart/common/child_process.hpp"
#include "support/dds_test_support.hpp"

namespace smart::test {

// The JSON summary a `smart` command prints last on stdout (null if there is none).
inline nlohmann::json summary_in(const std::string& out) {
  const auto start = out.find('{');
  if (start == std::string::npos) return nlohmann::json();
  // One value: a run's verdict and warnings follow its summary when stderr is merged.
  std::istringstream in(out.substr(start));
  nlohmann::json j;
  in >> j;
  return j;
}

// The last line of `out` that opens a JSON object: a command's report when its stderr (which may
// hold YAML or other braces) is merged into `out`.
inline nlohmann::json last_json_line(const std::string& out) {
  const auto at = out.rfind("\n{");
  // One value: a run's verdict follows its summary on stderr (tools/src/run_commands.cpp).
  std::istringstream in(at == std::string::npos ? out : out.substr(at + 1));
  nlohmann::json j;
  in >> j;
  return j;
}

struct SmartRun {
  int code = -1;  // -1: timed out (the process was killed)
  std::string out;
  nlohmann::json last_json() const { return summary_in(out); }
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Starts `smart args...` in the background, stdout to `out`; its log (stderr) to `log` if given.
inline common::ChildProcess start_smart(const std::vector<std::string>& args,
                                        const std::filesystem::path& out,
                                        const std::filesystem::path& log = {}) {
  std::vector<std::string> argv{smart_exe().string()};
  argv.insert(argv.end(), args.begin(), args.end());
  if (!log.empty()) {
    argv.insert(argv.begin(), {"/bin/sh", "-c", "exec \"$0\" \"$@\" 2>'" + log.string() + "'"});
  }
  return common::ChildProcess(argv, out);
}

// Waits until `done()` while `p` runs: an event, not a guessed time (a loaded machine starts
// processes slower than any bound). False if `p` exited first, or it did not come within `hang`
// (which only catches a hang).
template <class Done>
bool wait_while_running(common::ChildProcess& p, std::chrono::seconds hang, Done done) {
  const auto deadline = std::chrono::steady_clock::now() + hang * kSlowdown;
  while (std::chrono::steady_clock::now() < deadline) {
    const bool ran = p.running();
    if (done()) return true;
    if (!ran) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// Until `out` holds `text`.
inline bool wait_for_output(common::ChildProcess& p, const std::filesystem::path& out,
                            const std::string& text,
                            std::chrono::seconds hang = std::chrono::seconds(60)) {
  return wait_while_running(p, hang, [&] { return slurp(out).find(text) != std::string::npos; });
}

// Until `file` (a CSV with a header that `p` appends to) holds `rows` rows.
inline bool wait_for_rows(common::ChildProcess& p, const std::filesystem::path& file,
                          std::size_t rows, std::chrono::seconds hang = std::chrono::seconds(60)) {
  return wait_while_running(p, hang, [&] {
    const auto text = slurp(file);
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) >= rows + 1;
  });
}

// Until a run with `--out dir` has finished an action (a row of dir/progress.csv,
// results_format.hpp kProgressCsv): the run is under way, its robots moving.
inline bool wait_for_progress(common::ChildProcess& p, const std::filesystem::path& dir) {
  return wait_for_rows(p, dir / "progress.csv", 1);
}

// The port `smart serve --port 0` (stdout to `out`) says it listens on ("http://127.0.0.1:PORT"),
// waited for until it says so or exits: a loaded machine starts it slower than any guessed bound.
// 0 if it exited first, or said nothing within `hang` (which only catches a hang).
inline int serve_port(common::ChildProcess& serve, const std::filesystem::path& out,
                      std::chrono::seconds hang = std::chrono::seconds(60)) {
  const auto deadline = std::chrono::steady_clock::now() + hang;
  while (serve.running() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto j = summary_in(slurp(out));
    if (j.is_object()) return std::stoi(j["listening"].get<std::string>().substr(17));
  }
  return 0;
}

// Runs `smart args...` to the end; with_stderr: its error messages are in `out` too.
inline SmartRun run_smart(const std::vector<std::string>& args, std::chrono::seconds timeout,
                          const std::string& tag, bool with_stderr = false) {
  const auto out = temp_file(tag + ".out");
  std::vector<std::string> argv{smart_exe().string()};
  argv.insert(argv.end(), args.begin(), args.end());
  if (with_stderr) argv.insert(argv.begin(), {"/bin/sh", "-c", "exec \"$0\" \"$@\" 2>&1"});
  common::ChildProcess p(argv, out);
  SmartRun r;
  if (auto rc = p.wait(timeout)) {
    r.code = *rc;
  } else {
    p.terminate();
  }
  r.out = slurp(out);
  std::filesystem::remove(out);
  return r;
}

}  // namespace smart::test
