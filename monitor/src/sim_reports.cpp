#include "smart/monitor/sim_reports.hpp"

namespace smart::monitor {

std::optional<std::string> sim_disagreement(const MonitorResult& r,
                                            const std::vector<SimWord>& reports) {
  if (!r.success()) return std::nullopt;
  uint64_t robot = 0, wall = 0;
  for (std::size_t s = 0; s < reports.size(); ++s) {
    const auto* report = std::get_if<results::SimReport>(&reports[s]);
    if (!report) {
      return "sim host " + std::to_string(s) + " left no readable report (" +
             std::get<std::string>(reports[s]) + ")";
    }
    if (!report->ok) {
      return "sim host " + std::to_string(s) + " reports a failure: " + report->error;
    }
    robot += report->robot_contacts;
    wall += report->wall_contacts;
  }
  if (robot == r.robot_contacts && wall == r.wall_contacts) return std::nullopt;
  return "the sim hosts' own reports count " + std::to_string(robot) + " robot-robot and " +
         std::to_string(wall) +
         " robot-wall collisions, but the status the monitor received said " +
         std::to_string(r.robot_contacts) + " and " + std::to_string(r.wall_contacts) +
         "; a participant that is not the sim host wrote sim status (see rejected_samples)";
}

void apply_sim_reports(MonitorResult& r, const std::vector<SimWord>& reports) {
  if (auto why = sim_disagreement(r, reports)) {
    r.outcome = Outcome::kUnverified;
    r.error = "unverified: every action finished, but " + *why;
  }
}

}  // namespace smart::monitor
