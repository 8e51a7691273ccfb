// Runs the real `smart` executable as a child process and collects its stdout.
#pragma once

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "smart/tools/child_process.hpp"
#include "support/dds_test_support.hpp"

namespace smart::test {

struct SmartRun {
  int code = -1;  // -1: timed out (the process was killed)
  std::string out;
  nlohmann::json last_json() const {
    // The JSON summary is printed last on stdout.
    const auto start = out.find('{');
    return start == std::string::npos ? nlohmann::json() : nlohmann::json::parse(out.substr(start));
  }
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline SmartRun run_smart(const std::vector<std::string>& args, std::chrono::seconds timeout,
                          const std::string& tag) {
  const auto out = temp_file(tag + ".out");
  std::vector<std::string> argv{smart_exe().string()};
  argv.insert(argv.end(), args.begin(), args.end());
  tools::ChildProcess p(argv, out);
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
