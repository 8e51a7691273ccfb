#include "smart/grid/problem.hpp"

#include <algorithm>
#include <map>

namespace smart::grid {

std::string Problem::to_string() const {
  std::string s = source.empty() ? "<input>" : source;
  if (line > 0) s += ":" + std::to_string(line);
  s += ": ";
  if (robot >= 0) s += "robot " + std::to_string(robot) + ": ";
  return s + message;
}

namespace {
// A message with its numbers as '#': problems of one kind share it.
std::string kind_of(const std::string& message) {
  std::string k;
  for (const char c : message) {
    const bool digit = c >= '0' && c <= '9';
    if (!digit) {
      k += c;
    } else if (k.empty() || k.back() != '#') {
      k += '#';
    }
  }
  return k;
}

// Many problems of one kind are one mistake (a plan of another instance, a wrong --axis): a line
// saying so comes first (issue 26: 247 problems and no summary line).
std::string diagnosis(const std::vector<Problem>& problems) {
  constexpr std::size_t kMany = 10;
  if (problems.size() < kMany) return {};
  std::map<std::string, std::size_t> kinds;
  for (const auto& p : problems) ++kinds[kind_of(p.message)];
  const auto top = std::max_element(
      kinds.begin(), kinds.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  if (top->second * 2 < problems.size()) return {};
  return std::to_string(top->second) + " of " + std::to_string(problems.size()) +
         " problems are one kind, most likely one mistake: " + top->first + "\n";
}

std::string summarize(const std::vector<Problem>& problems) {
  std::string s = diagnosis(problems);
  constexpr std::size_t kShown = 50;
  for (std::size_t i = 0; i < problems.size() && i < kShown; ++i) {
    if (i > 0) s += "\n";
    s += problems[i].to_string();
  }
  if (problems.size() > kShown) {
    s += "\n... and " + std::to_string(problems.size() - kShown) + " more problems";
  }
  return s;
}
}  // namespace

InputError::InputError(std::vector<Problem> problems)
    : std::runtime_error(summarize(problems)), problems_(std::move(problems)) {}

void throw_if_any(std::vector<Problem> problems) {
  if (!problems.empty()) throw InputError(std::move(problems));
}

}  // namespace smart::grid
