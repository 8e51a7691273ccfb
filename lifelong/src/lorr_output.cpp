#include "smart/lifelong/lorr_output.hpp"

#include <algorithm>
#include <cmath>

namespace smart::lifelong {

namespace {

using ojson = nlohmann::ordered_json;

// LoRR's orientation (0 east, 1 south, 2 west, 3 north; Start-Kit ActionModel: moves =
// {+1, +cols, -1, -cols}) of a grid heading (0 east, 1 north, 2 west, 3 south: CCW positive).
int lorr_orientation(grid::Heading h) {
  static constexpr int kOf[4] = {0, 3, 2, 1};
  return kOf[static_cast<int>(h)];
}

constexpr const char* kOrientationName[4] = {"E", "S", "W", "N"};

struct Pose {
  int32_t row, col;
  int ori;
  void apply(char action) {
    static constexpr int kDRow[4] = {0, 1, 0, -1}, kDCol[4] = {1, 0, -1, 0};
    if (action == 'F') {
      row += kDRow[ori];
      col += kDCol[ori];
    } else if (action == 'R') {
      ori = (ori + 1) % 4;
    } else if (action == 'C') {
      ori = (ori + 3) % 4;
    }
  }
};

void run_length(std::string& out, char action, int64_t n, bool& first) {
  if (n <= 0) return;
  if (!first) out += ',';
  first = false;
  out += action;
  out += ' ';
  out += std::to_string(n);
}

}  // namespace

int64_t lorr_tick(double t_s) { return static_cast<int64_t>(std::floor(t_s / kLorrTickS + 1e-6)); }

LorrOutput::LorrOutput(const grid::Grid& grid, const std::vector<grid::Cell>& starts,
                       grid::Heading initial_heading, std::vector<grid::Task> source_tasks,
                       int segment_ticks)
    : width_(grid.width()),
      starts_(starts),
      initial_(initial_heading),
      source_(std::move(source_tasks)),
      segment_ticks_(std::max(1, segment_ticks)),
      robots_(starts.size(), Robot{{}, {}, initial_heading, {}}) {}

// The LoRR steps of one finished grid action at `tick` (a half-move into a midpoint is none).
void LorrOutput::add(std::vector<Step>& steps, grid::Heading& heading, const grid::Action& a,
                     int64_t tick, uint32_t seq) {
  std::string actions;
  if (a.type == grid::ActionType::kMove) {
    if (a.to.is_cell()) actions = "F";
  } else {
    const int turn = (static_cast<int>(a.heading) - static_cast<int>(heading) + 4) % 4;
    actions = turn == 1 ? "C" : turn == 3 ? "R" : turn == 2 ? "RR" : "";
    heading = a.heading;
  }
  for (const char c : actions) {
    const int64_t at = steps.empty() ? tick : std::max(tick, steps.back().tick + 1);
    steps.push_back({at, c, seq, heading});
  }
}

void LorrOutput::executed(uint32_t robot, const grid::Action& a, double time_s) {
  if (robot >= robots_.size()) return;
  auto& r = robots_[robot];
  add(r.executed, r.executed_heading, a, lorr_tick(time_s), a.seq);
}

void LorrOutput::planned(uint32_t robot, const grid::Action& a, double appended_s, double step) {
  if (robot >= robots_.size()) return;
  auto& r = robots_[robot];
  // What was planned from this seq on was dropped by the commit cut: the new window replaces it.
  const auto from = std::find_if(r.planned.begin(), r.planned.end(),
                                 [&](const Step& s) { return s.seq >= a.seq; });
  r.planned.erase(from, r.planned.end());
  grid::Heading heading = r.planned.empty() ? initial_ : r.planned.back().heading;
  add(r.planned, heading, a, lorr_tick(appended_s) + std::llround(step), a.seq);
}

void LorrOutput::schedule(uint32_t robot, int64_t tick, int64_t task) {
  if (robot >= robots_.size()) return;
  auto& s = robots_[robot].schedule;
  if (!s.empty() && s.back().first == tick) s.pop_back();  // one entry per tick: the last
  const int64_t before = s.empty() ? -1 : s.back().second;
  if (task != before || s.empty()) s.emplace_back(tick, task);
  if (s.size() == 1 && s.front().second == -1) s.clear();  // none from the start: nothing
}

void LorrOutput::on_event(const results::EventRow& e) {
  const int64_t tick = lorr_tick(e.t_s);
  if (e.event == "revealed" && e.task && !source_.empty()) {
    ojson cells = ojson::array();
    for (const auto c : source_[*e.task % source_.size()].errands) {
      cells.push_back(c.y);
      cells.push_back(c.x);
    }
    tasks_.push_back(ojson::array({*e.task, tick, std::move(cells)}));
  } else if (e.event == "assigned" && e.task && e.robot) {
    schedule(*e.robot, tick, static_cast<int64_t>(*e.task));
  } else if ((e.event == "opened" || e.event == "errand" || e.event == "finished") && e.task &&
             e.robot && e.errand) {
    events_.push_back(ojson::array({tick, *e.robot, *e.task, *e.errand + 1}));
    if (e.event == "finished") schedule(*e.robot, tick, -1);
  } else if (e.event == "refused") {
    ++(e.detail.find("late: no reply") != std::string::npos ? timeouts_ : planner_errors_);
  }
}

void LorrOutput::on_planner_call(const results::ThroughputRow& row) {
  planner_s_.push_back(row.planner_ms / 1000.0);
}

// Segments of segment_ticks_ ticks: "[(t,row,col,ori,0):(A n,A n,...)]", each opening with the
// robot's state at its first tick.
std::string LorrOutput::path_string(const std::vector<Step>& steps, uint32_t robot,
                                    int64_t ticks) const {
  Pose p{starts_[robot].y, starts_[robot].x, lorr_orientation(initial_)};
  std::string out;
  auto next = steps.begin();
  for (int64_t t0 = 0; t0 < ticks; t0 += segment_ticks_) {
    const int64_t t1 = std::min<int64_t>(t0 + segment_ticks_, ticks);
    out += "[(" + std::to_string(t0) + "," + std::to_string(p.row) + "," + std::to_string(p.col) +
           "," + std::to_string(p.ori) + ",0):(";
    bool first = true;
    int64_t cursor = t0;
    char run = 0;
    int64_t run_n = 0;
    const auto emit = [&](char a, int64_t n) {
      if (n <= 0) return;
      if (a == run) return void(run_n += n);
      run_length(out, run, run_n, first);
      run = a;
      run_n = n;
    };
    for (; next != steps.end() && next->tick < t1; ++next) {
      emit('W', next->tick - cursor);
      emit(next->action, 1);
      p.apply(next->action);
      cursor = next->tick + 1;
    }
    emit('W', t1 - cursor);
    run_length(out, run, run_n, first);
    out += ")]";
  }
  return out;
}

nlohmann::ordered_json LorrOutput::json(const LorrRunEnd& end) const {
  const int64_t ticks = lorr_tick(end.duration_s);
  ojson j;
  j["actionModel"] = "MAPF_T";
  j["version"] = "2026 LoRR";
  j["teamSize"] = robots_.size();
  j["numTaskFinished"] = end.tasks_finished;
  uint64_t cost = 0;
  for (const auto& r : robots_) {
    cost += static_cast<uint64_t>(std::count_if(r.executed.begin(), r.executed.end(),
                                                [&](const Step& s) { return s.tick < ticks; }));
  }
  j["sumOfCost"] = cost;
  j["makespan"] = ticks;
  j["numPlannerErrors"] = planner_errors_;
  j["numScheduleErrors"] = 0;
  j["numEntryTimeouts"] = timeouts_;
  j["agentMaxCounter"] = 1;
  j["outputSegmentSize"] = segment_ticks_;
  ojson delays = ojson::array(), start = ojson::array(), actual = ojson::array(),
        planned = ojson::array();
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    ojson d = ojson::array();
    if (r < end.delay_intervals.size()) {
      for (const auto& [a, b] : end.delay_intervals[r]) d.push_back(ojson::array({a, b}));
    }
    delays.push_back(std::move(d));
    start.push_back(
        ojson::array({starts_[r].y, starts_[r].x, kOrientationName[lorr_orientation(initial_)]}));
    actual.push_back(path_string(robots_[r].executed, r, ticks));
    planned.push_back(path_string(robots_[r].planned, r, ticks));
  }
  j["delayIntervals"] = std::move(delays);
  j["start"] = std::move(start);
  j["actualPaths"] = std::move(actual);
  j["events"] = events_;
  j["tasks"] = tasks_;
  j["plannerPaths"] = std::move(planned);
  j["plannerTimes"] = planner_s_;
  ojson errors = ojson::array();
  for (const auto& c : end.collisions) {
    errors.push_back(ojson::array({-1, c.a, c.b, lorr_tick(c.t_s),
                                   "robots " + std::to_string(c.a) + " and " + std::to_string(c.b) +
                                       " collided (physics contact)"}));
  }
  j["errors"] = std::move(errors);
  ojson schedules = ojson::array();
  for (const auto& r : robots_) {
    std::string s;
    for (const auto& [tick, task] : r.schedule) {
      s += (s.empty() ? "" : ",") + std::to_string(tick) + ":" + std::to_string(task);
    }
    schedules.push_back(s);
  }
  j["actualSchedule"] = schedules;
  j["plannerSchedule"] = std::move(schedules);  // every proposal of the scheduler is taken
  j["scheduleErrors"] = ojson::array();
  j["discretisation"] = {
      {"tick_s", kLorrTickS},
      {"source", "SMART-DDS"},
      {"note",
       "continuous execution discretised: each action at the tick it finished (executed) or was "
       "planned to finish (planned), one tick per action (agentMaxCounter 1), waits between"}};
  return j;
}

}  // namespace smart::lifelong
