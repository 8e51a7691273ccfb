// Comparing two runs' states.csv. The state topic is best effort, latest only
// (config/qos/*.yaml `state`): on a loaded machine a pose sample may be replaced or dropped
// before the monitor reads it, so which rows a file has is not part of a run's result. What is:
// every (time, robot) both files have shows the same state, to the digit; and the files share
// nearly all their rows (a check that could not pass on two unrelated files).
#pragma once

#include <map>
#include <string>
#include <utility>

#include "smart/monitor/results_format.hpp"

namespace smart::test {

// Empty when the rows both files have agree and they share at least 90 % of the smaller file's
// rows; otherwise the first disagreement, or the overlap.
inline std::string compare_state_rows(const std::string& a, const std::string& b) {
  const auto rows = [](const std::string& text) {
    std::map<std::pair<double, uint32_t>, std::string> out;
    results::for_each_state_row(text, [&](const results::StateRow& r) {
      std::string line;
      results::append_row(line, r);
      out[{r.t_s, r.robot}] = line;
    });
    return out;
  };
  const auto ra = rows(a), rb = rows(b);
  std::size_t common = 0;
  for (const auto& [key, line] : ra) {
    const auto it = rb.find(key);
    if (it == rb.end()) continue;
    ++common;
    if (it->second != line) return "'" + line + "' vs '" + it->second + "'";
  }
  const std::size_t smaller = std::min(ra.size(), rb.size());
  if (smaller == 0 || common * 10 < smaller * 9) {
    return std::to_string(common) + " rows in common of " + std::to_string(ra.size()) + " and " +
           std::to_string(rb.size());
  }
  return "";
}

}  // namespace smart::test
