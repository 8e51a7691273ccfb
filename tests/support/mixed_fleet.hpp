// A small mixed run, as on a lab floor but with the emulated JetBot: a 6x6 open map of 0.4 m
// cells; robot 2 drives from (4,0) down to (4,4) (a rotation and 4 moves as 8 half-moves: 9
// actions) while simulated robots 0 and 1 move around it. The `smart sim` host (real time)
// simulates robots 0 and 1 and shows robot 2 at its published pose; robot 2 is a
// `smart agent --backend jetbot --i2c emulated` process whose PCA9685 register writes drive a
// wheel model that streams its pose back as Vicon UDP datagrams.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/smart_process.hpp"

namespace smart::test {

struct MixedFleet {
  static constexpr double kCellM = 0.4;
  std::string map, scen, plan;

  // Writes the map and scenario and plans them with the built-in planner.
  explicit MixedFleet(const std::string& tag)
      : map(temp_file(tag + ".map").string()),
        scen(temp_file(tag + ".scen").string()),
        plan(temp_file(tag + ".plan").string()) {
    std::ofstream(map) << "type octile\nheight 6\nwidth 6\nmap\n......\n......\n......\n"
                          "......\n......\n......\n";
    std::ofstream(scen) << "version 1\n0\tm.map\t6\t6\t2\t2\t3\t0\t3\n"
                           "0\tm.map\t6\t6\t5\t5\t4\t5\t1\n0\tm.map\t6\t6\t4\t0\t4\t4\t4\n";
    using namespace std::chrono_literals;
    const auto r = run_smart({"plan", "--map", map, "--scen", scen, "--out", plan}, 30s, tag);
    EXPECT_EQ(r.code, 0) << r.out;
  }
  ~MixedFleet() {
    for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
  }
  MixedFleet(const MixedFleet&) = delete;
  MixedFleet& operator=(const MixedFleet&) = delete;

  std::vector<std::string> sim_args(int domain) const {
    return {"sim",
            "--map",
            map,
            "--scen",
            scen,
            "--agents",
            "3",
            "--clock",
            "realtime",
            "--cell-m",
            "0.4",
            "--robot",
            "jetbot",
            "--external-robots",
            "2",
            "--domain",
            std::to_string(domain)};
  }
  common::ChildProcess start_sim(int domain) const {
    return start_smart(sim_args(domain), "/dev/null");
  }
  // Robot 2's agent, its emulated JetBot starting at (x, y, yaw).
  static std::vector<std::string> agent_args(int domain, double x, double y, double yaw) {
    return {"agent",
            "--robot-id",
            "2",
            "--backend",
            "jetbot",
            "--config",
            "jetbot",
            "--i2c",
            "emulated",
            "--emulate-pose",
            std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(yaw),
            "--vicon-port",
            "0",
            "--domain",
            std::to_string(domain)};
  }
  static common::ChildProcess start_agent(int domain, double x, double y, double yaw,
                                          const std::filesystem::path& out) {
    return start_smart(agent_args(domain, x, y, yaw), out);
  }
  // Robot 2 at its start cell (4, 0), facing east.
  static std::vector<std::string> agent_at_start_args(int domain) {
    return agent_args(domain, 4 * kCellM, (6 - 1 - 0) * kCellM, 0.0);
  }
  static common::ChildProcess start_agent_at_start(int domain, const std::filesystem::path& out) {
    return start_smart(agent_at_start_args(domain), out);
  }
  std::vector<std::string> monitor_args(int domain) const {
    return {"monitor",
            "--map",
            map,
            "--scen",
            scen,
            "--plan",
            plan,
            "--axis",
            "xy",
            "--clock",
            "realtime",
            "--cell-m",
            "0.4",
            "--robot",
            "jetbot",
            "--domain",
            std::to_string(domain),
            "--no-progress",
            "--timeout-s",
            "15"};
  }
};

}  // namespace smart::test
