#include "smart/lifelong/plan_protocol.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <unordered_map>

namespace smart::lifelong {

namespace {

using nlohmann::json;

json cell_json(grid::Cell c) { return json::array({c.x, c.y}); }

std::string robot_step(std::size_t r, std::size_t k) {
  return "robot " + std::to_string(r) + " step " + std::to_string(k);
}

// A path of cells [[x, y], ...]; the reason names the robot and step of what is wrong.
bool read_path(const json& j, std::size_t r, std::vector<grid::Cell>& out, std::string& why) {
  if (!j.is_array()) {
    why = "paths[" + std::to_string(r) + "] is not an array of [x, y] cells";
    return false;
  }
  out.reserve(j.size());
  for (std::size_t k = 0; k < j.size(); ++k) {
    const json& c = j[k];
    if (!c.is_array() || c.size() != 2 || !c[0].is_number_integer() || !c[1].is_number_integer()) {
      why = robot_step(r, k) + ": a cell is [x, y], two integers (x the column, y the row)";
      return false;
    }
    const auto x = c[0].get<int64_t>(), y = c[1].get<int64_t>();
    if (x < INT32_MIN || x > INT32_MAX || y < INT32_MIN || y > INT32_MAX) {
      why = robot_step(r, k) + ": cell [" + std::to_string(x) + ", " + std::to_string(y) +
            "] is far off the map";
      return false;
    }
    out.push_back({static_cast<int32_t>(x), static_cast<int32_t>(y)});
  }
  return true;
}

PlanReply malformed(std::string why) {
  return {PlanReply::Kind::kMalformed, {}, "malformed reply: " + std::move(why)};
}

}  // namespace

std::string encode_start(const grid::Grid& grid, std::size_t robots, int window_steps) {
  json rows = json::array();
  for (int32_t y = 0; y < grid.height(); ++y) {
    std::string row(static_cast<std::size_t>(grid.width()), '.');
    for (int32_t x = 0; x < grid.width(); ++x) {
      if (!grid.free({x, y})) row[static_cast<std::size_t>(x)] = '@';
    }
    rows.push_back(std::move(row));
  }
  return json{{"type", "start"},
              {"protocol", kPlanProtocol},
              {"map", {{"width", grid.width()}, {"height", grid.height()}, {"rows", rows}}},
              {"robots", robots},
              {"window_steps", window_steps}}
      .dump();
}

ReadyLine decode_ready(std::string_view line) {
  const json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
  const auto type = j.is_object() ? j.find("type") : j.end();
  if (type == j.end() || *type != "ready") {
    return {false,
            {},
            "the first line a planner writes is {\"type\": \"ready\"} once it has read the "
            "start line; it wrote: " +
                std::string(line.substr(0, 200))};
  }
  const auto name = j.find("name");
  return {true, name != j.end() && name->is_string() ? name->get<std::string>() : "", {}};
}

std::string encode_request(uint64_t window, double time_s, double budget_s,
                           const planning::WindowRequest& request) {
  json robots = json::array();
  for (std::size_t r = 0; r < request.start.size(); ++r) {
    json errands = json::array();
    for (const auto c : request.goals[r]) errands.push_back(cell_json(c));
    json robot{{"cell", cell_json(request.start[r])}, {"errands", std::move(errands)}};
    if (r < request.heading.size()) robot["heading"] = grid::to_string(request.heading[r]);
    robots.push_back(std::move(robot));
  }
  return json{{"type", "request"},    {"window", window},       {"time_s", time_s},
              {"budget_s", budget_s}, {"steps", request.steps}, {"robots", std::move(robots)}}
      .dump();
}

PlanReply decode_reply(std::string_view line, uint64_t window, std::size_t robots) {
  const json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return malformed("not JSON (one object per line)");
  if (!j.is_object()) return malformed("not a JSON object");
  const auto w = j.find("window");
  if (w == j.end() || !w->is_number_unsigned()) {
    return malformed("no \"window\" number (the request's window)");
  }
  if (w->get<uint64_t>() < window) return {PlanReply::Kind::kStale, {}, {}};
  if (w->get<uint64_t>() != window) {
    return malformed("\"window\" " + std::to_string(w->get<uint64_t>()) +
                     " was never requested (the request was window " + std::to_string(window) +
                     ")");
  }
  if (const auto e = j.find("error"); e != j.end()) {
    return {PlanReply::Kind::kPlannerError,
            {},
            "the planner could not plan: " + (e->is_string() ? e->get<std::string>() : e->dump())};
  }
  const auto p = j.find("paths");
  if (p == j.end() || !p->is_array()) return malformed("no \"paths\" array (a path per robot)");
  if (p->size() != robots) {
    return malformed(std::to_string(p->size()) + " paths for " + std::to_string(robots) +
                     " robots");
  }
  PlanReply out{PlanReply::Kind::kWindow, std::vector<std::vector<grid::Cell>>(robots), {}};
  for (std::size_t r = 0; r < robots; ++r) {
    std::string why;
    if (!read_path((*p)[r], r, out.paths[r], why)) return malformed(why);
  }
  return out;
}

namespace {

std::string check_path(const grid::Grid& grid, const planning::WindowRequest& request,
                       const std::vector<grid::Cell>& path, std::size_t r) {
  const auto want = static_cast<std::size_t>(request.steps) + 1;
  if (path.size() != want) {
    return "robot " + std::to_string(r) + " has " + std::to_string(path.size()) +
           " cells; a window is " + std::to_string(want) + " (the cut cell and one per step)";
  }
  if (path[0] != request.start[r]) {
    return "robot " + std::to_string(r) + " starts at " + grid::to_string(path[0]) +
           ", not at its cut cell " + grid::to_string(request.start[r]);
  }
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (!grid.inside(path[k])) return robot_step(r, k) + " leaves the map at " + to_string(path[k]);
    if (!grid.free(path[k]))
      return robot_step(r, k) + " enters an obstacle at " + to_string(path[k]);
    if (k > 0 && std::abs(path[k].x - path[k - 1].x) + std::abs(path[k].y - path[k - 1].y) > 1) {
      return robot_step(r, k) + " jumps from " + to_string(path[k - 1]) + " to " +
             to_string(path[k]) + " (one cell a step at most)";
    }
  }
  return {};
}

}  // namespace

std::string check_window(const grid::Grid& grid, const planning::WindowRequest& request,
                         const std::vector<std::vector<grid::Cell>>& paths) {
  if (paths.size() != request.start.size()) {
    return std::to_string(paths.size()) + " paths for " + std::to_string(request.start.size()) +
           " robots";
  }
  for (std::size_t r = 0; r < paths.size(); ++r) {
    if (auto why = check_path(grid, request, paths[r], r); !why.empty()) return why;
  }
  const auto key = [&](grid::Cell c) { return static_cast<uint64_t>(grid.index(c)); };
  std::unordered_map<uint64_t, std::size_t> at;  // cell -> robot at step k
  at.reserve(paths.size() * 2);
  for (std::size_t k = 0; k <= static_cast<std::size_t>(request.steps); ++k) {
    at.clear();
    for (std::size_t r = 0; r < paths.size(); ++r) {
      const auto [it, fresh] = at.emplace(key(paths[r][k]), r);
      if (!fresh) {
        return "robots " + std::to_string(it->second) + " and " + std::to_string(r) +
               " collide at " + to_string(paths[r][k]) + " at step " + std::to_string(k);
      }
    }
    if (k == 0) continue;
    // A swap: robot r goes a -> b while the robot that was on b comes to a.
    for (std::size_t r = 0; r < paths.size(); ++r) {
      const grid::Cell a = paths[r][k - 1], b = paths[r][k];
      if (a == b) continue;
      const auto it = at.find(key(a));
      if (it != at.end() && it->second != r && paths[it->second][k - 1] == b) {
        return "robots " + std::to_string(r) + " and " + std::to_string(it->second) +
               " swap cells " + to_string(a) + " and " + to_string(b) + " at step " +
               std::to_string(k);
      }
    }
  }
  return {};
}

}  // namespace smart::lifelong
