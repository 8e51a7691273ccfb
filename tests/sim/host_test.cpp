// The sim host against a scripted monitor in the test process (real DDS on loopback).
#include "smart/sim/host.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "smart/dds/action_window.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/dds/writer.hpp"
#include "support/dds_test_support.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::sim {
namespace {

using namespace std::chrono_literals;

agent::RobotModel fast_model() {
  agent::RobotModel m;
  m.name = "fast";
  m.radius_m = 0.2;
  m.mass_kg = 5;
  m.wheel_base_m = 0.3;
  m.max_speed_mps = 1.0;
  m.max_accel_mps2 = 2.0;
  m.max_decel_mps2 = 2.0;
  m.max_turn_rate_radps = 2.0;
  m.max_angular_accel_radps2 = 8.0;
  return m;
}

TEST(SimHost, LockStepWaitsForTheMonitorThenExecutesWindowsAndStops) {
  const auto grid = test::grid_of({"......", "......"});
  dds::Domain domain(test::kSimHostProtocol, test::loopback());
  dds::Participant host_p(domain), mon_p(domain);
  const auto qos = dds::default_qos_profile();
  SimHostOptions opt;
  opt.timeout_s = 20;
  opt.state_rate_hz = 10;
  const auto starts = start_poses(grid, 1.0, {{0, 0}, {0, 1}}, 0.0);
  SimHost host(host_p, qos, grid, fast_model(), starts, opt);
  std::atomic<bool> stop{false};
  SimHostResult result;
  std::thread t([&] { result = host.run(stop); });

  // The monitor side: windows out, clock answers, progress and the ROS view in.
  dds::Topic<geometry_msgs_msg_dds__PoseArray_> tr(mon_p, "rt/smart/poses");
  dds::WireWriter<smart_msg_ActionWindow> windows(mon_p, qos, dds::kMonitorStrengthMin);
  dds::WireWriter<smart_msg_Clock> answers(mon_p, qos, dds::kMonitorStrengthMin);
  dds::WireReader<smart_msg_Clock> ticks(mon_p, qos);
  dds::WireReader<smart_msg_Progress> progress(mon_p, qos);
  dds::Reader<geometry_msgs_msg_dds__PoseArray_> ros(mon_p, tr, qos.state.to_dds());
  const uint64_t run = 42;
  auto latest_tick = [&] {
    int64_t latest = -1;
    ticks.take_each([&](const smart_msg_Clock& c) {
      if (c.source_id == dds::kSimClockSource) latest = std::max<int64_t>(latest, c.tick);
    });
    return latest;
  };
  // Nothing answered yet: the host must stay at tick 0. A waiting host announces its tick again
  // every CLOCK_REANNOUNCE_MS (idl/smart.idl): two announcements of tick 0 and none later show
  // it waited a whole period without stepping (an event, not a guessed sleep).
  int tick0_announcements = 0;
  int64_t highest = -1;
  dds::WaitSet clock_wait(mon_p);
  clock_wait.attach_status(ticks.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  for (const auto until = std::chrono::steady_clock::now() + 20s;
       tick0_announcements < 2 && std::chrono::steady_clock::now() < until;) {
    clock_wait.wait(100ms);
    ticks.take_each([&](const smart_msg_Clock& c) {
      if (c.source_id != dds::kSimClockSource) return;
      highest = std::max<int64_t>(highest, c.tick);
      if (c.tick == 0) ++tick0_announcements;
    });
  }
  ASSERT_GE(tick0_announcements, 2) << "the host never announced (or re-announced) tick 0";
  EXPECT_EQ(highest, 0) << "the host stepped without the monitor's answer";

  // Robot 0: two half-moves east; robot 1: nothing. Then answer tick 0 with the window total.
  dds::ActionWindowBuffer w0(0, run, 2), w1(1, run, 0);
  for (uint32_t s = 0; s < 2; ++s) {
    smart_msg_ActionStep step{};
    step.seq = s;
    step.type = smart_msg_ACTION_MOVE;
    step.from = {0.5 * s, 1.0, static_cast<int32_t>(s), 0};
    step.to = {0.5 * (s + 1), 1.0, static_cast<int32_t>(s + 1), 0};
    w0.steps().push_back(step);
  }
  windows.write(w0.view());
  windows.write(w1.view());
  int64_t finished = -1;
  bool saw_ros = false;
  uint64_t tick = 0;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (finished < 1 && std::chrono::steady_clock::now() < deadline) {
    answers.write(smart_msg_Clock{dds::kMonitorClockSource, run, tick, 0.0, 2, false});
    // Wait for the host's next tick, then collect what it reported.
    for (int i = 0; i < 200; ++i) {
      if (latest_tick() > static_cast<int64_t>(tick)) break;
      std::this_thread::sleep_for(2ms);
    }
    ++tick;
    progress.take_each([&](const smart_msg_Progress& p) {
      EXPECT_EQ(p.run_id, run);
      if (p.robot_id == 0) finished = p.finished_seq;
    });
    ros.take_each([&](const geometry_msgs_msg_dds__PoseArray_& m) {
      EXPECT_EQ(m.poses._length, 2u);
      EXPECT_STREQ(m.header.frame_id, "map");
      saw_ros = true;
    });
  }
  EXPECT_EQ(finished, 1);
  EXPECT_TRUE(saw_ros) << "no rt/smart/poses PoseArray seen";
  answers.write(smart_msg_Clock{dds::kMonitorClockSource, run, tick, 0.0, 2, true});
  t.join();
  EXPECT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(result.stopped_by_monitor);
  EXPECT_GT(result.ticks, 5u);
}

// Regression: a window with NaN coordinates crashed the sim host inside Simbody ("Inertia
// matrix contains a NaN"); one for a robot it does not have was half-applied. Both are now
// dropped at the edge, counted by reason, and the host goes on.
TEST(SimHost, MalformedWindowsAreDroppedNotExecuted) {
  const auto grid = test::grid_of({"......", "......"});
  dds::Domain domain(test::kSimHostBadWindows, test::loopback());
  dds::Participant host_p(domain), mon_p(domain);
  const auto qos = dds::default_qos_profile();
  SimHostOptions opt;
  opt.timeout_s = 20;
  SimHost host(host_p, qos, grid, fast_model(), start_poses(grid, 1.0, {{0, 0}, {0, 1}}, 0.0), opt);
  std::atomic<bool> stop{false};
  SimHostResult result;
  std::thread t([&] { result = host.run(stop); });
  dds::WireWriter<smart_msg_ActionWindow> windows(mon_p, qos, dds::kMonitorStrengthMin);
  dds::WireWriter<smart_msg_Clock> answers(mon_p, qos, dds::kMonitorStrengthMin);
  dds::WireReader<smart_msg_Progress> progress(mon_p, qos);
  ASSERT_TRUE(windows.wait_for_readers(1, 10s));
  const uint64_t run = 7;
  smart_msg_ActionStep nan_step{};
  nan_step.type = smart_msg_ACTION_MOVE;
  nan_step.to = {std::nan(""), 1e300, 1, 0};
  dds::ActionWindowBuffer bad(0, run, 1, {nan_step});
  smart_msg_ActionStep fine{};
  fine.type = smart_msg_ACTION_MOVE;
  fine.to = {0.5, 0.0, 1, 2};
  dds::ActionWindowBuffer stranger(9, run, 1, {fine});
  dds::ActionWindowBuffer idle(1, run, 0);  // a valid (empty) window: the host joins run 7
  windows.write(bad.view());
  windows.write(stranger.view());
  windows.write(idle.view());
  // The host never counted the bad windows, so a total of 0 lets it step.
  for (uint64_t tick = 0; tick < 20; ++tick) {
    answers.write(smart_msg_Clock{dds::kMonitorClockSource, run, tick, 0.0, 0, false});
    std::this_thread::sleep_for(5ms);
  }
  answers.write(smart_msg_Clock{dds::kMonitorClockSource, run, 20, 0.0, 0, true});
  t.join();
  EXPECT_TRUE(result.ok) << result.error;
  EXPECT_GT(result.ticks, 0u);
  ASSERT_EQ(result.rejected_samples.count("action"), 1u);
  const auto& reasons = result.rejected_samples.at("action");
  ASSERT_EQ(reasons.size(), 2u);
  EXPECT_EQ(reasons.begin()->second + std::next(reasons.begin())->second, 2u);
  bool any_progress = false;
  progress.take_each([&](const smart_msg_Progress&) { any_progress = true; });
  EXPECT_FALSE(any_progress) << "a dropped window was executed";
}

}  // namespace
}  // namespace smart::sim
