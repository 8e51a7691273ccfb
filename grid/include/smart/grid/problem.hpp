// Contract: a Problem is one thing wrong with an input (map, scenario, plan), located by source
// file, line, robot and, where known, cell and time. InputError carries every Problem found, so
// a user fixes all of them in one round. Messages say what happened, where, and how to fix it.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace smart::grid {

struct Problem {
  std::string source;  // file name (or "<text>")
  int line = 0;        // 1-based; 0 when not tied to a line
  int robot = -1;      // robot index; -1 when not tied to a robot
  std::string message;

  std::string to_string() const;  // "source:line: robot R: message"
};

class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<Problem> problems);
  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

// Throws InputError when `problems` is not empty.
void throw_if_any(std::vector<Problem> problems);

}  // namespace smart::grid
