// `smart run --lifelong`: a LoRR 2026 example problem and a generated task stream executed by the
// real monitor and sim processes over DDS (loopback, own domains), with their result files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <set>
#include <sstream>
#include <thread>

#include "smart/monitor/results_format.hpp"
#include "support/mixed_fleet.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"
#include "support/states_compare.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

std::string maze_problem() {
  return (benchmarks_dir() / "lorr-2026" / "maze.domain" / "maze-example_40.json").string();
}

SmartRun lifelong(const std::vector<std::string>& extra, DomainId domain, const std::string& tag) {
  std::vector<std::string> args{"run", "--domain", std::to_string(domain), "--no-progress"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_smart(args, 180s, tag, true);
}

TEST(LifelongRun, ALorrExampleRunsItsDurationWithoutCollisionAndFinishesTasks) {
  const auto out = temp_file("lifelong_lorr");
  const auto r =
      lifelong({"--lifelong", maze_problem(), "--duration-s", "120", "--out", out.string()},
               kLifelongLorr, "lifelong_lorr");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = summary_in(r.out);
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["robots"], 40);
  EXPECT_DOUBLE_EQ(j["sim_time_s"].get<double>(), 120.0);
  const auto& l = j["lifelong"];
  EXPECT_GT(l["tasks_finished"].get<int>(), 0);
  EXPECT_EQ(l["windows_refused"], 0);
  EXPECT_EQ(l["task_pool"], 60);  // numTasksReveal 1.5 x 40 robots
  EXPECT_EQ(l["lorr"]["version"], 2026);
  // Its delayConfig (pDelay 0.0003 per tick, 5..12 ticks, Gaussian) became the agents' delays.
  EXPECT_DOUBLE_EQ(j["uncertainty"]["delay_probability"].get<double>(), 0.0003);
  EXPECT_DOUBLE_EQ(j["uncertainty"]["delay_min_s"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["uncertainty"]["delay_max_s"].get<double>(), 1.2);
  EXPECT_DOUBLE_EQ(j["uncertainty"]["delay_std_ratio"].get<double>(), 0.22);
  EXPECT_GE(l["planner"]["calls"].get<int>(), 100);  // every sim second
  // The files: every finished task's row, every event, a throughput row per planning call.
  const auto tasks = results::parse_tasks_csv(slurp(out / results::kTasksCsv));
  std::size_t finished = 0;
  for (const auto& t : tasks) {
    if (!t.finished_s) continue;
    ++finished;
    ASSERT_TRUE(t.robot && t.assigned_s && t.opened_s);
    EXPECT_LE(t.revealed_s, *t.assigned_s);
    EXPECT_LE(*t.opened_s, *t.finished_s);
    EXPECT_EQ(t.errands_done, t.errands);
  }
  EXPECT_EQ(finished, l["tasks_finished"].get<std::size_t>());
  const auto events = slurp(out / results::kEventsCsv);
  EXPECT_THAT(events, HasSubstr(",revealed,"));
  EXPECT_THAT(events, HasSubstr(",assigned,"));
  EXPECT_THAT(events, HasSubstr(",finished,"));
  EXPECT_THAT(events, HasSubstr(",window,"));
  const auto rows = results::parse_throughput_csv(slurp(out / results::kThroughputCsv));
  EXPECT_EQ(rows.size(), l["planner"]["calls"].get<std::size_t>());
  EXPECT_EQ(rows.back().tasks_finished, finished);
  std::filesystem::remove_all(out);
}

// The first line where two texts differ, both versions; empty when they are equal.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream x(a), y(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(x, la)),
               gb = static_cast<bool>(std::getline(y, lb));
    if (!ga && !gb) return "";
    if (ga != gb || la != lb)
      return "line " + std::to_string(line) + ": '" + la + "' vs '" + lb + "'";
  }
}

// Lock-step lifelong runs are bit-identical for a seed: the planner is charged a fixed sim-time
// budget, never its wall time. (States as far as both runs received them: the pose stream is
// best effort, support/states_compare.hpp.)
TEST(LifelongRun, TheSameSeedGivesTheSameRunInLockStep) {
  std::vector<std::string> files[2];
  for (int k = 0; k < 2; ++k) {
    const auto out = temp_file("lifelong_seed_" + std::to_string(k));
    const auto r = lifelong(
        {"--tasks", "random", "--map", (benchmarks_dir() / "maps" / "random-32-32-20.map").string(),
         "--agents", "25", "--seed", "5", "--duration-s", "40", "--out", out.string()},
        kLifelongSeed, "lifelong_seed");
    ASSERT_EQ(r.code, 0) << r.out;
    for (const auto name : {results::kEventsCsv, results::kTasksCsv, results::kStatesCsv}) {
      files[k].push_back(slurp(out / name));
    }
    std::filesystem::remove_all(out);
  }
  const char* names[] = {"events.csv", "tasks.csv"};
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(first_difference(files[0][f], files[1][f]), "") << names[f] << " differs";
  }
  EXPECT_EQ(compare_state_rows(files[0][2], files[1][2]), "") << "states.csv";
  EXPECT_THAT(files[0][0], HasSubstr(",assigned,"));
}

// The same run under DDS Security, and as `smart monitor --lifelong` beside a separate
// `smart sim --lifelong` (each process loading the problem itself, as on two hosts): the same
// events, tasks and states as the plain `smart run`.
TEST(LifelongRun, ASecureRunAndASplitRunAreThePlainRun) {
  const auto keys = temp_file("ll_keys");
  std::filesystem::remove_all(keys);
  ASSERT_EQ(run_smart({"security", "init", "--out", keys.string()}, 60s, "ll_keys").code, 0);
  const std::vector<std::string> problem{
      "--tasks",
      "random",
      "--map",
      (benchmarks_dir() / "maps" / "random-32-32-20.map").string(),
      "--agents",
      "15",
      "--seed",
      "3",
      "--task-errands",
      "1",
      "--delay-probability",
      "0.02",
      "--delay-max-s",
      "2"};
  const std::vector<std::string> policy{"--duration-s", "60", "--no-progress"};
  const auto domain = std::to_string(kLifelongSecure);
  std::vector<std::string> files[3];
  for (int k = 0; k < 3; ++k) {
    const auto out = temp_file("ll_secure_" + std::to_string(k));
    std::filesystem::remove_all(out);
    std::vector<std::string> args{k == 2 ? "monitor" : "run", "--domain", domain, "--out",
                                  out.string()};
    args.insert(args.end(), problem.begin(), problem.end());
    args.insert(args.end(), policy.begin(), policy.end());
    if (k == 1) args.insert(args.end(), {"--security", keys.string()});
    std::optional<common::ChildProcess> sim;
    if (k == 2) {
      std::vector<std::string> s{"sim", "--domain", domain};
      s.insert(s.end(), problem.begin(), problem.end());
      sim.emplace(start_smart(s, temp_file("ll_split_sim.out")));
    }
    const auto r = run_smart(args, 120s, "ll_secure_" + std::to_string(k), true);
    ASSERT_EQ(r.code, 0) << r.out;
    if (sim) {
      ASSERT_EQ(sim->wait(20s).value_or(-1), 0) << slurp(temp_file("ll_split_sim.out"));
    }
    const auto j = summary_in(r.out);
    EXPECT_EQ(j["collisions"], 0);
    EXPECT_GT(j["lifelong"]["tasks_finished"].get<int>(), 0);
    for (const auto name : {results::kEventsCsv, results::kTasksCsv, results::kStatesCsv}) {
      files[k].push_back(slurp(out / name));
    }
    std::filesystem::remove_all(out);
  }
  const char* names[] = {"events.csv", "tasks.csv"};
  for (int k = 1; k < 3; ++k) {
    const char* how = k == 1 ? " differs under DDS Security" : " differs in the split run";
    for (int f = 0; f < 2; ++f) {
      EXPECT_EQ(first_difference(files[0][f], files[k][f]), "") << names[f] << how;
    }
    EXPECT_EQ(compare_state_rows(files[0][2], files[k][2]), "") << "states.csv" << how;
  }
  std::filesystem::remove_all(keys);
}

// A tiny LoRR 2024 problem on MixedFleet's 6x6 open floor: robots at (2,2), (5,5) and (4,0);
// the first three tasks lie next to them, the rest go round the floor.
std::filesystem::path write_floor_problem(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "floor.map") << "type octile\nheight 6\nwidth 6\nmap\n......\n......\n"
                                      "......\n......\n......\n......\n";
  std::ofstream(dir / "floor.agents") << "3\n14\n35\n4\n";
  const int cells[] = {20, 29, 16, 0, 35, 5, 30, 18, 3, 33, 12, 23};
  std::ofstream tasks(dir / "floor.tasks");
  tasks << "36\n";
  for (int k = 0; k < 36; ++k) tasks << cells[k % 12] << "\n";
  tasks.close();
  std::ofstream(dir / "floor.json")
      << R"({"mapFile": "floor.map", "agentFile": "floor.agents", "teamSize": 3,
             "taskFile": "floor.tasks", "numTasksReveal": 1.0})";
  return dir / "floor.json";
}

// A mixed lifelong run: `smart monitor --lifelong` and `smart sim --lifelong` in real time, and
// robot 2 an emulated JetBot's `smart agent` (support/mixed_fleet.hpp) that takes tasks from the
// stream like the simulated robots.
TEST(LifelongRun, AnEmulatedJetbotTakesTasksBesideSimulatedRobots) {
  const auto dir = temp_file("ll_mixed");
  std::filesystem::remove_all(dir);
  const auto problem = write_floor_problem(dir).string();
  const std::string domain = std::to_string(kLifelongMixed);
  const std::vector<std::string> world{"--lifelong", problem,   "--clock", "realtime", "--cell-m",
                                       "0.4",        "--robot", "jetbot",  "--domain", domain};
  std::vector<std::string> sim_args{"sim", "--external-robots", "2"};
  sim_args.insert(sim_args.end(), world.begin(), world.end());
  const auto sim_out = dir / "sim.out", agent_out = dir / "agent.out";
  auto sim = start_smart(sim_args, sim_out);
  auto agent = start_smart(
      MixedFleet::agent_args(kLifelongMixed, 4 * MixedFleet::kCellM, 5 * MixedFleet::kCellM, 0.0),
      agent_out);
  std::vector<std::string> mon{"monitor",     "--duration-s", "30",    "--no-progress",
                               "--timeout-s", "15",           "--out", (dir / "out").string()};
  mon.insert(mon.end(), world.begin(), world.end());
  const auto r = run_smart(mon, 120s, "ll_mixed_monitor", true);
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_EQ(agent.wait(10s).value_or(-1), 0) << slurp(agent_out);
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0) << slurp(sim_out);
  const auto j = summary_in(r.out);
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["lifelong"]["windows_refused"], 0);
  EXPECT_TRUE(summary_in(slurp(agent_out))["stopped_by_monitor"].get<bool>());
  std::set<uint32_t> finishers;
  for (const auto& t : results::parse_tasks_csv(slurp(dir / "out" / results::kTasksCsv))) {
    if (t.finished_s) finishers.insert(*t.robot);
  }
  EXPECT_TRUE(finishers.count(2)) << "the JetBot finished no task";
  EXPECT_GE(finishers.size(), 2u);
  std::filesystem::remove_all(dir);
}

TEST(LifelongRun, GeneratedStreamsRunWithDelaysInLockStepAndInRealTime) {
  const auto r =
      lifelong({"--tasks", "random", "--map",
                (benchmarks_dir() / "maps" / "warehouse-10-20-10-2-1.map").string(), "--agents",
                "60", "--duration-s", "60", "--task-errands", "1", "--delay-probability", "0.01",
                "--delay-min-s", "0.5", "--delay-max-s", "4"},
               kLifelongRandom, "lifelong_random");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = summary_in(r.out);
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["robots"], 60);
  EXPECT_EQ(j["lifelong"]["windows_refused"], 0);
  EXPECT_GT(j["lifelong"]["tasks_finished"].get<int>(), 0);
  EXPECT_DOUBLE_EQ(j["uncertainty"]["delay_probability"].get<double>(), 0.01);

  // Real time, next on the same domain: the fleet moves on the wall clock while the monitor
  // replans every second.
  const auto rt =
      lifelong({"--lifelong", maze_problem(), "--clock", "realtime", "--duration-s", "5"},
               kLifelongRandom, "lifelong_realtime");
  ASSERT_EQ(rt.code, 0) << rt.out;
  const auto k = summary_in(rt.out);
  EXPECT_TRUE(k["success"].get<bool>());
  EXPECT_EQ(k["clock"], "realtime");
  EXPECT_GE(k["sim_time_s"].get<double>(), 5.0);
  EXPECT_GE(k["lifelong"]["planner"]["calls"].get<int>(), 3);
  EXPECT_GT(k["finished_actions"].get<int>(), 0);
  EXPECT_EQ(k["lifelong"]["windows_refused"], 0);
}

// Issue 28: a planner in another language drives the run through a pipe (the example Python
// planner); a planner that crashes leaves the run going, its windows refused with the reason,
// robots waiting at the cut or the built-in planner standing in (--planner-fallback); a hung
// one in real time never stops the clock. All on one domain, one after the other.
TEST(LifelongRun, APythonPlannerDrivesARunAndABrokenOneNeverStopsIt) {
  const std::vector<std::string> stream{
      "--tasks",        "random",
      "--map",          (benchmarks_dir() / "maps" / "random-32-32-20.map").string(),
      "--agents",       "20",
      "--seed",         "3",
      "--task-errands", "1"};
  auto with = [&](std::vector<std::string> more) {
    more.insert(more.begin(), stream.begin(), stream.end());
    return more;
  };
  const auto python = "python3 " + (std::filesystem::path(SMART_SOURCE_DIR) / "examples" /
                                    "planners" / "greedy_planner.py")
                                       .string();
  const auto out = temp_file("lifelong_pipe");
  auto r = lifelong(with({"--duration-s", "120", "--planner-cmd", python, "--out", out.string()}),
                    kLifelongPipePlanner, "lifelong_pipe");
  ASSERT_EQ(r.code, 0) << r.out;
  auto j = summary_in(r.out);
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["lifelong"]["planner"]["name"], "external");
  EXPECT_EQ(j["lifelong"]["planner"]["heuristic"], "external: greedy_planner.py");
  EXPECT_EQ(j["lifelong"]["windows_refused"], 0);
  EXPECT_GE(j["lifelong"]["planner"]["calls"].get<int>(), 100);
  EXPECT_GT(j["lifelong"]["tasks_finished"].get<int>(), 0);
  std::filesystem::remove_all(out);

  const std::string crashes = R"(read start; echo '{"type": "ready"}'; exit 3)";
  for (const std::string fallback : {"stop", "builtin"}) {
    r = lifelong(with({"--duration-s", "60", "--planner-cmd", crashes, "--planner-fallback",
                       fallback, "--out", out.string()}),
                 kLifelongPipePlanner, "lifelong_pipe_" + fallback);
    ASSERT_EQ(r.code, 0) << r.out;
    j = summary_in(r.out);
    EXPECT_TRUE(j["success"].get<bool>()) << fallback;
    EXPECT_EQ(j["collisions"], 0);
    EXPECT_DOUBLE_EQ(j["sim_time_s"].get<double>(), 60.0);
    const auto& l = j["lifelong"];
    EXPECT_EQ(l["windows_refused"], l["planner"]["calls"]);
    EXPECT_EQ(l["planner"]["fallback"], fallback);
    // Said once in the log, and in events.csv for every window.
    EXPECT_THAT(r.out, HasSubstr("--planner-cmd window 1 refused: the planner closed its output "
                                 "and exited with code 3; no more windows from it"));
    const auto events = slurp(out / results::kEventsCsv);
    EXPECT_THAT(events,
                HasSubstr(",refused,,,,--planner-cmd window 2 refused: the planner closed"));
    if (fallback == "stop") {
      // Nobody moved: no window was ever appended (a task may still finish where its robot
      // stands).
      EXPECT_EQ(l["appended_actions"], 0);
      EXPECT_EQ(j["finished_actions"], 0);
    } else {
      EXPECT_THAT(events,
                  HasSubstr("no more windows from it; the fallback planner's window is used"));
      EXPECT_GT(l["tasks_finished"].get<int>(), 0);
    }
    std::filesystem::remove_all(out);
  }

  // Real time: a planner that reads its requests and never answers. The run keeps the wall
  // clock and ends on time; every window is refused as late.
  const std::string hangs = R"(read start; echo '{"type": "ready"}'; exec sleep 600)";
  r = lifelong(with({"--clock", "realtime", "--duration-s", "3", "--planner-cmd", hangs,
                     "--planner-timeout-s", "0.5"}),
               kLifelongPipePlanner, "lifelong_pipe_hang");
  ASSERT_EQ(r.code, 0) << r.out;
  j = summary_in(r.out);
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_GE(j["sim_time_s"].get<double>(), 3.0);
  EXPECT_GE(j["lifelong"]["windows_refused"].get<int>(), 1);
  EXPECT_THAT(r.out, HasSubstr("late: no reply within 0.5 s (--planner-timeout-s)"));
}

// A LoRR output path string replayed: the robot's (row, col, orientation) after each tick, and
// whether every segment's opening state matched the replay.
struct Replay {
  std::vector<std::array<int, 3>> after;  // per tick
  bool snapshots_match = true;
};
Replay replay(const std::string& path, std::array<int, 3> state) {
  static constexpr int kDRow[4] = {0, 1, 0, -1}, kDCol[4] = {1, 0, -1, 0};
  Replay out;
  std::size_t at = 0;
  while ((at = path.find("[(", at)) != std::string::npos) {
    int t = 0, row = 0, col = 0, ori = 0, counter = 0;
    std::sscanf(path.c_str() + at, "[(%d,%d,%d,%d,%d)", &t, &row, &col, &ori, &counter);
    out.snapshots_match &= static_cast<std::size_t>(t) == out.after.size() &&
                           std::array<int, 3>{row, col, ori} == state && counter == 0;
    const auto open = path.find(":(", at) + 2, close = path.find(")]", at);
    std::istringstream runs(path.substr(open, close - open));
    for (std::string run; std::getline(runs, run, ',');) {
      const char action = run[0];
      for (int k = std::stoi(run.substr(2)); k > 0; --k) {
        if (action == 'F')
          state = {state[0] + kDRow[state[2]], state[1] + kDCol[state[2]], state[2]};
        if (action == 'R') state[2] = (state[2] + 1) % 4;
        if (action == 'C') state[2] = (state[2] + 3) % 4;
        out.after.push_back(state);
      }
    }
    at = close;
  }
  return out;
}

// Issue 28: `--lorr-output` writes the run as the LoRR output JSON; replaying each robot's
// actualPaths from its start stays on the map's free cells, every segment opens with the replayed
// state, and at each event's tick the robot stands on the errand the event says it reached.
TEST(LifelongRun, ALorrOutputReplaysToTheRunsOwnErrands) {
  const auto out = temp_file("lifelong_lorr_output");
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  const auto map = benchmarks_dir() / "maps" / "random-32-32-20.map";
  const auto r =
      lifelong({"--tasks", "random", "--map", map.string(), "--agents", "12", "--seed", "4",
                "--task-errands", "2", "--duration-s", "90", "--delay-probability", "0.005",
                "--delay-max-s", "1.5", "--lorr-output", (out / "lorr.json").string()},
               kLifelongLorrOutput, "lifelong_lorr_output");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto summary = summary_in(r.out);
  const auto j = nlohmann::json::parse(slurp(out / "lorr.json"));
  EXPECT_EQ(j["teamSize"], 12);
  EXPECT_EQ(j["makespan"], 900);
  EXPECT_EQ(j["numTaskFinished"], summary["lifelong"]["tasks_finished"]);
  ASSERT_GT(j["numTaskFinished"].get<int>(), 0);
  std::vector<std::string> rows;  // the map's rows: '.' free
  {
    std::istringstream text(slurp(map));
    bool in_map = false;
    for (std::string line; std::getline(text, line);) {
      if (in_map) rows.push_back(line);
      if (line == "map") in_map = true;
    }
  }
  std::vector<Replay> robots;
  for (std::size_t i = 0; i < 12; ++i) {
    const auto& s = j["start"][i];
    robots.push_back(replay(j["actualPaths"][i], {s[0].get<int>(), s[1].get<int>(), 0}));
    EXPECT_TRUE(robots.back().snapshots_match) << "robot " << i;
    ASSERT_EQ(robots.back().after.size(), 900u) << "robot " << i;
    for (const auto& [row, col, ori] : robots.back().after) {
      ASSERT_EQ(rows.at(static_cast<std::size_t>(row)).at(static_cast<std::size_t>(col)), '.')
          << "robot " << i << " replays onto an obstacle";
    }
  }
  ASSERT_FALSE(j["events"].empty());
  for (const auto& e : j["events"]) {
    const int tick = e[0], robot = e[1], task = e[2], done = e[3];
    const auto& errands = j["tasks"][static_cast<std::size_t>(task)][2];
    ASSERT_EQ(j["tasks"][static_cast<std::size_t>(task)][0], task);
    const auto where =
        robots[static_cast<std::size_t>(robot)].after[static_cast<std::size_t>(tick)];
    const auto at = static_cast<std::size_t>(done - 1) * 2;  // row, col of errand done - 1
    EXPECT_EQ(where[0], errands[at]) << e.dump();
    EXPECT_EQ(where[1], errands[at + 1]) << e.dump();
  }
  std::size_t delays = 0;
  for (const auto& d : j["delayIntervals"]) delays += d.size();
  EXPECT_GT(delays, 0u);
  std::filesystem::remove_all(out);
}

// `smart args...` in the background with its log (stderr) in `out` too.
common::ChildProcess start_logged(const std::vector<std::string>& args,
                                  const std::filesystem::path& out) {
  std::vector<std::string> argv{"/bin/sh", "-c", R"(exec "$0" "$@" 2>&1)", smart_exe().string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return common::ChildProcess(argv, out);
}

// Until `file` holds `text` (true) or `process` has ended (false).
bool wait_for_line(const std::filesystem::path& file, const std::string& text,
                   common::ChildProcess& process) {
  const auto guard = std::chrono::steady_clock::now() + 60s * SMART_SLOWDOWN;
  while (slurp(file).find(text) == std::string::npos) {
    if (!process.running() || std::chrono::steady_clock::now() > guard) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

// Issue 28: the built-in planner as its own process drives a run over DDS (`smart planner`,
// `--planner external`), in the clear and under DDS Security with the planner identity: the same
// events, tasks and states as the in-process planner, bit for bit in lock-step; a second planner
// started for the run is refused and says which planner plans it; the chosen one ends with the
// run.
TEST(LifelongRun, TheBuiltInPlannerDrivesARunOverDdsAsItsOwnProcess) {
  const auto keys = temp_file("ll_dds_keys");
  std::filesystem::remove_all(keys);
  ASSERT_EQ(run_smart({"security", "init", "--out", keys.string()}, 60s, "ll_dds_keys").code, 0);
  const std::vector<std::string> problem{
      "--tasks",        "random",
      "--map",          (benchmarks_dir() / "maps" / "random-32-32-20.map").string(),
      "--agents",       "20",
      "--seed",         "3",
      "--task-errands", "1",
      "--duration-s",   "60"};
  const auto domain = std::to_string(kLifelongDdsPlanner);
  std::vector<std::string> files[3];
  for (int k = 0; k < 3; ++k) {
    const auto out = temp_file("ll_dds_" + std::to_string(k));
    std::filesystem::remove_all(out);
    std::vector<std::string> args{"run",   "--domain",   domain,  "--no-progress",
                                  "--out", out.string(), "--run", "lldds"};
    args.insert(args.end(), problem.begin(), problem.end());
    std::vector<std::string> planner{"planner", "--domain", domain, "--run",
                                     "lldds",   "--seed",   "3"};
    if (k == 2) {
      for (auto* a : {&args, &planner}) a->insert(a->end(), {"--security", keys.string()});
    }
    std::optional<common::ChildProcess> first, second;
    const auto first_log = temp_file("ll_dds_first.out"), second_log = temp_file("ll_dds_2nd.out");
    if (k > 0) {
      args.insert(args.end(), {"--planner", "external"});
      first.emplace(start_logged(planner, first_log));
      ASSERT_TRUE(wait_for_line(first_log, "waits for run 'lldds'", *first)) << slurp(first_log);
      planner.insert(planner.end(), {"--name", "second"});
      second.emplace(start_logged(planner, second_log));  // started later: refused
      ASSERT_TRUE(wait_for_line(second_log, "waits for run 'lldds'", *second)) << slurp(second_log);
    }
    const auto r = run_smart(args, 120s, "ll_dds_" + std::to_string(k), true);
    ASSERT_EQ(r.code, 0) << r.out;
    const auto j = summary_in(r.out);
    EXPECT_EQ(j["collisions"], 0);
    EXPECT_EQ(j["lifelong"]["windows_refused"], 0);
    EXPECT_GT(j["lifelong"]["tasks_finished"].get<int>(), 0);
    if (k > 0) {
      EXPECT_EQ(j["lifelong"]["planner"]["via"], "dds");
      EXPECT_EQ(j["lifelong"]["planner"]["heuristic"], "external: pibt");
      EXPECT_THAT(r.out,
                  HasSubstr("lifelong: planner 'pibt' (pid " + std::to_string(first->pid())));
      EXPECT_EQ(first->wait(30s * SMART_SLOWDOWN).value_or(-1), 0) << slurp(first_log);
      EXPECT_THAT(slurp(first_log), HasSubstr("planner: the run is over after"));
      EXPECT_EQ(second->wait(30s * SMART_SLOWDOWN).value_or(-1), 1) << slurp(second_log);
      EXPECT_THAT(slurp(second_log),
                  HasSubstr("refused: run 'lldds' on domain " + domain +
                            " is planned by planner 'pibt' (pid " + std::to_string(first->pid())));
    } else {
      EXPECT_EQ(j["lifelong"]["planner"]["via"], "process");
    }
    for (const auto name : {results::kEventsCsv, results::kTasksCsv, results::kStatesCsv}) {
      files[k].push_back(slurp(out / name));
    }
    std::filesystem::remove_all(out);
  }
  const char* names[] = {"events.csv", "tasks.csv"};
  for (int k = 1; k < 3; ++k) {
    const char* how = k == 1 ? " differs over DDS" : " differs over DDS Security";
    for (int f = 0; f < 2; ++f) {
      EXPECT_EQ(first_difference(files[0][f], files[k][f]), "") << names[f] << how;
    }
    EXPECT_EQ(compare_state_rows(files[0][2], files[k][2]), "") << "states.csv" << how;
  }
  std::filesystem::remove_all(keys);
}

TEST(LifelongRun, BadFlagsAreRefusedWithTheFix) {
  auto r =
      lifelong({"--lifelong", maze_problem(), "--plan", "p.txt"}, kLifelongBadFlags, "ll_bad1");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("drop --plan and --scen"));
  r = lifelong({"--tasks", "random", "--duration-s", "5"}, kLifelongBadFlags, "ll_bad2");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("--tasks random needs --map MAP and --agents N"));
  const auto resume = run_smart({"monitor", "--lifelong", maze_problem(), "--resume", "--domain",
                                 std::to_string(kLifelongBadFlags)},
                                30s, "ll_bad_resume", true);
  EXPECT_EQ(resume.code, 2);
  EXPECT_THAT(resume.out, HasSubstr("a lifelong run cannot be taken over"));
  r = lifelong({"--duration-s", "5"}, kLifelongBadFlags, "ll_bad3");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("--map, --scen, --plan required"));
  r = lifelong({"--lifelong", maze_problem(), "--planner-cmd", "python3 p.py",
                "--planner-timeout-s", "20", "--timeout-s", "30"},
               kLifelongBadFlags, "ll_bad4");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("give a --timeout-s above twice the planner's timeout"));
  r = lifelong({"--lifelong", maze_problem(), "--planner", "external", "--planner-cmd", "p"},
               kLifelongBadFlags, "ll_bad5");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("--planner external and --planner-cmd: choose one"));
  r = lifelong({"--lifelong", maze_problem(), "--planner", "external", "--planner-wait-s", "0.2",
                "--run", "ll_nobody"},
               kLifelongBadFlags, "ll_bad6");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("no planner announced itself on run 'll_nobody'"));
  EXPECT_THAT(r.out, HasSubstr("start one with `smart planner --domain " +
                               std::to_string(kLifelongBadFlags) + " --run ll_nobody`"));
}

// Regression: a run without --out writes the sim's world files to a scratch folder, removed only
// when the run ended normally; a run that threw (here: no external planner came) left
// /tmp/smart-lifelong-<pid> behind, one per failing run of the suite.
TEST(LifelongRun, AFailedRunWithoutOutLeavesNoScratchFolder) {
  const auto scratch = temp_file("ll_scratch");
  std::filesystem::create_directories(scratch);
  const char* old = std::getenv("TMPDIR");
  const std::string saved = old != nullptr ? old : "";
  setenv("TMPDIR", scratch.c_str(), 1);  // the child's temp_directory_path()
  const auto r = lifelong({"--lifelong", maze_problem(), "--planner", "external",
                           "--planner-wait-s", "0.2", "--run", "ll_scratch"},
                          kLifelongScratch, "ll_scratch_run");
  if (old != nullptr) {
    setenv("TMPDIR", saved.c_str(), 1);
  } else {
    unsetenv("TMPDIR");
  }
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("no planner announced itself"));
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(scratch)) {
    left.push_back(e.path().filename().string());
  }
  EXPECT_TRUE(left.empty()) << left.front();
  std::filesystem::remove_all(scratch);
}

}  // namespace
}  // namespace smart::test
