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
  const auto r = run_smart(all, 90s, tag);
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
  for (const char* check :
       {"motor board", "pose stream", "left wheel", "right wheel", "response"}) {
    EXPECT_EQ(rows.at(check)["level"], "OK") << rows.at(check);
  }
  EXPECT_EQ(rows.at("monitor")["level"], "WARN");  // none running
}

// The response row measures what the robot has: an ideal emulated JetBot moves within a few
// control periods; one whose motors answer with a 1 s time constant (first order: they start
// at once, slowly) takes about three times as long to move 5 mm.
TEST(DoctorCommand, TheResponseRowMeasuresTheMotorLag) {
  auto response = [](const std::vector<std::string>& flaws) {
    std::vector<std::string> args{"--robot-id",     "0",         "--i2c",    "emulated",
                                  "--emulate-pose", "0.5,0.5,0", "--wheels", "--yes"};
    args.insert(args.end(), flaws.begin(), flaws.end());
    return by_check(doctor(args, 0, "doctor_response")).at("response");
  };
  auto ms = [](const nlohmann::json& row) {
    return std::stod(row["measured"].get<std::string>().substr(std::string("pose moved ").size()));
  };
  const auto ideal = response({});
  EXPECT_EQ(ideal["level"], "OK") << ideal;
  const auto slow = response({"--emulate-motor-lag-s", "1.0"});
  EXPECT_GT(ms(slow), 2 * ms(ideal)) << slow << ideal;
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
  auto monitor =
      start_smart({"monitor", "--map", map.string(), "--scen", scen.string(), "--plan",
                   plan.string(), "--axis", "xy", "--clock", "realtime", "--domain",
                   std::to_string(kDoctorMonitor), "--timeout-s", "120", "--no-progress"},
                  "/dev/null");
  // Listens until the monitor was announced twice and matched (--wait-s), however slowly the
  // monitor starts on a loaded machine.
  const auto report = doctor({"--wait-s", "60"}, 0, "doctor_monitor", "0.5", kDoctorMonitor);
  monitor.terminate();
  const auto rows = by_check(report);
  EXPECT_EQ(rows.at("monitor")["level"], "OK") << rows.at("monitor");
  // The monitor's host is in the clock table too, through its announcements (one a second).
  int monitor_hosts = 0;
  for (const auto& r : report["rows"]) {
    const auto measured = r["measured"].get<std::string>();
    if (measured.rfind("the monitor;", 0) != 0) continue;
    ++monitor_hosts;
    EXPECT_EQ(r["level"], "OK") << r;
    EXPECT_EQ(measured.find("over 1 samples"), std::string::npos) << "announced again: " << r;
  }
  EXPECT_EQ(monitor_hosts, 1) << report;
  EXPECT_EQ(rows.at("qos")["level"], "OK") << rows.at("qos");
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

}  // namespace
}  // namespace smart::test
