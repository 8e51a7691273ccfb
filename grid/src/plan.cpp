#include "smart/grid/plan.hpp"

#include <algorithm>

namespace smart::grid {

std::string to_string(AxisOrder a) { return a == AxisOrder::kXY ? "xy" : "rowcol"; }

std::string to_string(PlanFormat f) {
  switch (f) {
    case PlanFormat::kAuto:
      return "auto";
    case PlanFormat::kSmart:
      return "smart";
    case PlanFormat::kLacam:
      return "lacam";
    case PlanFormat::kYaml:
      return "yaml";
  }
  return "auto";
}

double arrival_time(const RobotPath& path) {
  for (std::size_t k = path.steps.size(); k > 1; --k) {
    if (path.steps[k - 1].cell != path.steps[k - 2].cell) return path.steps[k - 1].time;
  }
  return path.steps.empty() ? 0.0 : path.steps.front().time;
}

PlanStats plan_stats(const Plan& plan) {
  PlanStats s;
  s.robots = plan.paths.size();
  for (const auto& p : plan.paths) {
    const double a = arrival_time(p);
    s.soc += a;
    s.makespan = std::max(s.makespan, a);
    for (std::size_t k = 1; k < p.steps.size(); ++k) {
      if (p.steps[k].cell != p.steps[k - 1].cell) {
        ++s.moves;
      } else {
        ++s.waits;
      }
    }
  }
  return s;
}

}  // namespace smart::grid
