// `smart doctor` on emulated JetBots (a healthy one, one with its left wheel wired backwards,
// one whose I2C bus is missing) and against a running `smart monitor`. Real processes, own domain.
#include <gtest/gtest.h>

#include <fstream>

#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

// The report (last line) and the table of `smart doctor args...`.
nlohmann::json doctor(const std::vector<std::string>& args, int expected_code,
                      const std::string& tag, const char* seconds = "0.5", int domain = kDoctor) {
  std::vector<std::string> all{"doctor", "--domain", std::to_string(domain), "--seconds", seconds};
  all.insert(all.end(), args.begin(), args.end());
  const auto r = run_smart(all, 30s, tag);
  EXPECT_EQ(r.code, expected_code) << r.out;
  return last_json_line(r.out);
}

std::map<std::string, nlohmann::json> by_check(const nlohmann::json& report) {
  std::map<std::string, nlohmann::json> rows;
  for (const auto& r : report["rows"]) rows[r["check"].get<std::string>()] = r;
  return rows;
}

TEST(DoctorCommand, AHealthyEmulatedJetbotPassesEveryRobotCheck) {
  const auto rows = by_check(doctor(
      {"--robot-id", "0", "--i2c", "emulated", "--emulate-pose", "0.5,0.5,0", "--wheels", "--yes"},
      0, "doctor_ok"));
  for (const char* check : {"motor board", "pose stream", "left wheel", "right wheel"}) {
    EXPECT_EQ(rows.at(check)["level"], "OK") << rows.at(check);
  }
  EXPECT_EQ(rows.at("monitor")["level"], "WARN");  // none running
}

TEST(DoctorCommand, ABackwardsWheelAndAMissingBusFailWithTheirFix) {
  auto rows = by_check(doctor({"--robot-id", "0", "--i2c", "emulated", "--emulate-pose",
                               "0.5,0.5,0", "--emulate-wheel-gains", "-1,1", "--wheels", "--yes"},
                              1, "doctor_backwards"));
  EXPECT_EQ(rows.at("left wheel")["level"], "FAIL");
  EXPECT_NE(rows.at("left wheel")["fix"].get<std::string>().find("hardware.left.sign"),
            std::string::npos);
  EXPECT_EQ(rows.at("right wheel")["level"], "OK");
  rows = by_check(doctor({"--robot-id", "0", "--i2c", "/dev/i2c-99"}, 1, "doctor_nobus"));
  EXPECT_EQ(rows.at("open")["level"], "FAIL");
  EXPECT_NE(rows.at("open")["measured"].get<std::string>().find("/dev/i2c-99"), std::string::npos);
}

// Every host on the domain is heard through its robots' states: an emulated JetBot's agent
// (robot 2) shows up with its robot and a clock offset (same machine: within tolerance).
TEST(DoctorCommand, HearsEveryHostOnTheDomainAndItsClockOffset) {
  auto agent = start_smart({"agent", "--robot-id", "2", "--i2c", "emulated", "--emulate-pose",
                            "0.5,0.5,0", "--domain", std::to_string(kDoctorHosts)},
                           "/dev/null");
  const auto report = doctor({}, 0, "doctor_hosts", "2", kDoctorHosts);
  agent.terminate();
  int hosts = 0;
  for (const auto& r : report["rows"]) {
    if (r["check"].get<std::string>().rfind("host ", 0) != 0) continue;
    ++hosts;
    EXPECT_EQ(r["level"], "OK") << r;
    EXPECT_NE(r["measured"].get<std::string>().find("robots 2;"), std::string::npos) << r;
    EXPECT_NE(r["measured"].get<std::string>().find("clock offset + delay"), std::string::npos);
  }
  EXPECT_EQ(hosts, 1) << report;
}

TEST(DoctorCommand, FindsTheMonitorOnTheDomainAndItsQosMatches) {
  const auto map = temp_file("doctor.map"), scen = temp_file("doctor.scen"),
             plan = temp_file("doctor.plan");
  std::ofstream(map) << "type octile\nheight 1\nwidth 3\nmap\n...\n";
  std::ofstream(scen) << "version 1\n0\tm.map\t3\t1\t0\t0\t2\t0\t2\n";
  std::ofstream(plan) << "Agent 0:(0,0)->(1,0)->(2,0)->\n";
  auto monitor = start_smart({"monitor", "--map", map.string(), "--scen", scen.string(), "--plan",
                              plan.string(), "--axis", "xy", "--clock", "realtime", "--domain",
                              std::to_string(kDoctorMonitor), "--timeout-s", "20", "--no-progress"},
                             "/dev/null");
  const auto rows = by_check(doctor({}, 0, "doctor_monitor", "3", kDoctorMonitor));
  monitor.terminate();
  EXPECT_EQ(rows.at("monitor")["level"], "OK") << rows.at("monitor");
  EXPECT_EQ(rows.at("qos")["level"], "OK") << rows.at("qos");
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

}  // namespace
}  // namespace smart::test
