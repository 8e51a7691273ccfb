#include "smart/serve/robot_detail.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "smart/monitor/adg.hpp"
#include "smart/monitor/results_format.hpp"

namespace smart::serve {

namespace {
using nlohmann::json;

json point(const monitor::Instance& in, grid::HalfCell h, double cell_m) {
  const auto p = in.grid.to_world(h, cell_m);
  return json::array({p.x_m, p.y_m});
}

// Other robot -> number of Type-2 edges between it and `robot`, in one direction.
json partners(const monitor::Instance& in, const monitor::Adg& adg, uint32_t robot, bool incoming) {
  const auto& edges = incoming ? adg.in : adg.out;
  const auto& begin = incoming ? adg.in_begin : adg.out_begin;
  std::map<uint32_t, uint32_t> count;
  const uint32_t first = in.actions.offset[robot], last = in.actions.offset[robot + 1];
  for (uint32_t node = first; node < last; ++node) {
    for (uint32_t e = begin[node]; e < begin[node + 1]; ++e)
      ++count[in.actions.actions[edges[e]].robot];
  }
  json out = json::array();
  for (const auto& [other, n] : count) out.push_back({{"robot", other}, {"edges", n}});
  return out;
}

json time_or_null(const std::vector<double>& finish_s, std::size_t node) {
  return node < finish_s.size() && !std::isnan(finish_s[node]) ? json(finish_s[node]) : json();
}

// When the robot of `node` had finished every action before it (0 for its first action).
json ready_time(const monitor::Instance& in, const std::vector<double>& finish_s, uint32_t node) {
  const auto& a = in.actions.actions[node];
  if (a.seq == 0) return 0.0;
  return time_or_null(finish_s, node - 1);
}

// The plan's ADG has the Type-2 edge from -> to.
bool planned(const monitor::Adg& adg, uint32_t from, uint32_t to) {
  const auto b = adg.in.begin() + adg.in_begin[to], e = adg.in.begin() + adg.in_begin[to + 1];
  return std::find(b, e, from) != e;
}

json steps(const monitor::Instance& in, const monitor::Adg& adg, uint32_t robot,
           const std::vector<double>& finish_s) {
  const bool switched = &adg != &in.adg;
  json out = json::array();
  for (uint32_t node = in.actions.offset[robot]; node < in.actions.offset[robot + 1]; ++node) {
    const auto& a = in.actions.actions[node];
    json waits = json::array(), waited = json::array();
    for (uint32_t e = adg.in_begin[node]; e < adg.in_begin[node + 1]; ++e) {
      const auto& o = in.actions.actions[adg.in[e]];
      waits.push_back({o.robot, o.seq, time_or_null(finish_s, adg.in[e])});
      if (switched && !planned(in.adg, adg.in[e], node)) waits.back().push_back(true);
    }
    for (uint32_t e = adg.out_begin[node]; e < adg.out_begin[node + 1]; ++e) {
      const auto& o = in.actions.actions[adg.out[e]];
      waited.push_back({o.robot, o.seq, ready_time(in, finish_s, adg.out[e])});
      if (switched && !planned(in.adg, node, adg.out[e])) waited.back().push_back(true);
    }
    out.push_back({{"type", a.type == grid::ActionType::kMove ? "move" : "rotate"},
                   {"finish_s", time_or_null(finish_s, node)},
                   {"in", waits},
                   {"out", waited}});
  }
  return out;
}

}  // namespace

std::vector<double> parse_action_times(std::string_view csv, const monitor::ActionPlan& actions) {
  std::vector<double> times(actions.actions.size(), std::nan(""));
  results::for_each_action_row(csv, [&](const results::ActionRow& row, std::size_t line) {
    if (row.robot >= actions.robots() || row.action >= actions.count(row.robot)) {
      throw std::invalid_argument(std::string(results::kActionsCsv) + " line " +
                                  std::to_string(line) + ": robot " + std::to_string(row.robot) +
                                  " action " + std::to_string(row.action) +
                                  " is not an action of this run's plan");
    }
    if (row.finish_time_s) times[actions.offset[row.robot] + row.action] = *row.finish_time_s;
  });
  return times;
}

json finished_curve(std::vector<double> finish_s, std::size_t max_points) {
  std::erase_if(finish_s, [](double t) { return std::isnan(t); });
  std::sort(finish_s.begin(), finish_s.end());
  json t = json::array(), n = json::array();
  const std::size_t total = finish_s.size();
  const std::size_t step =
      std::max<std::size_t>(1, (total + max_points - 1) / std::max<std::size_t>(max_points, 1));
  for (std::size_t i = step; i < total; i += step) {
    t.push_back(finish_s[i - 1]);
    n.push_back(i);
  }
  if (total > 0) {
    t.push_back(finish_s.back());
    n.push_back(total);
  }
  return {{"t_s", t}, {"finished", n}};
}

json starts_and_goals(const monitor::Instance& in, double cell_m) {
  json starts = json::array(), goals = json::array();
  for (uint32_t r = 0; r < in.actions.robots(); ++r) {
    auto goal = in.actions.start[r];
    for (uint32_t s = 0; s < in.actions.count(r); ++s) {
      const auto& a = in.actions.at(r, s);
      if (a.type == grid::ActionType::kMove && a.to.is_cell()) goal = a.to;
    }
    starts.push_back(point(in, in.actions.start[r], cell_m));
    goals.push_back(point(in, goal, cell_m));
  }
  return {{"starts", starts}, {"goals", goals}};
}

monitor::Adg ended_adg(const monitor::Instance& in, const std::vector<results::SwitchRow>& rows,
                       const std::vector<double>& finish_s, std::size_t* unmatched) {
  auto orders = monitor::passing_orders(in.actions, in.grid, in.adg.footprint);
  const std::size_t missed = monitor::apply_switches(
      orders, monitor::passing_switches(in.grid, in.actions, rows), finish_s);
  if (unmatched != nullptr) *unmatched = missed;
  return monitor::adg_of_orders(orders, in.actions, in.adg.footprint);
}

json robot_detail(const monitor::Instance& in, uint32_t robot, double cell_m,
                  const std::vector<double>& finish_s, const monitor::Adg* ended) {
  const monitor::Adg& adg = ended != nullptr ? *ended : in.adg;
  if (robot >= in.actions.robots()) {
    throw std::out_of_range("robot " + std::to_string(robot) + " is not in this run");
  }
  json path = json::array({point(in, in.actions.start[robot], cell_m)});
  for (uint32_t s = 0; s < in.actions.count(robot); ++s) {
    const auto& a = in.actions.at(robot, s);
    if (a.type == grid::ActionType::kMove && a.to.is_cell())
      path.push_back(point(in, a.to, cell_m));
  }
  return {{"robot", robot},
          {"actions", in.actions.count(robot)},
          {"path", path},
          {"waits_for", partners(in, adg, robot, true)},
          {"waited_by", partners(in, adg, robot, false)},
          {"steps", steps(in, adg, robot, finish_s)}};
}

}  // namespace smart::serve
