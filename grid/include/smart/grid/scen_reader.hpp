// Contract: parses MovingAI .scen text: "version 1", then one agent per line with 9
// tab-separated fields: bucket, map, width, height, start_x, start_y, goal_x, goal_y, optimal
// (x = column, y = row). Reads the first `max_agents` agents (all when 0); asking for more than
// the file has is an error. check_scen_against_map() reports starts/goals outside the map or
// on obstacles and size mismatches. All problems are reported at once (InputError).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/grid/problem.hpp"

namespace smart::grid {

struct ScenAgent {
  Cell start;
  Cell goal;
  int line = 0;
};

struct Scenario {
  std::string source;
  std::string map_name;
  int32_t map_width = 0;
  int32_t map_height = 0;
  std::vector<ScenAgent> agents;
};

Scenario parse_scen(std::string_view text, const std::string& source, std::size_t max_agents = 0);

std::vector<Problem> check_scen_against_map(const Scenario& scen, const Grid& grid);

}  // namespace smart::grid
