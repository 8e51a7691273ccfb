#include "smart/lifelong/task_manager.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace smart::lifelong {

TaskManager::TaskManager(std::vector<grid::Task> source, std::size_t robots, std::size_t pool,
                         Scheduler& scheduler)
    : source_(std::move(source)), pool_(pool), scheduler_(scheduler), held_(robots) {
  if (source_.empty()) throw std::invalid_argument("a lifelong run needs at least one task");
  if (pool_ == 0) throw std::invalid_argument("the task pool (numTasksReveal x robots) is 0");
  for (const auto& t : source_) {
    if (t.errands.empty()) {
      throw std::invalid_argument("task " + std::to_string(t.id) + " has no errands");
    }
  }
}

void TaskManager::event(double t, const char* what, uint64_t task, std::optional<uint32_t> robot,
                        std::optional<uint32_t> errand) {
  events_.push_back({t, what, task, robot, errand, {}});
}

void TaskManager::update(double time_s, const std::vector<grid::Cell>& cells) {
  while (open_.size() < pool_) {
    const auto& src = source_[next_id_ % source_.size()];
    Open o;
    o.row.task = next_id_;
    o.row.source_task = src.id;
    o.row.errands = static_cast<uint32_t>(src.errands.size());
    o.row.revealed_s = time_s;
    for (const auto c : src.errands) o.row.cells.emplace_back(c.x, c.y);
    o.errands = src.errands;
    open_.emplace(next_id_, std::move(o));
    order_.push_back(next_id_);
    event(time_s, "revealed", next_id_, std::nullopt, std::nullopt);
    // Where it is, so a live view can draw it (tasks.csv has it only once it finished).
    events_.back().detail = results::cells_text(open_.at(next_id_).row.cells);
    ++next_id_;
  }
  std::vector<uint32_t> free;
  for (uint32_t r = 0; r < held_.size(); ++r) {
    if (!held_[r]) free.push_back(r);
  }
  if (free.empty()) return;
  std::vector<OpenTask> offer;
  for (const uint64_t id : order_) {
    const auto& o = open_.at(id);
    if (!o.row.robot) offer.push_back({id, o.errands.front()});
  }
  for (const auto& [r, id] : scheduler_.assign(free, cells, offer)) {
    auto& o = open_.at(id);
    if (held_.at(r) || o.row.robot) continue;  // a scheduler's mistake changes nothing
    held_[r] = id;
    o.row.robot = r;
    o.row.assigned_s = time_s;
    event(time_s, "assigned", id, r, std::nullopt);
  }
}

void TaskManager::reached_while_idle(uint32_t robot, grid::Cell cell, double time_s) {
  while (held_[robot] && on_reached(robot, cell, time_s)) {
  }
}

bool TaskManager::on_reached(uint32_t robot, grid::Cell cell, double time_s) {
  if (robot >= held_.size() || !held_[robot]) return false;
  const uint64_t id = *held_[robot];
  auto& o = open_.at(id);
  if (o.errands[o.row.errands_done] != cell) return false;
  const uint32_t k = o.row.errands_done++;
  if (k == 0) o.row.opened_s = time_s;
  if (o.row.errands_done < o.row.errands) {
    event(time_s, k == 0 ? "opened" : "errand", id, robot, k);
    return true;
  }
  o.row.finished_s = time_s;
  event(time_s, "finished", id, robot, k);
  ++finished_;
  done_.push_back(o.row);
  order_.erase(std::find(order_.begin(), order_.end(), id));
  open_.erase(id);
  held_[robot].reset();
  return true;
}

std::vector<grid::Cell> TaskManager::goals(uint32_t robot) const {
  if (!held_[robot]) return {};
  const auto& o = open_.at(*held_[robot]);
  return {o.errands.begin() + o.row.errands_done, o.errands.end()};
}

std::size_t TaskManager::robots_with_task() const {
  return static_cast<std::size_t>(
      std::count_if(held_.begin(), held_.end(), [](const auto& h) { return h.has_value(); }));
}

std::vector<results::EventRow> TaskManager::take_events() {
  std::vector<results::EventRow> out;
  out.swap(events_);
  return out;
}

std::vector<results::TaskRow> TaskManager::take_finished() {
  std::vector<results::TaskRow> out;
  out.swap(done_);
  return out;
}

std::vector<results::TaskRow> TaskManager::unfinished() const {
  std::vector<results::TaskRow> out;
  for (const uint64_t id : order_) out.push_back(open_.at(id).row);
  return out;
}

}  // namespace smart::lifelong
