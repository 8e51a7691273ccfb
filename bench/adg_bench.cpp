// ADG build time and memory (issue: "Plans in, ADG out"). Target: 2000 robots with makespan
// ~500 in under 1 s on one core. Plans: SMART's 500/1000-robot warehouse plans and seeded
// random-walk plans (planning/random_plan.hpp) of 100..2000 robots, 500 timesteps, on the
// warehouse (161x63) and sortation (500x140) maps from ../shared/benchmarks.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/execution_tracker.hpp"
#include "smart/monitor/plan_reader.hpp"
#include "smart/monitor/plan_validator.hpp"
#include "smart/monitor/switchable_tracker.hpp"
#include "smart/planning/random_plan.hpp"
#include "smart/tools/machine.hpp"

namespace {

using namespace smart::monitor;
using smart::planning::generate_random_plan;

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("SMART_BENCHMARKS"); env && *env) return env;
  return SMART_BENCHMARKS_DIR;
}

const Grid& map(const std::string& name) {
  static std::map<std::string, Grid> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    const auto path = data_dir() / "maps" / (name + ".map");
    it = cache.emplace(name, parse_map(read_text_file(path, "map"), path.string())).first;
  }
  return it->second;
}

const Plan& random_plan(const std::string& map_name, std::size_t robots) {
  static std::map<std::pair<std::string, std::size_t>, Plan> cache;
  auto key = std::make_pair(map_name, robots);
  auto it = cache.find(key);
  if (it == cache.end()) {
    it = cache.emplace(key, generate_random_plan(map(map_name), {robots, 500, 42, 0.8, 0.1}).plan)
             .first;
  }
  return it->second;
}

const Plan& smart_plan(const std::string& file) {
  static std::map<std::string, Plan> cache;
  auto it = cache.find(file);
  if (it == cache.end()) {
    const auto path = data_dir() / "smart-examples" / file;
    it = cache
             .emplace(file, parse_plan(read_text_file(path, "plan"), path.string(),
                                       {PlanFormat::kAuto, AxisOrder::kRowCol}))
             .first;
  }
  return it->second;
}

std::size_t adg_bytes(const ActionPlan& ap, const Adg& adg) {
  return ap.actions.capacity() * sizeof(Action) +
         (adg.out.capacity() + adg.in.capacity() + adg.out_begin.capacity() +
          adg.in_begin.capacity()) *
             sizeof(uint32_t);
}

// Actions + ADG + acyclicity check: everything between a validated plan and the first dispatch.
void build_all(benchmark::State& state, const Plan& plan, const Grid& grid) {
  std::size_t nodes = 0, type2 = 0, bytes = 0;
  for (auto _ : state) {
    auto actions = build_actions(plan);
    std::vector<Problem> problems;
    auto adg = build_adg(actions, grid, plan.source, problems);
    auto cycle = check_acyclic(adg, actions, plan.source);
    if (!problems.empty() || !cycle.empty()) state.SkipWithError("invalid plan");
    nodes = adg.stats.nodes;
    type2 = adg.stats.type2;
    bytes = adg_bytes(actions, adg);
    benchmark::DoNotOptimize(adg);
  }
  state.counters["robots"] = static_cast<double>(plan.paths.size());
  state.counters["makespan"] = plan_stats(plan).makespan;
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["type2"] = static_cast<double>(type2);
  state.counters["adg_MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["nodes_per_s"] =
      benchmark::Counter(static_cast<double>(nodes), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["peak_rss_MB"] = smart::tools::peak_rss_mb();
}

void BM_AdgRandomWalk(benchmark::State& state, const std::string& map_name) {
  const auto robots = static_cast<std::size_t>(state.range(0));
  build_all(state, random_plan(map_name, robots), map(map_name));
}

void BM_AdgSmartPlan(benchmark::State& state, const std::string& file) {
  build_all(state, smart_plan(file), map("warehouse-10-20-10-2-1"));
}

void BM_ValidatePlan(benchmark::State& state, const std::string& file) {
  const auto& plan = smart_plan(file);
  const auto& grid = map("warehouse-10-20-10-2-1");
  for (auto _ : state) benchmark::DoNotOptimize(validate_plan(plan, grid));
  state.counters["robots"] = static_cast<double>(plan.paths.size());
}

void BM_ParsePlan(benchmark::State& state, const std::string& file) {
  const auto path = data_dir() / "smart-examples" / file;
  const auto text = read_text_file(path, "plan");
  for (auto _ : state) {
    benchmark::DoNotOptimize(parse_plan(text, file, {PlanFormat::kAuto, AxisOrder::kRowCol}));
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

// A whole run's dispatch decisions (issue 29: switching must stay cheap): every robot reports
// one finished action per round unless delayed (a seeded tenth of robots and rounds), until the
// plan is done; plain ADG (ExecutionTracker) against switchable passing orders (and
// switchable-opt). The monitor's
// own CPU for the same run is in docs/performance.md; the difference of the two is what
// switching costs.
template <class Tracker, class Make>
void execute(benchmark::State& state, const Make& make) {
  const auto& plan = smart_plan("scen_1_1000_paths.txt");
  const auto actions = build_actions(plan);
  std::vector<Problem> problems;
  const auto adg = build_adg(actions, map("warehouse-10-20-10-2-1"), plan.source, problems);
  std::size_t reports = 0, switches = 0, compared = 0, widened = 0;
  for (auto _ : state) {
    Tracker t = make(actions, adg);
    reports = 0;
    for (uint64_t round = 0; !t.complete(); ++round) {
      for (uint32_t r = 0; r < actions.robots(); ++r) {
        const uint64_t draw = uint64_t{r} * 2654435761u + round * 40503u;  // a seeded tenth
        if (t.enqueued(r) == t.finished(r) || draw % 10 == 0) continue;
        t.on_progress(r, t.finished(r), static_cast<double>(round));
        ++reports;
      }
    }
    if constexpr (std::is_same_v<Tracker, SwitchableTracker>) {
      switches = t.switches()->size();
      compared = t.lookahead_comparisons();
      widened = t.lookahead_widened();
    }
  }
  state.counters["robots"] = static_cast<double>(actions.robots());
  state.counters["reports"] = static_cast<double>(reports);
  state.counters["switches"] = static_cast<double>(switches);
  state.counters["lookahead_comparisons"] = static_cast<double>(compared);
  state.counters["lookahead_widened"] = static_cast<double>(widened);
  state.counters["ns_per_report"] = benchmark::Counter(
      static_cast<double>(reports),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ExecutePlainAdg(benchmark::State& state) {
  execute<ExecutionTracker>(
      state, [](const ActionPlan& a, const Adg& g) { return ExecutionTracker(a, g); });
}

void BM_ExecuteSwitchable(benchmark::State& state) {
  execute<SwitchableTracker>(state, [](const ActionPlan& a, const Adg& g) {
    return SwitchableTracker(a, passing_orders(a, map("warehouse-10-20-10-2-1"), g.footprint));
  });
}

// switchable-opt: also anticipation, by expected times (the rounds are its seconds).
void BM_ExecuteSwitchableOpt(benchmark::State& state) {
  execute<SwitchableTracker>(state, [](const ActionPlan& a, const Adg& g) {
    return SwitchableTracker(a, passing_orders(a, map("warehouse-10-20-10-2-1"), g.footprint),
                             SwitchOptions{.anticipate = true});
  });
}

// switchable-lookahead: anticipation comparing orders by every affected action's expected times.
void BM_ExecuteSwitchableLookahead(benchmark::State& state) {
  execute<SwitchableTracker>(state, [](const ActionPlan& a, const Adg& g) {
    return SwitchableTracker(
        a, passing_orders(a, map("warehouse-10-20-10-2-1"), g.footprint),
        SwitchOptions{.anticipate = true, .lookahead_actions = kDefaultLookaheadActions});
  });
}

BENCHMARK(BM_ExecutePlainAdg)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExecuteSwitchable)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExecuteSwitchableOpt)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExecuteSwitchableLookahead)->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_AdgRandomWalk, warehouse, std::string("warehouse-10-20-10-2-1"))
    ->Arg(100)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AdgRandomWalk, sortation, std::string("sortation_large"))
    ->Arg(100)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AdgSmartPlan, scen_1_500, std::string("scen_1_paths.txt"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AdgSmartPlan, scen_1_1000, std::string("scen_1_1000_paths.txt"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ValidatePlan, scen_1_1000, std::string("scen_1_1000_paths.txt"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ParsePlan, scen_1_1000, std::string("scen_1_1000_paths.txt"))
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (!std::filesystem::exists(data_dir() / "maps")) {
    std::fprintf(stderr,
                 "smart_bench: benchmark data not found at %s; set SMART_BENCHMARKS to the "
                 "shared/benchmarks folder\n",
                 data_dir().c_str());
    return 1;
  }
  benchmark::AddCustomContext("machine", smart::tools::machine_description());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
