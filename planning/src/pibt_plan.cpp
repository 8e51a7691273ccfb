#include "smart/planning/pibt_plan.hpp"

#include <string>
#include <utility>
#include <vector>

#include "smart/planning/distance_cache.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "smart/planning/pibt.hpp"

namespace smart::planning {

PlannerResult plan_pibt(const grid::Grid& grid, const grid::Scenario& scen,
                        const PibtPlanOptions& o) {
  PlannerResult out;
  const std::size_t n = scen.agents.size();
  const int64_t max_steps =
      o.max_steps > 0 ? o.max_steps : 50 * (int64_t{grid.width()} + grid.height());
  DistanceCache tables(grid);
  TableHeuristic heuristic(tables);
  Pibt pibt(grid, heuristic, o.seed);
  WindowRequest req;
  req.steps = o.window_steps;
  req.goals.resize(n);
  std::vector<std::vector<grid::Cell>> paths(n);
  for (std::size_t i = 0; i < n; ++i) {
    req.start.push_back(scen.agents[i].start);
    req.goals[i] = {scen.agents[i].goal};
    paths[i].push_back(scen.agents[i].start);
  }
  for (int64_t t = 0;; t += o.window_steps) {
    bool all_home = true;
    for (std::size_t i = 0; i < n; ++i) all_home = all_home && req.start[i] == scen.agents[i].goal;
    if (all_home) break;
    if (t >= max_steps) {
      out.error = "not every robot on its goal after " + std::to_string(t) +
                  " timesteps (PIBT alone is not complete; try another --seed or fewer robots)";
      return out;
    }
    const WindowPlan w = pibt.plan(req);
    for (std::size_t i = 0; i < n; ++i) {
      paths[i].insert(paths[i].end(), w.paths[i].begin() + 1, w.paths[i].end());
      req.start[i] = w.paths[i].back();
    }
  }
  out.plan = plan_from_timesteps(paths, "<built-in planner: pibt>");
  out.solved = true;
  return out;
}

}  // namespace smart::planning
