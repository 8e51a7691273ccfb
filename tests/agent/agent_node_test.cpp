// AgentNode over real DDS on loopback: a "monitor" participant writes windows and reads
// progress; the node routes windows and reports progress only when it changes.
#include "smart/agent/agent_node.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <thread>

#include "smart/convert/convert.hpp"
#include "smart/dds/action_window.hpp"
#include "smart/dds/domain.hpp"
#include "smart/dds/wire.hpp"
#include "support/dds_test_support.hpp"
#include "support/fake_robot.hpp"
#include "support/robot_models.hpp"

namespace smart::agent {
namespace {

using namespace std::chrono_literals;

template <class Pred>
bool eventually(Pred pred, std::chrono::milliseconds limit = 3000ms) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < until) {
    if (pred()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return pred();
}

smart_msg_ActionStep rotate_step(uint32_t seq, double heading) {
  smart_msg_ActionStep s{};
  s.seq = seq;
  s.type = smart_msg_ACTION_ROTATE;
  s.heading_rad = heading;
  return s;
}

struct Rig {
  dds::Domain domain;
  dds::Participant mon, host;
  dds::QosProfile qos = dds::default_qos_profile();
  dds::WireWriter<smart_msg_ActionWindow> windows{mon, qos, dds::kMonitorStrengthMin};
  dds::WireReader<smart_msg_Progress> progress{mon, qos};
  AgentNode node{host, qos};
  explicit Rig(int domain_id) : domain(domain_id, test::loopback()), mon(domain), host(domain) {}
  void send(uint32_t robot, uint64_t run, std::vector<smart_msg_ActionStep> steps) {
    ASSERT_TRUE(windows.wait_for_readers(1, 3000ms));
    dds::ActionWindowBuffer buf(robot, run, 4, std::move(steps));
    windows.write(buf.view());
  }
};

TEST(AgentNode, RoutesWindowsToHostedRobotsAndShowsEveryWindowToAccept) {
  Rig rig(test::kAgentNodeWindows);
  test::FakeRobot body(0.3);
  Agent a({3, test::footbot_model(), 0.1, 0.5}, body, body);
  rig.node.host(a);
  rig.send(3, 9, {rotate_step(0, 1.0), rotate_step(1, 2.0)});
  rig.send(5, 9, {rotate_step(0, 1.0)});  // not hosted here
  std::vector<WindowInfo> seen;
  ASSERT_TRUE(eventually([&] {
    rig.node.take_windows([&](const WindowInfo& w) {
      seen.push_back(w);
      return true;
    });
    return seen.size() >= 2;
  }));
  EXPECT_EQ(a.run_id(), 9u);
  EXPECT_EQ(a.queue_length(), 2u);
  EXPECT_EQ(seen[0].end_seq, 2u);
  EXPECT_EQ(seen[0].total_actions, 4u);
  EXPECT_FALSE(seen[0].empty);
}

TEST(AgentNode, AWindowRefusedByAcceptNeverReachesTheAgent) {
  Rig rig(test::kAgentNodeAccept);
  test::FakeRobot body(0.3);
  Agent a({0, test::footbot_model(), 0.1, 0.5}, body, body);
  rig.node.host(a);
  rig.send(0, 9, {rotate_step(0, 1.0)});
  std::size_t taken = 0;
  ASSERT_TRUE(eventually([&] {
    taken += rig.node.take_windows([](const WindowInfo&) { return false; });
    return taken > 0;
  }));
  EXPECT_EQ(a.run_id(), 0u);
}

// Robot 3, hosted beside robot 2, finishes after robot 2's unchanged progress was (not)
// published: the writer delivers in order, so once robot 3's sample is here any second sample of
// robot 2 would be too (its own instance: robot 3's cannot replace it). Waits for that event
// where a fixed sleep had stood for "long enough".
TEST(AgentNode, PublishesProgressOnlyWhenItChanges) {
  Rig rig(test::kAgentNodeProgress);
  test::FakeRobot body(0.3), marker_body(0.3);
  Agent a({2, test::footbot_model(), 0.1, 0.5}, body, body);
  Agent marker({3, test::footbot_model(), 0.1, 0.5}, marker_body, marker_body);
  EXPECT_TRUE(a.activate().ok());
  EXPECT_TRUE(marker.activate().ok());
  rig.node.host(a);
  rig.node.host(marker);
  EXPECT_EQ(rig.node.publish_progress(), 0u);  // no run yet: nothing to say
  a.on_window(9, {wire::from_wire(rotate_step(0, 0.0))});
  a.step(0.0);  // already facing 0: the rotation finishes at once
  ASSERT_TRUE(rig.progress.wait_for_writers(1, 3000ms));
  EXPECT_EQ(rig.node.publish_progress(), 1u);
  EXPECT_EQ(rig.node.publish_progress(), 0u);  // unchanged: not published again
  marker.on_window(9, {wire::from_wire(rotate_step(0, 0.0))});
  marker.step(0.0);
  EXPECT_EQ(rig.node.publish_progress(), 1u);  // robot 3 alone
  std::vector<smart_msg_Progress> got;
  bool marker_seen = false;
  ASSERT_TRUE(eventually([&] {
    rig.progress.take_each([&](const smart_msg_Progress& p) {
      if (p.robot_id == 3) {
        marker_seen = true;
      } else {
        got.push_back(p);
      }
    });
    return marker_seen;
  }));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].robot_id, 2u);
  EXPECT_EQ(got[0].run_id, 9u);
  EXPECT_EQ(got[0].finished_seq, 0);
  EXPECT_EQ(got[0].executing_seq, -1);
}

// The link model: a window delayed d reaches its agent d later on the caller's clock (accept
// sees it on receipt); progress delayed d is written, and counted, d later.
TEST(AgentNode, OverAModelledLinkWindowsAndProgressArriveTheDelayLater) {
  Rig rig(test::kAgentNodeLink);
  wire::LinkModel link;
  link.to_host.delay_ms = 500;
  link.to_monitor.delay_ms = 300;
  rig.node.set_link(link);
  test::FakeRobot body(0.3);
  Agent a({1, test::footbot_model(), 0.1, 0.5}, body, body);
  EXPECT_TRUE(a.activate().ok());
  rig.node.host(a);
  rig.send(1, 9, {rotate_step(0, 0.0)});
  std::size_t seen = 0;
  ASSERT_TRUE(eventually([&] {
    rig.node.take_windows([&](const WindowInfo&) { return ++seen > 0; }, 10.0);  // sent at 10 s
    return seen > 0;
  }));
  EXPECT_EQ(a.run_id(), 0u) << "in flight";
  rig.node.take_windows({}, 10.49);
  EXPECT_EQ(a.run_id(), 0u) << "still in flight at 10.49 s";
  rig.node.take_windows({}, 10.5);
  ASSERT_EQ(a.run_id(), 9u) << "arrived at 10.5 s";
  body.freeze_stamp_at(10.5);  // a fresh pose at 10.5 s
  a.step(10.5);                // facing 0 already: done
  ASSERT_TRUE(rig.progress.wait_for_writers(1, 3000ms));
  EXPECT_EQ(rig.node.publish_progress(10.5), 0u) << "progress in flight";
  EXPECT_EQ(rig.node.publish_progress(10.79), 0u);
  EXPECT_EQ(rig.node.publish_progress(10.801), 1u) << "written and counted at 10.8 s";
  std::vector<smart_msg_Progress> got;
  ASSERT_TRUE(eventually([&] {
    rig.progress.take_each([&](const smart_msg_Progress& p) { got.push_back(p); });
    return !got.empty();
  }));
  EXPECT_EQ(got[0].finished_seq, 0);
}

TEST(AgentNode, RepublishRepeatsTheLastReportedProgressForARestartedAgentsSake) {
  Rig rig(test::kAgentNodeRepublish);
  test::FakeRobot body(0.3);
  Agent a({1, test::footbot_model(), 0.1, 0.5}, body, body);
  EXPECT_TRUE(a.activate().ok());
  rig.node.host(a);
  rig.node.republish_progress();  // nothing reported yet: nothing repeated
  a.on_window(9, {wire::from_wire(rotate_step(0, 0.0))});
  a.step(0.0);
  ASSERT_TRUE(rig.progress.wait_for_writers(1, 3000ms));
  EXPECT_EQ(rig.node.publish_progress(), 1u);
  std::vector<smart_msg_Progress> got;
  auto take = [&] {
    rig.progress.take_each([&](const smart_msg_Progress& p) { got.push_back(p); });
    return got.size();
  };
  ASSERT_TRUE(eventually([&] { return take() >= 1; }));  // keep last 1: take it first
  rig.node.republish_progress();
  ASSERT_TRUE(eventually([&] { return take() >= 2; }));
  EXPECT_EQ(got[1].finished_seq, got[0].finished_seq);
  EXPECT_EQ(got[1].run_id, 9u);
}

// Only a monitor's writers are heard (idl/smart.idl, "Ownership"): a stray writer with a
// host's strength cannot hand a robot a window.
TEST(AgentNode, WindowsFromAWriterWeakerThanAMonitorAreDropped) {
  Rig rig(test::kAgentNodeWeakMonitor);
  dds::WireWriter<smart_msg_ActionWindow> stray{rig.mon, rig.qos};  // HOST_STRENGTH
  test::FakeRobot body(0.3);
  Agent a({0, test::footbot_model(), 0.1, 0.5}, body, body);
  rig.node.host(a);
  ASSERT_TRUE(stray.wait_for_readers(1, 3000ms));
  dds::ActionWindowBuffer buf(0, 9, 4, {rotate_step(0, 1.0)});
  stray.write(buf.view());
  ASSERT_TRUE(eventually([&] {
    rig.node.take_windows();
    return rig.node.rejections().total() > 0;
  }));
  EXPECT_EQ(a.run_id(), 0u);
  EXPECT_EQ(rig.node.rejections().counts().at("action").begin()->first,
            "not a monitor's writer (ownership strength below MONITOR_STRENGTH_MIN)");
}

}  // namespace
}  // namespace smart::agent

namespace smart::agent {
namespace {

// Sim shards: a window for a robot the node does not host goes to the caller (who gives it to the
// robot's agent when it arrives); the arriving robot continues its previous host's progress
// count; progress the caller's filter takes is counted but not written (its home shard writes it).
TEST(AgentNode, WindowsOfRobotsNotHostedGoToTheCallerAndFilteredProgressIsNotWritten) {
  Rig rig(test::kAgentNodeShards);
  rig.send(4, 9, {rotate_step(0, 0.0), rotate_step(1, 0.0), rotate_step(2, 1.0)});
  std::optional<std::pair<uint64_t, std::vector<AgentAction>>> kept;
  ASSERT_TRUE(eventually([&] {
    rig.node.take_windows({}, 0, [&](uint32_t robot, uint64_t run, std::vector<AgentAction> w) {
      EXPECT_EQ(robot, 4u);
      kept.emplace(run, std::move(w));
    });
    return kept.has_value();
  }));
  EXPECT_EQ(kept->first, 9u);
  ASSERT_EQ(kept->second.size(), 3u);
  test::FakeRobot body(0.3);
  Agent a({4, test::footbot_model(), 0.1, 0.5}, body, body);
  EXPECT_TRUE(a.activate().ok());
  a.on_window(9, {wire::from_wire(rotate_step(0, 0.0))});
  a.step(0.0);  // seq 0 finished where it was (another host reported it)
  rig.node.host(a, 0, -1);
  a.on_window(kept->first, kept->second);
  EXPECT_EQ(a.queue_length(), 2u) << "the kept window reached the agent";
  EXPECT_EQ(rig.node.reported(4), (std::pair<int64_t, int64_t>{0, -1}));
  a.step(0.1);  // seq 1: already facing 0
  ASSERT_TRUE(rig.progress.wait_for_writers(1, 3000ms));
  std::vector<smart_msg_Progress> taken;
  EXPECT_EQ(rig.node.publish_progress(0,
                                      [&](const smart_msg_Progress& p) {
                                        taken.push_back(p);
                                        return p.robot_id != 4;
                                      }),
            1u)
      << "one action beyond what was reported before";
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0].finished_seq, 1);
  // One writer delivers in order: once a sentinel written after publish_progress() is in, a
  // sample the node had written for robot 4 would be in too.
  rig.node.write(wire::progress(5, 9, 0, -1));
  std::vector<uint32_t> written;
  ASSERT_TRUE(eventually([&] {
    rig.progress.take_each([&](const smart_msg_Progress& p) { written.push_back(p.robot_id); });
    return !written.empty() && written.back() == 5;
  }));
  EXPECT_EQ(written, std::vector<uint32_t>{5}) << "the filtered sample was written by the node";
  EXPECT_EQ(rig.node.unhost(4), (std::pair<int64_t, int64_t>{1, 2}));
  EXPECT_EQ(rig.node.reported(4), (std::pair<int64_t, int64_t>{-1, -1}));
}

}  // namespace
}  // namespace smart::agent
