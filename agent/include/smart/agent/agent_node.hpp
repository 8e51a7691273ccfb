// Contract: the DDS loop of the robots one process hosts (the sim host: every robot of the
// fleet; `smart agent`: one), shared so both speak to the monitor the same way:
// - take_windows() drops windows that fail the wire checks (wire/validate.hpp; counted in
//   rejections(), logged rate-limited), and routes each other received action window (keyed topic,
//   demultiplexed by robot id) to the hosted agent of that robot, when `accept` (if given) agrees;
//   `accept` sees every window, hosted robot or not (the sim host counts them for the lock-step
//   handshake); a window of a robot not hosted here goes to `unhosted`, if given (a sharded sim
//   keeps it for the robot's arrival), else nowhere;
// - publish_progress() publishes a robot's cumulative progress only when it changed, for
//   robots that have a run, where `write_here` (if given) agrees (else the caller took the sample:
//   a sharded sim's robot whose home is another shard), and returns how many actions were newly
//   reported finished; write() sends samples the caller made for robots this node speaks for;
// - publish_state() packs one robot's state, flush_states() sends what was packed (a host with
//   many robots sends a period's states in a few messages: Writer::write_batched); progress is
//   sent before publish_progress() and republish_progress() return; take_monitor_clock() the
//   monitor's newest clock sample (its answers and its stop).
// - Only the run's monitor is heard (idl/smart.idl, "Ownership"): with a run key (the
//   participant is proven, smart/wire/run_proof.hpp) windows and clock answers are taken only
//   from writers proven as the run's monitor, decided as they match and before their first
//   sample (dds/admission.hpp): a stranger's samples never enter the readers, so it can neither
//   seize a window instance nor stop the run (refused samples counted, reason "not a member of
//   this run", with the sender's GUID prefix). Without a key, and in any case: writers weaker
//   than MONITOR_STRENGTH_MIN are dropped (counted, reason "not a monitor's writer"); DDS
//   exclusive ownership delivers the strongest monitor's windows, and clock answers count only
//   from the participant whose windows were taken last (or, before any window, the first
//   monitor heard).
// - The link model (set_link, wire/link.hpp): a received window reaches its agent only at its
//   arrival time, and progress is written only at its arrival time; `now_s` is the caller's
//   clock (the sim host's sim time, an agent's wall time). Windows still count for `accept` on
//   receipt, and publish_progress() counts actions when their progress is written, so the
//   lock-step handshake sees exactly what travelled. Windows of one robot received at the same
//   time share one draw (how many of them a keep-last reader sees depends on timing).
// Edge code: the agent core never sees DDS types (wire/convert.hpp converts).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "smart/agent/agent.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/wire.hpp"
#include "smart/wire/link.hpp"
#include "smart/wire/lockstep.hpp"

namespace smart::agent {

struct WindowInfo {
  uint32_t robot_id = 0;
  uint64_t run_id = 0;
  uint32_t total_actions = 0;
  uint32_t end_seq = 0;  // one past the last seq in the window
  bool empty = true;
};

class AgentNode {
 public:
  // robots: the fleet size when known (0: not known here); bounds: the map's, when known.
  // Windows that fail wire::check_window never reach an agent nor `accept`. speaks_for: the
  // robots whose partitions progress and states are written in (`smart agent`: its robots;
  // idl/smart.idl, "Runs"); empty: the run's partition (a sim host, which speaks for any robot).
  AgentNode(const dds::Participant& participant, const dds::QosProfile& qos, std::size_t robots = 0,
            std::optional<wire::Bounds> bounds = std::nullopt,
            const std::vector<uint32_t>& speaks_for = {});

  // Hosts `agent` (robot agent.robot_id()); the agent must outlive the node. A robot arriving
  // from another host (a sim shard) comes with what its previous host last reported (progress is
  // counted per host: the count continues instead of reporting its actions again).
  void host(Agent& agent, int64_t reported_finished = -1, int64_t reported_executing = -1);
  // The robot leaves this host; returns what was last reported for it (finished, executing).
  std::pair<int64_t, int64_t> unhost(uint32_t robot);
  std::pair<int64_t, int64_t> reported(uint32_t robot) const;

  // Samples the caller made for robots this node speaks for, on the node's own writers (a
  // sharded sim writes what another shard reported for the robots homed here: the monitor hears
  // each robot from one writer).
  void write(const smart_msg_Progress& progress);
  void write(const smart_msg_RobotState& state);

  // Turns the link model on (off by default: everything passes at once).
  void set_link(const wire::LinkModel& link);

  using Accept = std::function<bool(const WindowInfo&)>;
  using Unhosted =
      std::function<void(uint32_t robot, uint64_t run_id, std::vector<AgentAction> actions)>;
  std::size_t take_windows(const Accept& accept = {}, double now_s = 0,
                           const Unhosted& unhosted = {});
  using ProgressFilter = std::function<bool(const smart_msg_Progress&)>;
  uint64_t publish_progress(double now_s = 0, const ProgressFilter& write_here = {});
  // Real time: writes every hosted robot's last reported progress again. Progress is cumulative,
  // so a repeat is harmless, and it reaches a monitor that dropped the first copy (a restarted
  // agent's writer owns its robot's instance only once the dead one's lease ran out).
  void republish_progress();
  void publish_state(uint32_t robot, uint64_t run_id, double time_s, const PoseSample& pose,
                     WheelSpeeds wheels);
  void flush_states();
  std::optional<wire::Tick> take_monitor_clock();

  const wire::Rejections& rejections() const { return rejections_; }
  dds_entity_t action_reader() const { return actions_.handle(); }
  dds_entity_t clock_reader() const { return clocks_.handle(); }

 private:
  struct Hosted {
    Agent* agent = nullptr;
    int64_t reported_finished = -1;
    int64_t reported_executing = -1;
  };
  Hosted* hosted(uint32_t robot);

  bool from_monitor(const char* topic, dds_instance_handle_t from, bool window);
  template <class Reader>
  void count_refused(const char* topic, dds::WriterAdmission& admission, const Reader& reader);
  void deliver_windows(double now_s);
  double window_arrival_s(uint32_t robot, double now_s);
  uint64_t write_progress(double now_s);

  struct Delayed {
    double at_s;
    uint32_t robot;
    uint64_t run_id;
    std::vector<AgentAction> actions;       // a window
    int64_t finished = -1, executing = -1;  // progress
  };

  std::vector<Hosted> hosted_;  // by robot id; agent == nullptr: not hosted here
  std::optional<wire::LinkChannel> to_host_, to_monitor_;
  std::vector<Delayed> windows_in_flight_, progress_in_flight_;  // in arrival order
  std::vector<std::pair<int64_t, int64_t>> queued_;  // per robot: last progress sent on the link
  std::map<uint32_t, std::pair<double, double>> window_draws_;  // robot: receipt time, arrival
  std::optional<dds_guid_t> monitor_;  // participant of the last accepted window
  std::size_t robots_;
  std::optional<wire::Bounds> bounds_;
  wire::Rejections rejections_;
  dds::WriterAdmission from_monitor_windows_, from_monitor_clock_;  // before their readers
  dds::WireReader<smart_msg_ActionWindow> actions_;
  dds::WireReader<smart_msg_Clock> clocks_;
  dds::WireWriter<smart_msg_Progress> progress_;
  dds::WireWriter<smart_msg_RobotState> states_;
};

}  // namespace smart::agent
