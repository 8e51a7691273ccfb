// The checks every received sample passes before it touches a core or a results file.
#include "smart/convert/validate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace smart::wire {
namespace {

using ::testing::HasSubstr;

smart_msg_ActionStep step(uint32_t seq, double x, double y) {
  smart_msg_ActionStep s{};
  s.seq = seq;
  s.type = smart_msg_ACTION_MOVE;
  s.from = {x, y, 0, 0};
  s.to = {x + 0.5, y, 1, 0};
  return s;
}

struct Window {
  std::vector<smart_msg_ActionStep> steps;
  smart_msg_ActionWindow msg{};
  Window(uint32_t robot, uint32_t total, std::vector<smart_msg_ActionStep> s)
      : steps(std::move(s)) {
    msg.robot_id = robot;
    msg.total_actions = total;
    msg.actions._buffer = steps.data();
    msg.actions._length = msg.actions._maximum = static_cast<uint32_t>(steps.size());
  }
};

const Bounds kMap = bounds_of(grid::Grid(4, 3, std::vector<uint8_t>(12, 0)), 1.0);

TEST(Validate, AWellFormedWindowPasses) {
  Window w(1, 5, {step(2, 0, 0), step(3, 0.5, 0)});
  EXPECT_EQ(check_window(w.msg, 4, kMap), "");
  EXPECT_EQ(check_window(Window(1, 0, {}).msg, 4, kMap), "");
}

TEST(Validate, WindowsThatCouldHurtAreRejectedWithTheReason) {
  auto nan = step(0, 0, 0);
  nan.to.x_m = std::nan("");
  EXPECT_THAT(check_window(Window(0, 5, {nan}).msg, 4, kMap),
              HasSubstr("not a finite number: actions[0].to.x_m"));
  auto far = step(0, 0, 0);
  far.to.y_m = 1e300;
  EXPECT_THAT(check_window(Window(0, 5, {far}).msg, 4, kMap), HasSubstr("outside the map"));
  EXPECT_THAT(check_window(Window(0, 5, {far}).msg, 4, std::nullopt), "");  // no map known
  EXPECT_THAT(check_window(Window(7, 5, {step(0, 0, 0)}).msg, 4, kMap),
              HasSubstr("robot 7 is not in this fleet of 4 robots (check --agents"));
  EXPECT_THAT(check_window(Window(0, 5, {step(0, 0, 0), step(2, 0, 0)}).msg, 4, kMap),
              HasSubstr("seqs not consecutive at actions[1]"));
  EXPECT_THAT(check_window(Window(0, 1, {step(1, 0, 0)}).msg, 4, kMap),
              HasSubstr("seq past total_actions"));
  auto odd = step(0, 0, 0);
  odd.type = static_cast<smart_msg_ActionType>(7);
  EXPECT_THAT(check_window(Window(0, 5, {odd}).msg, 4, kMap), HasSubstr("unknown action type"));
}

TEST(Validate, StatesProgressClockAndStatus) {
  smart_msg_RobotState s{};
  s.robot_id = 1;
  s.pose = {1.0, 1.0, 0.0};
  EXPECT_EQ(check_state(s, 4, kMap), "");
  s.linear_mps = std::numeric_limits<double>::infinity();
  EXPECT_THAT(check_state(s, 4, kMap), HasSubstr("linear_mps"));
  s.linear_mps = 0;
  s.pose.x_m = -50;
  EXPECT_THAT(check_state(s, 4, kMap), HasSubstr("outside the map"));
  EXPECT_EQ(check_progress({2, 1, -1, 0}, 4), "");
  EXPECT_THAT(check_progress({4, 1, 0, 0}, 4), HasSubstr("robot 4 is not in this fleet"));
  EXPECT_THAT(check_progress({0, 1, -5, 0}, 4), HasSubstr("below NO_SEQ"));
  EXPECT_EQ(check_clock({0, 1, 3, 0.3, 0, false}), "");
  EXPECT_THAT(check_clock({0, 1, 3, std::nan(""), 0, false}), HasSubstr("sim_time_s"));
  EXPECT_THAT(check_clock({0, 1, 3, -1.0, 0, false}), HasSubstr("negative"));
  smart_msg_SimStatus st{};
  st.first_contact_a = st.first_contact_b = -1;
  EXPECT_EQ(check_status(st, 4), "");
  st.robot_contacts = 1;
  EXPECT_THAT(check_status(st, 4), HasSubstr("without the robots involved"));
  st.first_contact_a = 0;
  st.first_contact_b = 4;
  EXPECT_THAT(check_status(st, 4), HasSubstr("first_contact robot 4"));
  st.first_contact_b = 3;
  EXPECT_EQ(check_status(st, 4), "");
  st.min_gap_m = std::nan("");
  EXPECT_THAT(check_status(st, 4), HasSubstr("min_gap_m"));
}

TEST(Validate, AMonitorsAnnouncementNeedsARunAPidAMonitorsStrengthAndAPrintableHost) {
  smart_msg_MonitorInfo m{};
  m.monitor_id = 7;
  m.run_id = 42;
  m.pid = 1234;
  m.strength = smart_msg_MONITOR_STRENGTH_MIN + 5;
  std::snprintf(m.host, sizeof(m.host), "%s", "lab-pc-1.local");
  EXPECT_EQ(check_monitor_info(m), "");
  m.strength = smart_msg_MONITOR_STRENGTH_RESUME;  // a monitor started with --resume
  EXPECT_EQ(check_monitor_info(m), "");
  auto bad = m;
  bad.run_id = 0;
  EXPECT_THAT(check_monitor_info(bad), HasSubstr("run id 0"));
  bad = m;
  bad.pid = -1;
  EXPECT_THAT(check_monitor_info(bad), HasSubstr("pid -1"));
  bad = m;
  bad.strength = 0;  // a stray program's default strength
  EXPECT_THAT(check_monitor_info(bad), HasSubstr("below MONITOR_STRENGTH_MIN"));
  bad = m;
  std::snprintf(bad.host, sizeof(bad.host), "%s", "pc\x1b]0;owned\x07");  // a terminal escape
  EXPECT_THAT(check_monitor_info(bad), HasSubstr("non-printable byte (27 at 2)"));
}

TEST(Validate, RejectionsAreCountedByTopicAndReasonAndLoggedSparingly) {
  Rejections r;
  int logged = 0;
  for (int i = 0; i < 2000; ++i)
    logged += r.count("state", "not a finite number: pose.x_m") ? 1 : 0;
  logged += r.count("clock", "negative sim_time_s") ? 1 : 0;
  EXPECT_EQ(logged, 5 + 2 + 1);  // first five, the 1000th and 2000th; the clock's first
  EXPECT_EQ(r.total(), 2001u);
  EXPECT_EQ(r.counts().at("state").at("not a finite number: pose.x_m"), 2000u);
  EXPECT_EQ(r.counts().at("clock").size(), 1u);
}

// Issue 25: 400 000 samples with distinct bad robot ids pushed the monitor to 388 MB and
// summary.json to 41.6 MB (one entry per reason text, each holding the id).
TEST(Validate, RejectionsStayBoundedWhateverTheReasonsAndSendersAre) {
  Rejections r;
  for (uint32_t id = 0; id < 100000; ++id) {
    r.count("progress", "robot " + std::to_string(1000 + id) + " is out of range",
            "participant " + std::to_string(id % 40));
  }
  for (int k = 0; k < 100; ++k)
    r.count("state",
            std::string(1, char('a' + k % 26)) + "x" + std::string(size_t(k / 26 + 1), 'y'));
  EXPECT_EQ(r.total(), 100100u);
  ASSERT_EQ(r.counts().at("progress").size(), 1u);
  EXPECT_EQ(r.counts().at("progress").at("robot # is out of range"), 100000u);
  EXPECT_THAT(r.examples().at("progress").at("robot # is out of range"),
              ::testing::ElementsAre("robot 1000 is out of range", "robot 1001 is out of range",
                                     "robot 1002 is out of range"));
  EXPECT_EQ(r.counts().at("state").size(), Rejections::kMaxClasses + 1);
  EXPECT_GT(r.counts().at("state").at("other reasons"), 0u);
  ASSERT_EQ(r.senders().size(), Rejections::kMaxSenders + 1);
  EXPECT_EQ(r.senders().at("participant 0").samples.at("progress"), 2500u);
  EXPECT_EQ(r.senders().at("participant 0").first_reason, "progress: robot 1000 is out of range");
  EXPECT_EQ(r.senders().at("other senders").samples.at("progress"), 100000u - 16u * 2500u);
}

TEST(Validate, AReasonsClassIsItsTextWithEveryNumberAsAHash) {
  EXPECT_EQ(reason_class("robot 4000 is out of range (the run has 20 robots)"),
            "robot # is out of range (the run has # robots)");
  EXPECT_EQ(reason_class("no digits"), "no digits");
  EXPECT_EQ(reason_class("x1.5e3"), "x#.#e#");
}

}  // namespace
}  // namespace smart::wire
