#include "smart/serve/task_timeline.hpp"

#include <algorithm>
#include <map>

#include "smart/monitor/results_format.hpp"

namespace smart::serve {

namespace {

using nlohmann::json;

json or_null(const std::optional<double>& v) { return v ? json(*v) : json(); }

json task_json(const results::TaskRow& t) {
  json cells = json::array();
  for (const auto& [x, y] : t.cells) cells.push_back({x, y});
  return {{"id", t.task},
          {"robot", t.robot ? json(*t.robot) : json()},
          {"revealed_s", t.revealed_s},
          {"assigned_s", or_null(t.assigned_s)},
          {"finished_s", or_null(t.finished_s)},
          {"cells", std::move(cells)},
          {"done_s", json::array()}};
}

// A running run's task as its events tell it (tasks.csv has only the finished ones yet).
void apply_event(std::map<uint64_t, json>& tasks, const results::EventRow& e) {
  if (!e.task) return;
  if (e.event == "revealed" && !tasks.count(*e.task)) {
    const auto cells = results::parse_cells(e.detail);
    if (!cells || cells->empty()) return;
    results::TaskRow row;
    row.task = *e.task;
    row.revealed_s = e.t_s;
    row.cells = *cells;
    tasks[*e.task] = task_json(row);
    return;
  }
  const auto it = tasks.find(*e.task);
  if (it == tasks.end()) return;
  auto& t = it->second;
  if (e.event == "assigned" && e.robot && t["robot"].is_null()) {
    t["robot"] = *e.robot;
    t["assigned_s"] = e.t_s;
  }
  if ((e.event == "opened" || e.event == "errand" || e.event == "finished") && e.errand) {
    auto& done = t["done_s"];
    if (*e.errand == done.size() && done.size() < t["cells"].size()) done.push_back(e.t_s);
    if (e.event == "finished" && t["finished_s"].is_null()) t["finished_s"] = e.t_s;
  }
}

}  // namespace

json task_timeline(std::string_view tasks_csv, std::string_view events_csv,
                   std::string_view throughput_csv) {
  std::map<uint64_t, json> tasks;
  for (const auto& t : results::parse_tasks_csv(tasks_csv)) tasks[t.task] = task_json(t);
  for (const auto& e : results::parse_events_csv(events_csv)) apply_event(tasks, e);
  json out = {{"tasks", json::array()}};
  for (auto& [id, t] : tasks) out["tasks"].push_back(std::move(t));
  json t_s = json::array(), finished = json::array(), last_min = json::array();
  for (const auto& r : results::parse_throughput_csv(throughput_csv)) {
    t_s.push_back(r.t_s);
    finished.push_back(r.tasks_finished);
    last_min.push_back(r.tasks_last_min);
  }
  out["throughput"] = {{"t_s", std::move(t_s)},
                       {"finished", std::move(finished)},
                       {"last_min", std::move(last_min)}};
  return out;
}

}  // namespace smart::serve
