#include "smart/grid/scen_reader.hpp"

#include <array>
#include <map>
#include <optional>

#include "smart/grid/text.hpp"

namespace smart::grid {

namespace {

// One row's width, height, start and goal (the fields after bucket and map), or nullopt with
// each bad field added to `problems`.
std::optional<std::array<int32_t, 6>> scen_row(const std::vector<std::string_view>& fields,
                                               const std::string& source, int ln,
                                               std::vector<Problem>& problems) {
  std::array<int32_t, 6> v{};
  bool ok = true;
  const char* names[6] = {"width", "height", "start_x", "start_y", "goal_x", "goal_y"};
  for (std::size_t k = 0; k < 6; ++k) {
    const auto p = parse_int(fields[k + 2]);
    if (!p || *p < 0 || *p > kMaxGridSide) {
      problems.push_back({source, ln, -1,
                          std::string(names[k]) + " is '" + excerpt(fields[k + 2]) +
                              "'; it must be a whole number from 0 to " +
                              std::to_string(kMaxGridSide)});
      ok = false;
    } else {
      v[k] = static_cast<int32_t>(*p);
    }
  }
  if (!parse_double(fields[8])) {
    problems.push_back(
        {source, ln, -1, "optimal length is '" + excerpt(fields[8]) + "'; it must be a number"});
    ok = false;
  }
  if (!ok) return std::nullopt;
  return v;
}

}  // namespace

Scenario parse_scen(std::string_view text, const std::string& source, std::size_t max_agents) {
  Scenario scen;
  scen.source = source;
  const auto lines = split_lines(text);
  std::vector<Problem> problems;
  if (lines.empty() || !trim(lines[0]).starts_with("version")) {
    problems.push_back(
        {source, 1, -1, "missing 'version 1' header; is this a MovingAI .scen file?"});
    throw InputError(problems);
  }
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (max_agents > 0 && scen.agents.size() >= max_agents) break;
    const auto line = lines[i];
    const int ln = static_cast<int>(i) + 1;
    if (trim(line).empty()) continue;
    auto fields = split(line, '\t');
    if (fields.size() != 9) fields = split_whitespace(line);  // tolerate space separation
    if (fields.size() != 9) {
      problems.push_back({source, ln, -1,
                          "expected 9 tab-separated fields (bucket, map, width, height, start_x, "
                          "start_y, goal_x, goal_y, optimal), found " +
                              std::to_string(fields.size())});
      continue;
    }
    const auto row = scen_row(fields, source, ln, problems);
    if (!row) continue;
    const auto& v = *row;
    if (scen.agents.empty()) {
      scen.map_name = std::string(trim(fields[1]));
      scen.map_width = v[0];
      scen.map_height = v[1];
    } else if (v[0] != scen.map_width || v[1] != scen.map_height) {
      problems.push_back({source, ln, -1,
                          "map size " + std::to_string(v[0]) + "x" + std::to_string(v[1]) +
                              " differs from the " + std::to_string(scen.map_width) + "x" +
                              std::to_string(scen.map_height) +
                              " of the first row; a scenario belongs to one map"});
      continue;
    }
    scen.agents.push_back({{v[2], v[3]}, {v[4], v[5]}, ln});
  }
  if (problems.empty() && max_agents > 0 && scen.agents.size() < max_agents) {
    problems.push_back({source, 0, -1,
                        "asked for " + std::to_string(max_agents) + " agents but the file has " +
                            std::to_string(scen.agents.size()) + "; lower --agents"});
  }
  if (problems.empty() && scen.agents.empty()) {
    problems.push_back({source, 0, -1, "the scenario lists no agents"});
  }
  throw_if_any(problems);
  return scen;
}

std::vector<Problem> check_scen_against_map(const Scenario& scen, const Grid& grid) {
  std::vector<Problem> problems;
  if (scen.map_width != grid.width() || scen.map_height != grid.height()) {
    problems.push_back({scen.source, scen.agents.empty() ? 0 : scen.agents[0].line, -1,
                        "scenario is for a " + std::to_string(scen.map_width) + "x" +
                            std::to_string(scen.map_height) + " map ('" + scen.map_name +
                            "') but the map is " + std::to_string(grid.width()) + "x" +
                            std::to_string(grid.height()) + "; pass the matching --map"});
  }
  std::map<Cell, int> starts, goals;
  for (std::size_t r = 0; r < scen.agents.size(); ++r) {
    const auto& a = scen.agents[r];
    const int robot = static_cast<int>(r);
    for (const auto& [cell, what] : {std::pair{a.start, "start"}, std::pair{a.goal, "goal"}}) {
      if (!grid.inside(cell)) {
        problems.push_back({scen.source, a.line, robot,
                            std::string(what) + " " + to_string(cell) + " is outside the " +
                                std::to_string(grid.width()) + "x" + std::to_string(grid.height()) +
                                " map"});
      } else if (grid.blocked(cell)) {
        problems.push_back({scen.source, a.line, robot,
                            std::string(what) + " " + to_string(cell) + " is an obstacle"});
      }
    }
    if (auto [it, fresh] = starts.emplace(a.start, robot); !fresh) {
      problems.push_back({scen.source, a.line, robot,
                          "start " + to_string(a.start) + " is also robot " +
                              std::to_string(it->second) + "'s start"});
    }
    if (auto [it, fresh] = goals.emplace(a.goal, robot); !fresh) {
      problems.push_back({scen.source, a.line, robot,
                          "goal " + to_string(a.goal) + " is also robot " +
                              std::to_string(it->second) + "'s goal"});
    }
  }
  return problems;
}

}  // namespace smart::grid
