// Watches a run from the test process as any DDS tool would: progress and robot states on the
// run's domain (loopback). Used to act at a point of the run rather than after a fixed sleep.
#pragma once

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <thread>

#include "smart/dds/qos_profile.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/wire.hpp"
#include "support/dds_test_support.hpp"

namespace smart::test {

class FleetWatcher {
 public:
  explicit FleetWatcher(int domain_id, const std::string& run = smart_msg_DEFAULT_RUN)
      : domain_(domain_id, loopback()),
        participant_(domain_, run),
        progress_(participant_, dds::default_qos_profile()),
        states_(participant_, dds::default_qos_profile()) {}

  // Waits until some robot (or `robot`) reports finished_seq >= at_least; returns the highest
  // finished_seq seen (-1: none).
  int64_t wait_for_finished(int64_t at_least, std::chrono::seconds timeout,
                            std::optional<uint32_t> robot = std::nullopt) {
    int64_t most = -1;
    const auto give_up = std::chrono::steady_clock::now() + timeout;
    while (most < at_least && std::chrono::steady_clock::now() < give_up) {
      progress_.take_each([&](const smart_msg_Progress& p) {
        if (!robot || p.robot_id == *robot) most = std::max<int64_t>(most, p.finished_seq);
      });
      take_states();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return most;
  }

  // The last pose published for `robot` so far.
  std::optional<smart_msg_Pose2D> last_pose(uint32_t robot) {
    take_states();
    const auto it = poses_.find(robot);
    return it == poses_.end() ? std::nullopt : std::optional<smart_msg_Pose2D>(it->second);
  }

 private:
  void take_states() {
    states_.take_each([&](const smart_msg_RobotState& s) { poses_[s.robot_id] = s.pose; });
  }
  dds::Domain domain_;
  dds::Participant participant_;
  dds::WireReader<smart_msg_Progress> progress_;
  dds::WireReader<smart_msg_RobotState> states_;
  std::map<uint32_t, smart_msg_Pose2D> poses_;
};

}  // namespace smart::test
