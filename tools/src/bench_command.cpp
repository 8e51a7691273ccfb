// `smart bench sim`: sim speed of World + agents with every robot driving a random walk of grid
// moves (collisions allowed and counted). Prints one JSON line. No DDS: this measures the
// simulator and the agents, the part that scales with the fleet.
// `smart bench run`: end to end, `smart run` (monitor + sim processes over loopback DDS) on the
// first N robots of a plan for each N given; one JSON line per run, then a Markdown table.
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "smart/agent/agent.hpp"
#include "smart/common/child_process.hpp"
#include "smart/convert/convert.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/action_builder.hpp"
#include "smart/planning/random_walks.hpp"
#include "smart/sim/fleet.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/machine.hpp"

namespace smart::tools {

namespace {

struct BenchSimOptions {
  std::string map, robot = "footbot";
  std::size_t robots = 100;
  double sim_seconds = 30;
  double cell_m = 1.0;
  uint64_t seed = 1;
  int system_capacity = 0, threads = 0;
};

int run_bench_sim(const BenchSimOptions& o) {
  const auto grid = grid::parse_map(grid::read_text_file(o.map, "map"), o.map);
  const auto model = agent::load_robot_model(find_config_file("robots", o.robot));
  planning::RandomWalks walks;
  try {
    walks = planning::generate_random_walks(grid, o.robots,
                                            static_cast<std::size_t>(o.sim_seconds) + 10, o.seed);
  } catch (const std::invalid_argument& e) {
    std::cerr << "bench sim: " << e.what() << " of " << o.map
              << "; use fewer --robots or a larger map\n";
    return kExitBadInput;
  }
  const auto& plan = walks.plan;
  const auto actions = monitor::build_actions(plan, grid::Heading::kEast);
  sim::SimConfig cfg;
  cfg.cell_m = o.cell_m;
  cfg.system_capacity = o.system_capacity;
  cfg.threads = o.threads;
  sim::Fleet fleet(grid, model, cfg, sim::start_poses(grid, o.cell_m, walks.starts, 0.0));
  for (uint32_t r = 0; r < o.robots; ++r) {
    // Through the wire conversion, exactly what a sim host's agents would receive.
    std::vector<agent::AgentAction> w;
    for (uint32_t s = 0; s < actions.count(r); ++s) {
      w.push_back(wire::from_wire(wire::to_wire(actions.at(r, s), grid, o.cell_m)));
    }
    fleet.agent(r).on_window(1, w);
  }
  const auto ticks = static_cast<uint64_t>(std::llround(o.sim_seconds / cfg.control_period_s));
  const auto t0 = std::chrono::steady_clock::now();
  for (uint64_t k = 0; k < ticks; ++k) fleet.step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::size_t finished = 0;
  for (uint32_t r = 0; r < o.robots; ++r) {
    finished += static_cast<std::size_t>(fleet.agent(r).finished_seq() + 1);
  }
  const auto& world = fleet.world();
  const auto stats = fleet.stats();
  std::cout << nlohmann::json{{"map", o.map},
                              {"robots", o.robots},
                              {"sim_seconds", world.time_s()},
                              {"wall_seconds", wall},
                              {"sim_speed", world.time_s() / wall},
                              {"finished_actions", finished},
                              {"collisions", world.contacts().robot_robot_events},
                              {"wall_contacts", world.contacts().robot_wall_events},
                              {"system_capacity", world.system_capacity()},
                              {"mean_awake_robots", stats.mean_awake_robots},
                              {"mean_active_systems", stats.mean_active_systems},
                              {"threads", world.threads()},
                              {"machine", machine_description()}}
                   .dump()
            << std::endl;
  return 0;
}

struct BenchRunOptions {
  std::string map, scen, plan, axis, robot = "footbot", clock = "lockstep", out = "build/bench-run";
  std::vector<std::size_t> agents{10, 100, 500, 1000};
  std::vector<std::string> qos{"lan"};
  int domain = 90;
};

// The rows as the Markdown table of docs/performance.md.
void print_table(const std::vector<nlohmann::json>& rows) {
  std::cout
      << "\n| robots | qos | success | sim time | wall time | sim speed | vs first qos | CPU s per "
         "sim s | AET | collisions | closest approach | monitor RSS | sim RSS | ADG build | first "
         "report |\n"
         "|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const auto num = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : 0.0; };
  for (const auto& r : rows) {
    char line[400];
    std::snprintf(
        line, sizeof line,
        "| %zu | %s | %s | %.0f s | %.1f s | %.1fx | %.2f | %.2f | %.0f s | %d | %.2f m | "
        "%.0f MB | %.0f MB | %.0f ms | %.1f s |",
        r["robots"].get<std::size_t>(), r["qos"].get<std::string>().c_str(),
        r["success"].get<bool>() ? "yes" : "no", num(r["sim_time_s"]), num(r["wall_time_s"]),
        num(r["sim_speed"]), num(r["speed_vs_first_qos"]), num(r["cpu_s_per_sim_s"]),
        num(r["aet_s"]), r["collisions"].get<int>(), num(r["min_separation_m"]),
        num(r["monitor_peak_rss_mb"]), num(r["sim_peak_rss_mb"]), num(r["adg_build_ms"]),
        num(r["first_report_wall_s"]));
    std::cout << line << "\n";
  }
  std::cout << "\nmachine: " << machine_description() << std::endl;
}

// One `smart run` of the first n robots over `qos`: its row, or nullopt (said on stderr).
std::optional<nlohmann::json> bench_one_run(const BenchRunOptions& o, std::size_t n,
                                            const std::string& qos) {
  const auto dir = std::filesystem::path(o.out) /
                   (o.qos.size() > 1 ? std::to_string(n) + "-" + qos : std::to_string(n));
  std::vector<std::string> argv{common::self_executable().string(),
                                "run",
                                "--map",
                                o.map,
                                "--scen",
                                o.scen,
                                "--plan",
                                o.plan,
                                "--agents",
                                std::to_string(n),
                                "--robot",
                                o.robot,
                                "--clock",
                                o.clock,
                                "--qos",
                                qos,
                                "--domain",
                                std::to_string(o.domain),
                                "--out",
                                dir.string(),
                                "--no-progress"};
  if (!o.axis.empty()) argv.insert(argv.end(), {"--axis", o.axis});
  common::ChildProcess run(argv, "/dev/null");
  const int rc = run.wait(std::chrono::hours(4)).value_or(124);
  std::ifstream in(dir / "summary.json");
  if (rc != 0 || !in) {
    std::cerr << "bench run: `smart run` with " << n << " robots over --qos " << qos
              << " failed (exit code " << rc << "); see " << (dir / "summary.json").string()
              << " or rerun that command by hand\n";
    return std::nullopt;
  }
  const auto s = nlohmann::json::parse(in);
  return nlohmann::json{{"robots", n},
                        {"qos", qos},
                        {"success", s["success"]},
                        {"sim_time_s", s["sim_time_s"]},
                        {"wall_time_s", s["wall_time_s"]},
                        {"sim_speed", s["sim_speed"]},
                        {"aet_s", s["aet_s"]},
                        {"collisions", s["collisions"]},
                        {"wall_contacts", s["wall_contacts"]},
                        {"min_separation_m", s["min_separation_m"]},
                        {"monitor_peak_rss_mb", s["peak_rss_mb"]["monitor"]},
                        {"sim_peak_rss_mb", s["peak_rss_mb"]["sim"]},
                        {"cpu_s_per_sim_s", s["cpu_s_per_sim_s"]},
                        {"adg_build_ms", s["build_time_ms"]["adg_total"]},
                        {"first_report_wall_s", s["first_report_wall_s"]},
                        {"machine", machine_description()}};
}

// Each fleet size over each --qos profile; speed_vs_first_qos is a run's sim speed over the
// first profile's at that size (issue 26: a modelled link must keep lock-step's wall speed).
int run_bench_run(const BenchRunOptions& o) {
  std::vector<nlohmann::json> rows;
  for (const auto n : o.agents) {
    double first_speed = 0;
    for (const auto& qos : o.qos) {
      auto row = bench_one_run(o, n, qos);
      if (!row) return kExitRunFailed;
      const double speed = (*row)["sim_speed"].is_number() ? (*row)["sim_speed"].get<double>() : 0;
      if (first_speed == 0) first_speed = speed;
      (*row)["speed_vs_first_qos"] = first_speed > 0 ? speed / first_speed : 0.0;
      std::cout << row->dump() << std::endl;
      rows.push_back(*row);
    }
  }
  print_table(rows);
  return kExitSuccess;
}

}  // namespace

void register_bench_command(CLI::App& app, int& exit_code) {
  auto* bench = app.add_subcommand("bench", "Benchmarks (results belong in docs/performance.md)");
  bench->require_subcommand(1);
  auto o = std::make_shared<BenchSimOptions>();
  auto* sim = bench->add_subcommand(
      "sim", "Sim speed of the Simbody world + agents, every robot on a random walk");
  sim->add_option("--map", o->map, "MovingAI .map file")->required();
  sim->add_option("--robots,--agents", o->robots, "robots in the simulated fleet")
      ->check(CLI::Range(1ul, 100000ul))
      ->capture_default_str();
  sim->add_option("--sim-seconds", o->sim_seconds, "sim seconds to simulate")
      ->check(finite_in(0.1, 1e6))
      ->capture_default_str();
  sim->add_option("--robot", o->robot, "robot model name or YAML file")->capture_default_str();
  sim->add_option("--cell-m", o->cell_m, "grid cell size in metres")
      ->check(finite_in(0.05, 100.0))
      ->capture_default_str();
  sim->add_option("--seed", o->seed, "seed of the robots' random walks")->capture_default_str();
  sim->add_option("--system-capacity", o->system_capacity,
                  "robot bodies per Simbody system (0: automatic)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  sim->add_option("--threads", o->threads, "sim threads (0: automatic)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  sim->callback([&exit_code, o] { exit_code = run_bench_sim(*o); });

  auto r = std::make_shared<BenchRunOptions>();
  auto* run = bench->add_subcommand(
      "run", "End-to-end speed and memory of `smart run` for several fleet sizes");
  run->add_option("--map", r->map, "MovingAI .map file")->required();
  run->add_option("--scen", r->scen, "MovingAI .scen file")->required();
  run->add_option("--plan", r->plan, "plan file")->required();
  run->add_option("--axis", r->axis, "xy or rowcol (SMART path files)")
      ->check(CLI::IsMember({"xy", "rowcol"}));
  run->add_option("--agents,--robots", r->agents, "fleet sizes: first N robots of the plan")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("--qos", r->qos,
                  "QoS profiles to compare at each size, the first the reference (e.g. "
                  "lan,sim-lossy-wifi)")
      ->delimiter(',')
      ->capture_default_str();
  run->add_option("--robot", r->robot, "robot model name or YAML file")->capture_default_str();
  run->add_option("--clock", r->clock, "lockstep or realtime")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->capture_default_str();
  run->add_option("--domain", r->domain, "DDS domain id")
      ->check(CLI::Range(0, 230))
      ->capture_default_str();
  run->add_option("--out", r->out, "folder for each run's results (one subfolder per size)")
      ->capture_default_str();
  run->callback([&exit_code, r] { exit_code = run_bench_run(*r); });
}

}  // namespace smart::tools
