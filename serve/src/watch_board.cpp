#include "smart/serve/watch_board.hpp"

#include <algorithm>

namespace smart::serve {

WatchBoard::Run* WatchBoard::run_for(uint64_t run_id, double now_s) {
  auto it = runs_.find(run_id);
  if (it == runs_.end()) {
    if (runs_.size() >= kMaxRuns) {  // drop the run heard of least recently
      auto oldest = std::min_element(runs_.begin(), runs_.end(), [](const auto& a, const auto& b) {
        return a.second.heard_s < b.second.heard_s;
      });
      robots_ -= oldest->second.robots.size();
      runs_.erase(oldest);
    }
    it = runs_.emplace(run_id, Run{}).first;
  }
  it->second.heard_s = std::max(it->second.heard_s, now_s);
  return &it->second;
}

WatchBoard::Robot* WatchBoard::robot_for(uint64_t run_id, uint32_t robot, double now_s) {
  Run* run = run_for(run_id, now_s);
  auto it = run->robots.find(robot);
  if (it == run->robots.end()) {
    if (robots_ >= kMaxRobots) return nullptr;
    ++robots_;
    it = run->robots.emplace(robot, Robot{}).first;
  }
  it->second.heard_s = now_s;
  return &it->second;
}

void WatchBoard::on_state(const WatchedState& s, double now_s) {
  Robot* r = robot_for(s.run_id, s.robot, now_s);
  if (r == nullptr) return;
  r->state = s;
  r->progress.robot = s.robot;
  Run& run = runs_.at(s.run_id);
  run.sim_time_s = std::max(run.sim_time_s, s.sim_time_s);
}

void WatchBoard::on_progress(const WatchedProgress& p, double now_s) {
  Robot* r = robot_for(p.run_id, p.robot, now_s);
  if (r == nullptr) return;
  r->progress = p;
  r->state.robot = p.robot;
}

void WatchBoard::on_monitor(const WatchedMonitor& m, double now_s) {
  Run* run = run_for(m.run_id, now_s);
  run->monitor = m;
  run->monitor_known = true;
}

nlohmann::json WatchBoard::robot_json(const Robot& r, double now_s) const {
  const auto& s = r.state;
  const bool executing = r.progress.executing_seq > r.progress.finished_seq;
  const char* status = now_s - r.heard_s > stale_s_ ? "stale"
                       : executing                  ? "moving"
                       : s.queue > 0                ? "waiting"
                                                    : "idle";
  return {{"id", s.robot},
          {"x_m", s.x_m},
          {"y_m", s.y_m},
          {"yaw_rad", s.yaw_rad},
          {"linear_mps", s.linear_mps},
          {"status", status},
          {"queue", s.queue},
          {"finished_seq", r.progress.finished_seq},
          {"executing_seq", r.progress.executing_seq}};
}

nlohmann::json WatchBoard::snapshot(double now_s, uint64_t run_id) const {
  nlohmann::json runs = nlohmann::json::array();
  const Run* shown = nullptr;
  uint64_t shown_id = 0;
  for (const auto& [id, run] : runs_) {
    runs.push_back({{"run_id", id},
                    {"name", run.monitor_known ? run.monitor.run : ""},
                    {"robots", run.robots.size()},
                    {"heard_s_ago", now_s - run.heard_s}});
    const bool pick = run_id != 0 ? id == run_id : !shown || run.heard_s > shown->heard_s;
    if (pick) shown = &run, shown_id = id;
  }
  nlohmann::json robots = nlohmann::json::array();
  nlohmann::json monitor;  // null unless known
  if (shown) {
    for (const auto& [id, r] : shown->robots) robots.push_back(robot_json(r, now_s));
    if (shown->monitor_known)
      monitor = {{"host", shown->monitor.host}, {"pid", shown->monitor.pid}};
  }
  return {{"runs", runs},
          {"run_id", shown_id},
          {"name", shown && shown->monitor_known ? shown->monitor.run : ""},
          {"monitor", monitor},
          {"t_s", shown ? shown->sim_time_s : 0.0},
          {"robots", robots}};
}

}  // namespace smart::serve
