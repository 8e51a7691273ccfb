// The lifelong problem every process of a run loads alike (`smart run`, `smart monitor`,
// `smart sim`): a LoRR problem, or seeded random starts and tasks on a map.
#include <fstream>
#include <stdexcept>

#include "run_support.hpp"
#include "smart/agent/uncertainty.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/task_generator.hpp"

namespace smart::tools {

namespace {

LifelongProblem lorr_problem(const SimCliOptions& o) {
  const auto& file = o.source.problem;
  auto lp = grid::load_lorr_problem(file);
  LifelongProblem p{absolute_path(file),
                    std::move(lp.grid),
                    std::move(lp.starts),
                    std::move(lp.tasks),
                    0,
                    lp.spec};
  if (o.world.agents > 0) {
    if (o.world.agents > p.starts.size()) {
      throw std::invalid_argument("--agents " + std::to_string(o.world.agents) + ": " + file +
                                  " has only " + std::to_string(p.starts.size()) + " robots");
    }
    p.starts.resize(o.world.agents);
  }
  p.pool = std::max<std::size_t>(
      1, static_cast<std::size_t>(lp.spec.num_tasks_reveal * static_cast<double>(p.starts.size())));
  return p;
}

LifelongProblem random_problem(const SimCliOptions& o, uint64_t seed) {
  const auto& w = o.world;
  if (w.map.empty() || w.agents == 0) {
    throw std::invalid_argument(
        "--tasks random needs --map MAP and --agents N (the robots get random distinct starts)");
  }
  grid::MapMarks marks;
  LifelongProblem p;
  p.source = absolute_path(w.map);
  p.grid = grid::load_task_map(w.map, &marks);
  p.starts = planning::random_starts(p.grid, w.agents, seed);
  p.tasks = planning::generate_tasks(p.grid, marks, std::max<std::size_t>(1000, 10 * w.agents),
                                     o.source.errands, seed);
  p.pool = w.agents;
  return p;
}

}  // namespace

LifelongProblem load_lifelong_problem(const SimCliOptions& o) {
  if (!o.source.problem.empty() && !o.source.tasks.empty()) {
    throw std::invalid_argument("--lifelong PROBLEM.json and --tasks random exclude each other");
  }
  if (!o.world.scen.empty()) {
    throw std::invalid_argument(
        "a lifelong run plans as it goes: drop --scen (starts come from the problem's agents "
        "file, or are drawn at random with --tasks random)");
  }
  return o.source.problem.empty() ? random_problem(o, o.seed.value_or(1)) : lorr_problem(o);
}

// A LoRR 2026 delayConfig as the agents' delay events (ticks x 0.1 s), unless flags set them.
void apply_lorr_delays(const LifelongProblem& p, SimCliOptions& o) {
  if (!p.spec || !p.spec->delay.present) return;
  if (o.delay_probability || o.delay_rate_hz || o.delay_min_s || o.delay_max_s) return;
  const auto& d = p.spec->delay;
  const double tick_s = agent::kDelayTickS;
  if (d.event_model == "poisson") {
    o.delay_rate_hz = d.p_delay / tick_s;  // pDelay: expected events per tick
  } else {
    o.delay_probability = d.p_delay;
  }
  o.delay_min_s = d.min_delay_ticks * tick_s;
  o.delay_max_s = d.max_delay_ticks * tick_s;
  if (d.duration_model == "gaussian") {
    o.delay_mean_ratio = d.gauss_mean_ratio;
    o.delay_std_ratio = d.gauss_std_ratio;
  }
}

void write_world(const LifelongProblem& p, const std::filesystem::path& dir, WorldCliOptions& w) {
  std::filesystem::create_directories(dir);
  const auto map = dir / results::kLifelongMap, scen = dir / "lifelong.scen";
  std::ofstream(map) << planning::to_movingai_map(p.grid);
  std::ofstream out(scen);
  out << "version 1\n";
  for (const auto c : p.starts) {
    out << "0\tlifelong.map\t" << p.grid.width() << '\t' << p.grid.height() << '\t' << c.x << '\t'
        << c.y << '\t' << c.x << '\t' << c.y << "\t0\n";
  }
  if (!out) throw std::runtime_error(scen.string() + ": cannot be written; check the folder");
  w.map = map.string();
  w.scen = scen.string();
  w.agents = p.starts.size();
}

}  // namespace smart::tools
