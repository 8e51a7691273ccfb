#include "smart/lifelong/lifelong_execution.hpp"

#include <algorithm>
#include <string>

namespace smart::lifelong {

namespace {
std::size_t pool_of(const LifelongOptions& o, std::size_t robots) {
  return o.task_pool > 0 ? o.task_pool : std::max<std::size_t>(1, robots);
}
}  // namespace

LifelongExecution::LifelongExecution(const grid::Grid& grid, const std::vector<grid::Cell>& starts,
                                     std::vector<grid::Task> tasks, const LifelongOptions& options,
                                     std::function<double()> wall_ms)
    : LifelongExecution(
          grid, starts, std::move(tasks), options,
          std::make_unique<BuiltinPlanner>(
              grid,
              BuiltinPlannerOptions{options.distance_budget_mb, options.seed, options.heuristic,
                                    starts.size(), options.lns_passes},
              std::move(wall_ms))) {}

LifelongExecution::LifelongExecution(const grid::Grid& grid, const std::vector<grid::Cell>& starts,
                                     std::vector<grid::Task> tasks, const LifelongOptions& options,
                                     std::unique_ptr<WindowPlanner> planner)
    : options_(options),
      adg_(grid, starts, options.initial_heading),
      tasks_(std::move(tasks), starts.size(), pool_of(options, starts.size()), scheduler_),
      planner_(std::move(planner)) {
  if (options.switching) adg_.enable_switching(*options.switching);
}

monitor::ProgressUpdate LifelongExecution::on_progress(uint32_t robot, int64_t finished_seq,
                                                       double time_s) {
  std::vector<grid::Cell> reached;
  auto u = adg_.on_progress(robot, finished_seq, time_s, [&](const grid::Action& a) {
    if (observer_ != nullptr) observer_->executed(robot, a, time_s);
    if (a.type == grid::ActionType::kMove && a.to.is_cell()) {
      reached.push_back({a.to.x2 / 2, a.to.y2 / 2});
    }
  });
  const uint64_t before = tasks_.finished();
  for (const auto c : reached) tasks_.on_reached(robot, c, time_s);
  for (uint64_t k = before; k < tasks_.finished(); ++k) finish_times_.push_back(time_s);
  return u;
}

bool LifelongExecution::due(double time_s) const {
  if (time_s >= next_plan_s_) return true;
  if (options_.min_unfinished == 0) return false;
  for (uint32_t r = 0; r < adg_.robots(); ++r) {
    if (tasks_.task_of(r) && adg_.end(r) - adg_.finished(r) <= options_.min_unfinished) {
      return true;
    }
  }
  return false;
}

std::vector<uint32_t> LifelongExecution::on_time(double time_s, const std::vector<uint32_t>& sent) {
  now_s_ = std::max(now_s_, time_s);
  std::vector<uint32_t> changed;
  if (pending_) changed = arrive(time_s);
  if (!pending_ && !complete() && due(time_s)) {
    plan(time_s, sent);
    const auto more = arrive(time_s);
    changed.insert(changed.end(), more.begin(), more.end());
  }
  // Two windows may arrive in one call (a late one, then the next planned at once): each robot
  // once, so its window is pushed once.
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

void LifelongExecution::plan(double time_s, const std::vector<uint32_t>& sent) {
  const auto cut = adg_.commit_cut(sent, options_.lookahead);
  adg_.truncate(cut);
  tasks_.update(time_s, cut.cell);
  const std::size_t n = adg_.robots();
  planning::WindowRequest req{cut.cell, std::vector<std::vector<grid::Cell>>(n),
                              options_.window_steps, cut.heading, time_s};
  for (uint32_t r = 0; r < n; ++r) {
    // A robot standing still on its new task's errands has done them already.
    if (adg_.finished(r) == adg_.end(r)) tasks_.reached_while_idle(r, cut.cell[r], time_s);
    req.goals[r] = tasks_.goals(r);
  }
  next_plan_s_ = time_s + options_.period_s;
  while (!finish_times_.empty() && finish_times_.front() < time_s - 60) {
    finish_times_.erase(finish_times_.begin());
  }
  pending_ = Pending{time_s + options_.budget_s,
                     {time_s, tasks_.finished(), finish_times_.size(), 0, cut.kept_unfinished,
                      tasks_.robots_with_task()},
                     std::nullopt};
  planner_->submit(std::move(req));
}

// The planner's answer, appended once it is there and the sim-time budget has passed.
std::vector<uint32_t> LifelongExecution::arrive(double time_s) {
  if (!pending_->window) pending_->window = planner_->poll();
  if (!pending_->window || time_s < pending_->release_s) return {};
  const auto& w = *pending_->window;
  ++stats_.planner_calls;
  stats_.planner_total_ms += w.wall_ms;
  stats_.planner_max_ms = std::max(stats_.planner_max_ms, w.wall_ms);
  stats_.distance_tables = w.distance_tables;
  stats_.heuristic = w.heuristic;
  stats_.heuristic_mb = w.heuristic_mb;
  pending_->row.planner_ms = w.wall_ms;
  throughput_.push_back(pending_->row);
  auto changed = append(w, time_s);
  pending_.reset();
  return changed;
}

// A window not appended (the planner's error or the graph's refusal): robots stop at the cut.
void LifelongExecution::refuse(double time_s, const std::string& why) {
  ++stats_.windows_refused;
  events_.push_back({time_s, "refused", std::nullopt, std::nullopt, std::nullopt, why});
}

std::vector<uint32_t> LifelongExecution::append(const PlannedWindow& window, double time_s) {
  if (!window.error.empty()) {
    refuse(time_s, window.error);
    return {};
  }
  if (!window.replaced.empty())
    refuse(time_s, window.replaced + "; the fallback planner's window is used");
  std::vector<uint32_t> before(adg_.robots()), sent(adg_.robots());
  for (uint32_t r = 0; r < before.size(); ++r) {
    before[r] = adg_.end(r);
    sent[r] = adg_.enqueued(r);
  }
  monitor::AppendStats st;
  const auto problems = adg_.append(window.paths, time_s, &st);
  if (!problems.empty()) {
    refuse(time_s, problems.front().to_string());
    return {};
  }
  stats_.appended_actions += st.actions;
  stats_.type2_edges += st.type2;
  events_.push_back(
      {time_s, "window", std::nullopt, std::nullopt, std::nullopt,
       std::to_string(st.actions) + " actions " + std::to_string(st.type2) + " type-2 edges"});
  std::vector<uint32_t> changed;
  for (uint32_t r = 0; r < before.size(); ++r) {
    // A robot with new actions, or with an old one sent now: a held entry that the cut freed
    // (its followers dropped), or, switchable-opt, a due entry decided at the append.
    if (adg_.end(r) == before[r]) {
      if (adg_.enqueued(r) != sent[r]) changed.push_back(r);
      continue;
    }
    changed.push_back(r);
    if (observer_ == nullptr) continue;
    for (uint32_t seq = before[r]; seq < adg_.end(r); ++seq) {
      const auto& a = adg_.action(r, seq);
      observer_->planned(r, a, time_s, a.end_time - adg_.window_start());
    }
  }
  return changed;
}

std::vector<results::EventRow> LifelongExecution::take_events() {
  auto out = tasks_.take_events();
  out.insert(out.end(), events_.begin(), events_.end());
  events_.clear();
  std::stable_sort(
      out.begin(), out.end(),
      [](const results::EventRow& a, const results::EventRow& b) { return a.t_s < b.t_s; });
  stats_.tasks_finished = tasks_.finished();
  stats_.tasks_revealed = tasks_.revealed();
  return out;
}

std::vector<results::ThroughputRow> LifelongExecution::take_throughput() {
  std::vector<results::ThroughputRow> out;
  out.swap(throughput_);
  return out;
}

}  // namespace smart::lifelong
