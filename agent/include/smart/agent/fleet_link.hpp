// Contract: the agent side of the SMART topics on one DDS participant, shared by every process
// that hosts agents (sim host: many robots; hardware agent: one). It demultiplexes the keyed
// action topic by robot id, converts wire types to agent types, and publishes progress, robot
// state and clock samples. Edge code: the agent core never sees DDS types.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "smart/agent/types.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/writer.hpp"

namespace smart::agent {

inline constexpr uint32_t kSimClockSource = 0;      // Clock.source_id of the sim host
inline constexpr uint32_t kMonitorClockSource = 1;  // Clock.source_id of the monitor

AgentAction from_wire(const smart_msg_ActionStep& step);

// The RobotState sample of one robot (wire type) from what its agent knows.
smart_msg_RobotState make_robot_state(uint32_t robot, uint64_t run_id, double time_s,
                                      const PoseSample& pose, WheelSpeeds wheels,
                                      std::size_t queue_length);

struct ReceivedWindow {
  uint32_t robot_id = 0;
  uint64_t run_id = 0;
  uint32_t total_actions = 0;
  uint32_t end_seq = 0;  // one past the last seq in the window (first seq if empty)
  std::vector<AgentAction> actions;
};

class FleetLink {
 public:
  FleetLink(const dds::Participant& participant, const dds::QosProfile& qos);

  // Takes every received window; fn is called once per valid sample, in arrival order.
  std::size_t take_windows(const std::function<void(const ReceivedWindow&)>& fn);
  // Takes robot states published by other hosts (mixed runs: hardware robots' poses).
  std::size_t take_states(const std::function<void(const smart_msg_RobotState&)>& fn);
  // Takes clock samples of the monitor; returns the one with the highest tick, if any.
  std::optional<smart_msg_Clock> take_monitor_clock();

  void publish_progress(uint32_t robot, uint64_t run_id, int64_t finished_seq,
                        int64_t executing_seq);
  void publish_state(const smart_msg_RobotState& state);
  void publish_clock(const smart_msg_Clock& clock);
  void publish_sim_status(const smart_msg_SimStatus& status);

  dds_entity_t action_reader() const { return actions_.handle(); }
  dds_entity_t clock_reader() const { return clocks_.handle(); }
  uint32_t monitors_matched() const { return actions_.subscription_matched().current_count; }

 private:
  dds::Topic<smart_msg_ActionWindow> action_topic_;
  dds::Topic<smart_msg_Progress> progress_topic_;
  dds::Topic<smart_msg_RobotState> state_topic_;
  dds::Topic<smart_msg_Clock> clock_topic_;
  dds::Topic<smart_msg_SimStatus> status_topic_;
  dds::Reader<smart_msg_ActionWindow> actions_;
  dds::Reader<smart_msg_Clock> clocks_;
  dds::Reader<smart_msg_RobotState> states_in_;
  dds::Writer<smart_msg_Progress> progress_;
  dds::Writer<smart_msg_RobotState> states_;
  dds::Writer<smart_msg_Clock> clock_out_;
  dds::Writer<smart_msg_SimStatus> status_out_;
};

}  // namespace smart::agent
