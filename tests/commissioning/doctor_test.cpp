// The doctor's measuring checks on in-process emulated JetBots (hw/emulated_jetbot.hpp runs the
// real driver against a simulated PCA9685 and streams Vicon UDP to this process) and on an empty
// DDS domain of their own.
#include "smart/commissioning/doctor.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <thread>

#include "smart/agent/robot_model.hpp"
#include "smart/dds/wire.hpp"
#include "support/dds_test_support.hpp"
#include "support/emulated_robot_io.hpp"

namespace smart::commissioning {
namespace {

using ::testing::HasSubstr;

class DoctorChecks : public ::testing::Test {
 protected:
  // An emulated JetBot at (0.5, 0.5) on this host's own Vicon port.
  hw::RobotIo open(std::vector<double> wheel_gains = {}) const {
    return test::open_emulated_jetbot(participant_, std::move(wheel_gains));
  }
  static std::map<std::string, CheckRow> by_check(const std::vector<CheckRow>& rows) {
    std::map<std::string, CheckRow> out;
    for (const auto& r : rows) out[r.check] = r;
    return out;
  }
  static DoctorSettings quick_with_wheels() {
    DoctorSettings s;
    s.listen_s = 0.5;
    s.wheels = true;
    return s;
  }
  DoctorSettings settings_ = quick_with_wheels();
  dds::Domain domain_{test::kCommissioningDoctor, test::loopback()};
  dds::Participant participant_{domain_, "doctor"};
};

TEST_F(DoctorChecks, AHealthyEmulatedJetbotPassesEveryRobotCheck) {
  const auto rows = by_check(robot_checks(settings_, "0", [&] { return open(); }));
  for (const char* check :
       {"motor board", "pose stream", "left wheel", "right wheel", "response"}) {
    ASSERT_TRUE(rows.contains(check)) << check;
    EXPECT_EQ(rows.at(check).level, Level::kOk) << check << ": " << rows.at(check).measured;
  }
}

TEST_F(DoctorChecks, ALeftWheelWiredBackwardsFailsNamingTheSignToFlip) {
  const auto rows = by_check(robot_checks(settings_, "0", [&] { return open({-1.0, 1.0}); }));
  EXPECT_EQ(rows.at("left wheel").level, Level::kFail);
  EXPECT_THAT(rows.at("left wheel").fix, HasSubstr("sign"));
  EXPECT_EQ(rows.at("right wheel").level, Level::kOk);
}

TEST_F(DoctorChecks, NoYesNoWheelsAndARobotThatDoesNotOpenIsOneFailNamingIt) {
  settings_.confirm = [](const std::string& robot) { return robot != "0"; };
  auto rows = by_check(robot_checks(settings_, "0", [&] { return open(); }));
  EXPECT_EQ(rows.at("wheels").level, Level::kWarn);
  EXPECT_FALSE(rows.contains("left wheel"));
  const auto failed = robot_checks(settings_, "1", []() -> hw::RobotIo {
    throw std::invalid_argument("--i2c /dev/i2c-9: no such device");
  });
  ASSERT_EQ(failed.size(), 1u);
  EXPECT_EQ(failed[0].check, "open");
  EXPECT_EQ(failed[0].level, Level::kFail);
  EXPECT_THAT(failed[0].measured, HasSubstr("/dev/i2c-9"));
}

TEST_F(DoctorChecks, AnEmptyDomainHasNoMonitorAndSaysWhereItListened) {
  const auto rows = by_check(
      domain_checks(settings_, dds::default_qos_profile(), participant_, "domain 208, run doctor"));
  ASSERT_TRUE(rows.contains("monitor"));
  EXPECT_EQ(rows.at("monitor").level, Level::kWarn);
  EXPECT_THAT(rows.at("monitor").measured, HasSubstr("domain 208, run doctor"));
  EXPECT_FALSE(rows.contains("qos"));
}

// Started beside a monitor that is not up yet, the doctor listens on (wait_s) until the monitor
// was announced twice and its action writer matched, instead of reporting after a fixed time.
TEST_F(DoctorChecks, WithWaitItListensUntilALateMonitorIsHeardTwiceAndMatched) {
  settings_.listen_s = 0.2;
  settings_.wait_s = 60;
  std::atomic<bool> done{false};
  std::thread monitor([&] {
    std::this_thread::sleep_for(std::chrono::seconds(1));  // comes after listen_s
    dds::WireWriter<smart_msg_MonitorInfo> info(participant_, dds::default_qos_profile(), 0);
    dds::WireWriter<smart_msg_ActionWindow> actions(participant_, dds::default_qos_profile());
    smart_msg_MonitorInfo m{};
    m.monitor_id = 7;
    m.run_id = 1;
    std::snprintf(m.host, sizeof(m.host), "%s", "late-host");
    m.pid = 4242;
    m.strength = smart_msg_MONITOR_STRENGTH_MIN;
    while (!done) {
      info.write(m);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  const auto rows = domain_checks(settings_, dds::default_qos_profile(), participant_, "here");
  done = true;
  monitor.join();
  const auto checks = by_check(rows);
  ASSERT_TRUE(checks.contains("monitor"));
  EXPECT_EQ(checks.at("monitor").level, Level::kOk) << checks.at("monitor").measured;
  EXPECT_THAT(checks.at("monitor").measured, HasSubstr("late-host"));
  ASSERT_TRUE(checks.contains("qos"));
  EXPECT_EQ(checks.at("qos").level, Level::kOk) << checks.at("qos").measured;
  for (const auto& r : rows) {
    if (r.measured.rfind("the monitor;", 0) == 0) {
      EXPECT_THAT(r.measured, ::testing::Not(HasSubstr("over 1 samples"))) << r.measured;
    }
  }
}

}  // namespace
}  // namespace smart::commissioning
