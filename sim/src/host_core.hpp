// Internal to the sim host: what its pumps share (host.cpp: the lock-step and real-time loops of
// a whole fleet; sharded_host.cpp: one shard of a sharded sim). The fleet and its agents behind
// one AgentNode, the clock and status writers, external robots' states, the run id and the
// windows received, the pacer, the result. It knows no mode: a pump says which robots it steps
// (host_robots) and which it speaks for (the `home` filter of publish_states, the progress filter
// of step).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "smart/agent/agent_node.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/wire.hpp"
#include "smart/sim/fleet.hpp"
#include "smart/sim/host.hpp"
#include "smart/sim/pacer.hpp"
#include "smart/wire/lockstep.hpp"

namespace smart::sim::detail {

// One way a sim host runs (SimHost::run), chosen once at construction.
class HostLoop {
 public:
  virtual ~HostLoop() = default;
  virtual SimHostResult run(const std::atomic<bool>& stop_requested) = 0;
};

struct HostCore {
  using RobotFilter = std::function<bool(uint32_t robot)>;  // empty: every robot
  using SteadyClock = std::chrono::steady_clock;

  HostCore(const dds::Participant& participant, const dds::QosProfile& qos, const grid::Grid& grid,
           const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
           const SimHostOptions& options);

  // The node drives the agents of the robots `steps` agrees on (never external ones).
  void host_robots(const RobotFilter& steps);
  // Windows of every robot count for the handshake, hosted here or not; those of robots not
  // hosted go to `unhosted`.
  void read_windows(const agent::AgentNode::Unhosted& unhosted = {});
  // A stop ends only the run this host executes (any answer that is not a stop passes).
  bool stop_of_this_run(const wire::Tick& answer) const;
  void track_external_robots();
  // One control period; the changed progress goes out where `write_here` agrees.
  void step(const agent::AgentNode::ProgressFilter& write_here = {});
  bool states_due() const { return state_every > 0 && tick % state_every == 0; }
  // States of the robots `steps` agrees on: written for those `home` agrees on, the others
  // appended to `away` (when given) for their home to write.
  void publish_states(const RobotFilter& steps = {}, const RobotFilter& home = {},
                      std::vector<smart_msg_RobotState>* away = nullptr);
  void publish_clock(uint64_t finished_total_announced);
  // The fleet's status, written when it changed (or `force`); rss_mb is asked only then.
  void publish_status(const ContactStats& c, const std::function<double()>& rss_mb, bool force);
  void write_status(const ContactStats& c, double rss_mb);
  double wall_s() const;
  std::string silent_monitor() const;
  // Waits until the pacer lets the next period start (false: a stop was requested meanwhile).
  bool paced(const std::atomic<bool>& stop_requested);
  // Deactivates the fleet and says how the run went.
  SimHostResult result(bool ok, std::string error, bool by_monitor);

  const dds::Participant& participant;
  SimHostOptions opt;
  Fleet fleet;
  wire::Bounds bounds;
  agent::AgentNode node;  // drops windows that fail the wire checks (robot ids, NaN, off-map)
  dds::WireWriter<smart_msg_Clock> clock_out;
  dds::WireWriter<smart_msg_SimStatus> status_out;
  // External robots' poses: agents only (with a run key), each for its own robots.
  std::unique_ptr<dds::WriterAdmission> from_agents;  // before states_in: its filter
  dds::WireReader<smart_msg_RobotState> states_in;
  Pacer pacer;                // lock-step: periods no faster than opt.real_time_factor x real time
  wire::SyncCounter windows;  // per robot, the end of the latest window received
  uint64_t finished_total = 0;  // actions this host reported finished (sum over robots)
  uint64_t run_id = 0;
  uint64_t tick = 0;
  uint64_t state_every = 1;
  wire::Rejections rejected_states;  // external robots' states
  ContactStats last_status{};
  const SteadyClock::time_point wall0 = SteadyClock::now();

 private:
  bool accept_window(const agent::WindowInfo& w);
};

}  // namespace smart::sim::detail
