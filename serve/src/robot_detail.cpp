#include "smart/serve/robot_detail.hpp"

#include <map>
#include <stdexcept>
#include <string>

namespace smart::serve {

namespace {
using nlohmann::json;

json point(const monitor::Instance& in, grid::HalfCell h, double cell_m) {
  const auto p = in.grid.to_world(h, cell_m);
  return json::array({p.x_m, p.y_m});
}

// Other robot -> number of Type-2 edges between it and `robot`, in one direction.
json partners(const monitor::Instance& in, uint32_t robot, bool incoming) {
  const auto& adg = in.adg;
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
}  // namespace

json robot_detail(const monitor::Instance& in, uint32_t robot, double cell_m) {
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
          {"waits_for", partners(in, robot, true)},
          {"waited_by", partners(in, robot, false)}};
}

}  // namespace smart::serve
