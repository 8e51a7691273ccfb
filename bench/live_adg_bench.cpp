// Lifelong replanning costs (issue 27 goals: appending a 10-step window for 10 000 robots <= 50
// ms, a commit cut <= 20 ms, on 2 cores): LoRR 2026 examples' robots on their maps and 10 000
// robots on the sortation map, windows
// planned by PIBT (planning/pibt.hpp) from the previous window's cut, as a lifelong run does.
// Run by `smart_lifelong_bench` (make bench); results in docs/performance.md.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>

#include "smart/grid/lorr.hpp"
#include "smart/monitor/live_adg.hpp"
#include "smart/planning/guide_paths.hpp"
#include "smart/planning/pibt.hpp"
#include "smart/planning/task_generator.hpp"
#include "smart/planning/window_lns.hpp"
#include "smart/tools/machine.hpp"

namespace {

using namespace smart;

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("SMART_BENCHMARKS"); env && *env) return env;
  return SMART_BENCHMARKS_DIR;
}

// A LoRR problem with one window appended and its next window planned from the cut: the state a
// lifelong run is in when it appends.
struct Scene {
  grid::LorrProblem problem;
  std::unique_ptr<planning::DistanceCache> dist;
  std::unique_ptr<planning::GoalHeuristic> heuristic;  // as `--heuristic auto` chooses
  std::unique_ptr<planning::Pibt> pibt;
  std::unique_ptr<monitor::LiveAdg> adg;
  monitor::CommitCut cut;
  std::vector<std::vector<grid::Cell>> next;  // the window planned from the cut

  std::vector<std::vector<grid::Cell>> goals() const {
    std::vector<std::vector<grid::Cell>> g(problem.starts.size());
    for (std::size_t r = 0; r < g.size(); ++r) {
      g[r] = problem.tasks[r % problem.tasks.size()].errands;
    }
    return g;
  }
};

// 10 000 robots on the sortation map (500x140) whose tasks share 200 goal cells (stations), as
// warehouse tasks do: a 10 000-robot window without 10 000 distance tables.
grid::LorrProblem sortation_10000() {
  grid::LorrProblem p;
  p.grid = grid::load_task_map(data_dir() / "maps" / "sortation_large.map", nullptr);
  p.starts = planning::random_starts(p.grid, 10000, 5);
  const auto stations = planning::random_starts(p.grid, 200, 6);
  for (uint32_t k = 0; k < stations.size(); ++k) p.tasks.push_back({k, 0, {stations[k]}});
  return p;
}

Scene& scene(const std::string& file) {
  static std::map<std::string, Scene> cache;
  auto it = cache.find(file);
  if (it != cache.end()) return it->second;
  Scene& s = cache[file];
  s.problem = file == "sortation_10000" ? sortation_10000()
                                        : grid::load_lorr_problem(data_dir() / "lorr-2026" / file);
  s.dist = std::make_unique<planning::DistanceCache>(s.problem.grid);
  if (planning::choose_heuristic(planning::HeuristicKind::kAuto, s.problem.grid,
                                 s.problem.starts.size(),
                                 std::size_t{1} << 30) == planning::HeuristicKind::kTables) {
    s.heuristic = std::make_unique<planning::TableHeuristic>(*s.dist);
  } else {
    s.heuristic = std::make_unique<planning::GuidePaths>(s.problem.grid);
  }
  s.pibt = std::make_unique<planning::Pibt>(s.problem.grid, *s.heuristic, 1);
  s.adg =
      std::make_unique<monitor::LiveAdg>(s.problem.grid, s.problem.starts, grid::Heading::kEast);
  const auto w1 = s.pibt->plan({s.problem.starts, s.goals(), 10});
  if (!s.adg->append(w1.paths, 0).empty()) throw std::runtime_error("window 1 refused");
  // Robots are 3 actions into the window when the next cut is made.
  const std::vector<uint32_t> sent(s.problem.starts.size(), 3);
  s.cut = s.adg->commit_cut(sent, 8);
  s.adg->truncate(s.cut);
  s.next = s.pibt->plan({s.cut.cell, s.goals(), 10}).paths;
  // The next window appended: the graph a run makes its next cut on.
  if (!s.adg->append(s.next, 100).empty()) throw std::runtime_error("window 2 refused");
  return s;
}

void BM_CommitCut(benchmark::State& state, const std::string& file) {
  Scene& s = scene(file);
  const std::vector<uint32_t> sent(s.problem.starts.size(), 3);
  for (auto _ : state) benchmark::DoNotOptimize(s.adg->commit_cut(sent, 8));
  state.counters["robots"] = static_cast<double>(s.problem.starts.size());
}

// Each iteration cuts the scene's graph back to `cut` and appends `next` again: the same window
// on the same graph, whose memory is reused as in a long run. Between windows a run dispatches
// and checks thousands of actions, so the caches are emptied first (twice the L3 written over):
// the append is timed cold, the conservative figure.
void BM_AppendWindow(benchmark::State& state, const std::string& file) {
  Scene& s = scene(file);
  std::size_t edges = 0;
  std::vector<uint64_t> evict(std::size_t{64} << 17);  // 64 MiB
  for (auto _ : state) {
    state.PauseTiming();
    s.adg->truncate(s.cut);
    for (auto& x : evict) x += 1;
    benchmark::DoNotOptimize(evict.data());
    state.ResumeTiming();
    monitor::AppendStats st;
    if (!s.adg->append(s.next, 100, &st).empty()) state.SkipWithError("window refused");
    edges = st.type2;
  }
  state.counters["robots"] = static_cast<double>(s.problem.starts.size());
  state.counters["type2"] = static_cast<double>(edges);
}

void BM_PibtWindow(benchmark::State& state, const std::string& file) {
  Scene& s = scene(file);
  for (auto _ : state) benchmark::DoNotOptimize(s.pibt->plan({s.cut.cell, s.goals(), 10}));
  state.counters["robots"] = static_cast<double>(s.problem.starts.size());
  state.counters["heuristic_mb"] = static_cast<double>(s.heuristic->memory_bytes()) / 1048576.0;
  state.SetLabel(s.heuristic->name());
  if (const auto* g = dynamic_cast<const planning::GuidePaths*>(s.heuristic.get())) {
    state.counters["searches"] = static_cast<double>(g->searches());
    state.counters["expanded_per_search"] =
        static_cast<double>(g->expanded()) /
        static_cast<double>(std::max<std::size_t>(1, g->searches()));
  }
}

// One pass of window LNS (planning/window_lns.hpp, `--window-lns-passes 1`) over the PIBT window
// planned from the cut: what the option adds to each planning call. Its distance tables are the
// scene's (warm, as in a run after its first windows).
void BM_WindowLns(benchmark::State& state, const std::string& file) {
  Scene& s = scene(file);
  planning::WindowLns lns(s.problem.grid, *s.dist);
  const planning::WindowRequest request{s.cut.cell, s.goals(), 10};
  planning::WindowPlan window{s.next, 0};
  lns.improve(request, window);  // the tables of goals reached in the window: warm, as in a run
  for (auto _ : state) {
    state.PauseTiming();
    window.paths = s.next;
    state.ResumeTiming();
    lns.improve(request, window);
  }
  const auto& st = lns.stats();
  state.counters["robots"] = static_cast<double>(s.problem.starts.size());
  state.counters["improved_per_window"] =
      static_cast<double>(st.improved) / static_cast<double>(std::max<uint64_t>(1, st.windows));
  state.counters["expanded_per_robot"] =
      static_cast<double>(st.expansions) / static_cast<double>(std::max<uint64_t>(1, st.replanned));
}

#define LIFELONG_BENCH(name, file)                                                            \
  BENCHMARK_CAPTURE(BM_CommitCut, name, std::string(file))->Unit(benchmark::kMillisecond);    \
  BENCHMARK_CAPTURE(BM_AppendWindow, name, std::string(file))->Unit(benchmark::kMillisecond); \
  BENCHMARK_CAPTURE(BM_PibtWindow, name, std::string(file))->Unit(benchmark::kMillisecond)

LIFELONG_BENCH(random_400, "random.domain/random-example_400.json");
LIFELONG_BENCH(warehouse_2500, "warehouse.domain/fulfill-example_2500.json");
LIFELONG_BENCH(sortation_10000, "sortation_10000");
// Window LNS where the goals' distance tables fit (not iron: 10 000 goals of 3.4 M cells).
BENCHMARK_CAPTURE(BM_WindowLns, random_400, std::string("random.domain/random-example_400.json"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WindowLns, warehouse_2500,
                  std::string("warehouse.domain/fulfill-example_2500.json"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_WindowLns, sortation_10000, std::string("sortation_10000"))
    ->Unit(benchmark::kMillisecond);
// 10 000 robots on 1800x1912 cells with 10 000 distinct goals: guide paths (a table per goal
// would take 137 GB).
LIFELONG_BENCH(iron_10000, "iron_harvest.domain/iron-example_10000.json");

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (!std::filesystem::exists(data_dir() / "lorr-2026")) {
    std::fprintf(stderr, "smart_lifelong_bench: no lorr-2026 folder in %s; set SMART_BENCHMARKS\n",
                 data_dir().c_str());
    return 1;
  }
  benchmark::AddCustomContext("machine", smart::tools::machine_description());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
