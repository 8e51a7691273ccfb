// Tiny hand-made fixtures for monitor tests.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/grid/plan.hpp"
#include "smart/grid/scen_reader.hpp"

namespace smart::test {

// Rows top to bottom, '.' free and '@' blocked.
inline grid::Grid grid_of(const std::vector<std::string>& rows) {
  const auto h = static_cast<int32_t>(rows.size());
  const auto w = static_cast<int32_t>(rows.at(0).size());
  std::vector<uint8_t> cells;
  for (const auto& r : rows) {
    for (char c : r) cells.push_back(c == '@' ? 1 : 0);
  }
  return grid::Grid(w, h, std::move(cells), "fixture");
}

// Untimed paths: robot i's cells at times 0, 1, 2, ...
inline grid::Plan plan_of(const std::vector<std::vector<grid::Cell>>& paths) {
  grid::Plan p;
  p.source = "fixture.txt";
  p.format = grid::PlanFormat::kSmart;
  for (std::size_t r = 0; r < paths.size(); ++r) {
    grid::RobotPath rp{static_cast<int>(r), static_cast<int>(r) + 1, {}};
    for (std::size_t k = 0; k < paths[r].size(); ++k) {
      rp.steps.push_back({paths[r][k], static_cast<double>(k), static_cast<int>(r) + 1});
    }
    p.paths.push_back(rp);
  }
  return p;
}

// A scenario whose starts and goals are the plan's first and last cells.
inline grid::Scenario scen_of(const grid::Plan& plan, const grid::Grid& grid) {
  grid::Scenario s;
  s.source = "fixture.scen";
  s.map_width = grid.width();
  s.map_height = grid.height();
  for (const auto& p : plan.paths) {
    s.agents.push_back({p.steps.front().cell, p.steps.back().cell, p.robot + 2});
  }
  return s;
}

// Tests that read the shared benchmarks fail without them, naming where they looked: CI clones
// the repository beside ../shared (README), and a skip would hide checks that did not run.
inline std::string no_benchmarks(const std::filesystem::path& where) {
  return "no benchmark data at " + where.string() +
         ": clone the repository beside ../shared, or set SMART_BENCHMARKS";
}

inline std::filesystem::path benchmarks_dir() {
  if (const char* env = std::getenv("SMART_BENCHMARKS"); env != nullptr && *env != '\0') {
    return env;
  }
  return SMART_BENCHMARKS_DIR;
}

}  // namespace smart::test
