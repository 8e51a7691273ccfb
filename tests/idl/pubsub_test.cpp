// In-process publish/subscribe through the typed layer: two participants in one domain.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <thread>

#include "smart/dds/action_window.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/writer.hpp"
#include "support/dds_test_support.hpp"

namespace smart::dds {
namespace {

using namespace std::chrono_literals;

// Takes valid samples until `done` holds or 10 s pass, waiting on a wait set between takes.
template <class T, class Fn, class Done>
bool take_until(const Participant& p, Reader<T>& reader, Fn on_sample, Done done) {
  WaitSet ws(p);
  ws.attach_status(reader.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    ws.wait(100ms);
    reader.take_each(on_sample);
  }
  return true;
}

struct TwoParticipants {
  explicit TwoParticipants(int domain_id)
      : domain(domain_id, test::loopback()), pub(domain), sub(domain) {}
  Domain domain;
  Participant pub;
  Participant sub;
  QosProfile profile = default_qos_profile();
};

TEST(RoundTrip, ActionWindowWithSteps) {
  TwoParticipants f(test::kRoundTripAction);
  Topic<smart_msg_ActionWindow> tp(f.pub, std::string(kActionTopic));
  Topic<smart_msg_ActionWindow> ts(f.sub, std::string(kActionTopic));
  Writer<smart_msg_ActionWindow> w(f.pub, tp, f.profile.action.to_dds());
  Reader<smart_msg_ActionWindow> r(f.sub, ts, f.profile.action.to_dds());
  ActionWindowBuffer buf(3, 77, 10);
  for (uint32_t i = 0; i < 4; ++i) {
    smart_msg_ActionStep s{};
    s.seq = 2 + i;
    s.type = i == 0 ? smart_msg_ACTION_ROTATE : smart_msg_ACTION_MOVE;
    s.from.col2 = 2 * static_cast<int32_t>(i);
    s.to.col2 = 2 * static_cast<int32_t>(i) + 1;
    s.to.x_m = 0.5 * i + 0.25;
    s.heading_rad = 1.5707963267948966;
    s.plan_time_s = 1.0 + i;
    buf.steps().push_back(s);
  }
  w.write(buf.view());
  std::vector<smart_msg_ActionStep> got;
  uint32_t robot = 0, total = 0;
  uint64_t run = 0;
  ASSERT_TRUE(take_until(
      f.sub, r,
      [&](const smart_msg_ActionWindow& m) {
        robot = m.robot_id;
        run = m.run_id;
        total = m.total_actions;
        got = copy_steps(m);
      },
      [&] { return !got.empty(); }));
  EXPECT_EQ(robot, 3u);
  EXPECT_EQ(run, 77u);
  EXPECT_EQ(total, 10u);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[0].type, smart_msg_ACTION_ROTATE);
  EXPECT_EQ(got[3].seq, 5u);
  EXPECT_EQ(got[3].to.col2, 7);
  EXPECT_DOUBLE_EQ(got[3].to.x_m, 1.75);
  EXPECT_DOUBLE_EQ(got[1].heading_rad, 1.5707963267948966);
  EXPECT_DOUBLE_EQ(got[2].plan_time_s, 3.0);
}

TEST(RoundTrip, Progress) {
  TwoParticipants f(test::kRoundTripProgress);
  Topic<smart_msg_Progress> tp(f.pub, std::string(kProgressTopic));
  Topic<smart_msg_Progress> ts(f.sub, std::string(kProgressTopic));
  Writer<smart_msg_Progress> w(f.pub, tp, f.profile.progress.to_dds());
  Reader<smart_msg_Progress> r(f.sub, ts, f.profile.progress.to_dds());
  w.write(smart_msg_Progress{5, 9, 41, 42});
  smart_msg_Progress got{};
  bool have = false;
  ASSERT_TRUE(take_until(
      f.sub, r, [&](const smart_msg_Progress& m) { got = m, have = true; }, [&] { return have; }));
  EXPECT_EQ(got.robot_id, 5u);
  EXPECT_EQ(got.run_id, 9u);
  EXPECT_EQ(got.finished_seq, 41);
  EXPECT_EQ(got.executing_seq, 42);
}

TEST(RoundTrip, RobotState) {
  TwoParticipants f(test::kRoundTripState);
  Topic<smart_msg_RobotState> tp(f.pub, std::string(kStateTopic));
  Topic<smart_msg_RobotState> ts(f.sub, std::string(kStateTopic));
  Writer<smart_msg_RobotState> w(f.pub, tp, f.profile.state.to_dds());
  Reader<smart_msg_RobotState> r(f.sub, ts, f.profile.state.to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, 5s));
  ASSERT_TRUE(r.wait_for_writers(1, 5s));
  smart_msg_RobotState s{};
  s.robot_id = 12;
  s.run_id = 4;
  s.sim_time_s = 3.5;
  s.pose = {1.0, 2.0, -0.5};
  s.linear_mps = 0.3;
  s.angular_radps = 0.1;
  s.wheel_left_mps = 0.29;
  s.wheel_right_mps = 0.31;
  s.queue_length = 6;
  smart_msg_RobotState got{};
  bool have = false;
  // Best effort and volatile: write until one arrives.
  WaitSet ws(f.sub);
  ws.attach_status(r.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  for (int i = 0; i < 100 && !have; ++i) {
    w.write(s);
    ws.wait(50ms);
    r.take_each([&](const smart_msg_RobotState& m) { got = m, have = true; });
  }
  ASSERT_TRUE(have);
  EXPECT_EQ(got.robot_id, 12u);
  EXPECT_DOUBLE_EQ(got.pose.y_m, 2.0);
  EXPECT_DOUBLE_EQ(got.pose.yaw_rad, -0.5);
  EXPECT_DOUBLE_EQ(got.wheel_right_mps, 0.31);
  EXPECT_EQ(got.queue_length, 6u);
}

TEST(RoundTrip, Clock) {
  TwoParticipants f(test::kRoundTripClock);
  Topic<smart_msg_Clock> tp(f.pub, std::string(kClockTopic));
  Topic<smart_msg_Clock> ts(f.sub, std::string(kClockTopic));
  Writer<smart_msg_Clock> w(f.pub, tp, f.profile.clock.to_dds());
  Reader<smart_msg_Clock> r(f.sub, ts, f.profile.clock.to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, 5s));
  w.write(smart_msg_Clock{0, 8, 1234, 123.4, 99, true});
  smart_msg_Clock got{};
  bool have = false;
  ASSERT_TRUE(take_until(
      f.sub, r, [&](const smart_msg_Clock& m) { got = m, have = true; }, [&] { return have; }));
  EXPECT_EQ(got.tick, 1234u);
  EXPECT_DOUBLE_EQ(got.sim_time_s, 123.4);
  EXPECT_EQ(got.sync_total, 99u);
  EXPECT_TRUE(got.stop);
}

TEST(KeyedInstances, AThousandRobotsAreAllDelivered) {
  TwoParticipants f(test::kKeyedThousand);
  Topic<smart_msg_Progress> tp(f.pub, std::string(kProgressTopic));
  Topic<smart_msg_Progress> ts(f.sub, std::string(kProgressTopic));
  Writer<smart_msg_Progress> w(f.pub, tp, f.profile.progress.to_dds());
  Reader<smart_msg_Progress> r(f.sub, ts, f.profile.progress.to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, 5s));
  constexpr uint32_t kRobots = 1000;
  for (uint32_t i = 0; i < kRobots; ++i) {
    // Two updates per robot: keep-last 1 per instance must keep the second.
    w.write(smart_msg_Progress{i, 1, 0, 1});
    w.write(smart_msg_Progress{i, 1, static_cast<int32_t>(i), -1});
  }
  std::vector<int32_t> latest(kRobots, -2);
  std::set<uint32_t> seen;
  ASSERT_TRUE(take_until(
      f.sub, r,
      [&](const smart_msg_Progress& m) {
        seen.insert(m.robot_id);
        latest[m.robot_id] = m.finished_seq;
      },
      [&] {
        return seen.size() == kRobots &&
               std::all_of(latest.begin(), latest.end(), [&](int32_t v) { return v >= 0; }) &&
               latest[kRobots - 1] == static_cast<int32_t>(kRobots - 1);
      }));
  for (uint32_t i = 0; i < kRobots; ++i) ASSERT_EQ(latest[i], static_cast<int32_t>(i)) << i;
}

TEST(Durability, TransientLocalLateJoinerGetsLatestSampleOfEveryRobot) {
  TwoParticipants f(test::kLateJoiner);
  Topic<smart_msg_ActionWindow> tp(f.pub, std::string(kActionTopic));
  Writer<smart_msg_ActionWindow> w(f.pub, tp, f.profile.action.to_dds());
  constexpr uint32_t kRobots = 50;
  for (uint32_t round = 0; round < 3; ++round) {
    for (uint32_t i = 0; i < kRobots; ++i) {
      ActionWindowBuffer b(i, 1, 3);
      smart_msg_ActionStep s{};
      s.seq = round;
      b.steps().push_back(s);
      w.write(b.view());
    }
  }
  // The reader is created only now, after everything was written.
  Topic<smart_msg_ActionWindow> ts(f.sub, std::string(kActionTopic));
  Reader<smart_msg_ActionWindow> r(f.sub, ts, f.profile.action.to_dds());
  std::vector<int> count(kRobots, 0);
  std::vector<uint32_t> seq(kRobots, 99);
  std::size_t robots_seen = 0;
  ASSERT_TRUE(take_until(
      f.sub, r,
      [&](const smart_msg_ActionWindow& m) {
        if (count[m.robot_id]++ == 0) ++robots_seen;
        seq[m.robot_id] = m.actions._buffer[0].seq;
      },
      [&] { return robots_seen == kRobots; }));
  // A marker written now, after the history: the writer delivers in order, so once it is here
  // any older window still owed to a robot would be too (waited for, not slept on).
  ActionWindowBuffer marker(kRobots, 1, 3);
  w.write(marker.view());
  bool marker_seen = false;
  ASSERT_TRUE(take_until(
      f.sub, r,
      [&](const smart_msg_ActionWindow& m) {
        if (m.robot_id == kRobots) {
          marker_seen = true;
        } else {
          ++count[m.robot_id];
        }
      },
      [&] { return marker_seen; }));
  for (uint32_t i = 0; i < kRobots; ++i) {
    EXPECT_EQ(count[i], 1) << "robot " << i << ": keep-last 1 means only the latest window";
    EXPECT_EQ(seq[i], 2u) << "robot " << i;
  }
}

TEST(InstanceState, DisposeIsSeenAsAnInvalidSampleOfThatRobot) {
  TwoParticipants f(test::kDisposeState);
  Topic<smart_msg_Progress> tp(f.pub, std::string(kProgressTopic));
  Topic<smart_msg_Progress> ts(f.sub, std::string(kProgressTopic));
  Writer<smart_msg_Progress> w(f.pub, tp, f.profile.progress.to_dds());
  Reader<smart_msg_Progress> r(f.sub, ts, f.profile.progress.to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, 5s));
  w.write(smart_msg_Progress{21, 1, 3, -1});
  w.dispose(smart_msg_Progress{21, 0, 0, 0});
  bool saw_valid = false, saw_disposed = false;
  WaitSet ws(f.sub);
  ws.attach_status(r.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (!(saw_valid && saw_disposed) && std::chrono::steady_clock::now() < deadline) {
    ws.wait(100ms);
    auto samples = r.take();
    for (auto s : samples) {
      EXPECT_EQ(s.data().robot_id, 21u);  // the key is set even on invalid samples
      if (s.valid()) saw_valid = true;
      if (s.disposed()) saw_disposed = true;
    }
  }
  EXPECT_TRUE(saw_valid);
  EXPECT_TRUE(saw_disposed);
}

TEST(Listener, DataAvailableCallbackRunsAndStopsWithTheReader) {
  TwoParticipants f(test::kListener);
  Topic<smart_msg_Progress> tp(f.pub, std::string(kProgressTopic));
  Topic<smart_msg_Progress> ts(f.sub, std::string(kProgressTopic));
  Writer<smart_msg_Progress> w(f.pub, tp, f.profile.progress.to_dds());
  // A second reader on the same participant, alive throughout, marks a sample's arrival there:
  // once its callback ran for the last sample, a listener left behind by the destroyed reader
  // would have run too (instead of a 200 ms sleep).
  std::atomic<int> marker_calls{0};
  Reader<smart_msg_Progress> marker(f.sub, ts, f.profile.progress.to_dds(),
                                    [&] { ++marker_calls; });
  std::atomic<int> calls{0};
  {
    Reader<smart_msg_Progress> r(f.sub, ts, f.profile.progress.to_dds(), [&] { ++calls; });
    Reader<smart_msg_Progress> moved = std::move(r);
    ASSERT_TRUE(w.wait_for_readers(2, 5s));
    w.write(smart_msg_Progress{1, 1, 0, -1});
    ASSERT_TRUE(wait_until([&] { return calls.load() > 0 && marker_calls.load() > 0; }, 5000ms));
  }
  ASSERT_TRUE(wait_until([&] { return w.publication_matched().current_count == 1; }, 5000ms));
  const int before = calls.load(), marked = marker_calls.load();
  w.write(smart_msg_Progress{1, 1, 1, -1});
  ASSERT_TRUE(wait_until([&] { return marker_calls.load() > marked; }, 5000ms));
  EXPECT_EQ(calls.load(), before);
}

// Regression (an emulated ROS 2 agent aborted at shutdown under ASan): its odometry listener took
// from a reader that was being deleted, dds_take failed, the wrapper threw, and the exception left
// Cyclone's listener thread: std::terminate. A failing callback is now logged and dropped.
TEST(Listener, ACallbackThatThrowsDoesNotAbortTheProcessAndLaterSamplesStillArrive) {
  TwoParticipants f(test::kListenerThrows);
  Topic<smart_msg_Progress> tp(f.pub, std::string(kProgressTopic));
  Topic<smart_msg_Progress> ts(f.sub, std::string(kProgressTopic));
  Writer<smart_msg_Progress> w(f.pub, tp, f.profile.progress.to_dds());
  std::atomic<int> calls{0};
  Reader<smart_msg_Progress> r(f.sub, ts, f.profile.progress.to_dds(), [&] {
    if (++calls == 1) throw Error(DDS_RETCODE_BAD_PARAMETER, "taking from 'rt/robot_1/odom'");
  });
  ASSERT_TRUE(w.wait_for_readers(1, 5s));
  w.write(smart_msg_Progress{1, 1, 0, -1});
  ASSERT_TRUE(wait_until([&] { return calls.load() >= 1; }, 5000ms));
  w.write(smart_msg_Progress{1, 1, 1, -1});
  EXPECT_TRUE(wait_until([&] { return calls.load() >= 2; }, 5000ms));
}

TEST(WaitSetTest, GuardConditionWakesAWaiterAndTimeoutReturnsNothing) {
  Domain d(test::kWaitSet, test::loopback());
  Participant p(d);
  WaitSet ws(p);
  GuardCondition guard(p);
  ws.attach(guard.handle(), 42);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_TRUE(ws.wait(50ms).empty());
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 45ms);
  std::thread t([&] {
    std::this_thread::sleep_for(50ms);
    guard.set(true);
  });
  const auto hit = ws.wait(5000ms);
  t.join();
  ASSERT_EQ(hit.size(), 1u);
  EXPECT_EQ(hit[0], 42);
  EXPECT_TRUE(guard.triggered());
}

TEST(Status, MatchedCountsFollowEndpointLifetimes) {
  TwoParticipants f(test::kMatchedStatus);
  Topic<smart_msg_Clock> tp(f.pub, std::string(kClockTopic));
  Topic<smart_msg_Clock> ts(f.sub, std::string(kClockTopic));
  Writer<smart_msg_Clock> w(f.pub, tp, f.profile.clock.to_dds());
  EXPECT_EQ(w.publication_matched().current_count, 0u);
  {
    Reader<smart_msg_Clock> r(f.sub, ts, f.profile.clock.to_dds());
    ASSERT_TRUE(w.wait_for_readers(1, 5s));
    ASSERT_TRUE(r.wait_for_writers(1, 5s));
    EXPECT_EQ(r.subscription_matched().current_count, 1u);
  }
  EXPECT_TRUE(wait_until([&] { return w.publication_matched().current_count == 0; }, 5000ms));
}

TEST(Status, RequestedDeadlineMissedIsCounted) {
  TwoParticipants f(test::kDeadlineMissed);
  Topic<smart_msg_RobotState> tp(f.pub, std::string(kStateTopic));
  Topic<smart_msg_RobotState> ts(f.sub, std::string(kStateTopic));
  TopicQos q = f.profile.state;
  q.reliability = Reliability::kReliable;
  q.deadline = Millis(50);
  Writer<smart_msg_RobotState> w(f.pub, tp, q.to_dds());
  Reader<smart_msg_RobotState> r(f.sub, ts, q.to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, 5s));
  smart_msg_RobotState s{};
  s.robot_id = 1;
  w.write(s);  // then silence: the reader's 50 ms deadline passes
  EXPECT_TRUE(wait_until([&] { return r.requested_deadline_missed().total_count > 0; }, 3000ms));
  EXPECT_GT(w.offered_deadline_missed().total_count, 0u);
}

TEST(Status, BestEffortWriterDoesNotMatchAReliableReader) {
  TwoParticipants f(test::kIncompatibleQos);
  Topic<smart_msg_Progress> tp(f.pub, std::string(kProgressTopic));
  Topic<smart_msg_Progress> ts(f.sub, std::string(kProgressTopic));
  TopicQos be = f.profile.progress;
  be.reliability = Reliability::kBestEffort;
  Writer<smart_msg_Progress> w(f.pub, tp, be.to_dds());
  Reader<smart_msg_Progress> r(f.sub, ts, f.profile.progress.to_dds());
  EXPECT_TRUE(wait_until([&] { return w.offered_incompatible_qos().total_count > 0; }, 3000ms));
  EXPECT_EQ(w.publication_matched().current_count, 0u);
}

}  // namespace
}  // namespace smart::dds
