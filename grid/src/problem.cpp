#include "smart/grid/problem.hpp"

namespace smart::grid {

std::string Problem::to_string() const {
  std::string s = source.empty() ? "<input>" : source;
  if (line > 0) s += ":" + std::to_string(line);
  s += ": ";
  if (robot >= 0) s += "robot " + std::to_string(robot) + ": ";
  return s + message;
}

namespace {
std::string summarize(const std::vector<Problem>& problems) {
  std::string s;
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
