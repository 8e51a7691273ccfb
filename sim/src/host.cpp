#include "smart/sim/host.hpp"

#include <thread>

#include "host_core.hpp"
#include "sharded_host.hpp"
#include "smart/common/memory.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/sim/ros_view.hpp"

namespace smart::sim {

namespace {

// A whole fleet in one process: the lock-step loop (wire::HostHandshake) or the real-time loop,
// with the ROS 2 view.
class FleetHost final : public detail::HostLoop {
 public:
  FleetHost(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
            const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
            const SimHostOptions& o)
      : core_(p, qos, grid, model, starts, o),
        ros_view_(p, qos, starts.size(), o.ros_pose_robots, o.ros_namespace),
        handshake_(o.timeout_s, dds::kClockReannounceS) {
    core_.host_robots({});
    ros_view_.publish_map(grid, o.sim.cell_m);
  }

  SimHostResult run(const std::atomic<bool>& stop_requested) override {
    return core_.opt.clock == ClockMode::kLockstep ? run_lockstep(stop_requested)
                                                   : run_realtime(stop_requested);
  }

 private:
  // One control period; then everything it produced goes out.
  void advance() {
    core_.track_external_robots();
    core_.step();
    if (core_.states_due()) publish_states();
    publish_status(false);
    core_.publish_clock(core_.finished_total);
  }

  void publish_states() {
    ros_view_.publish(core_.fleet.world());
    core_.publish_states();
  }

  void publish_status(bool force) {
    core_.publish_status(core_.fleet.world().contacts(), common::peak_rss_mb, force);
  }

  SimHostResult finish(bool ok, std::string error, bool by_monitor) {
    publish_states();  // the monitor judges the robots' final poses (success means success)
    publish_status(true);
    return core_.result(ok, std::move(error), by_monitor);
  }

  SimHostResult run_lockstep(const std::atomic<bool>& stop_requested);
  SimHostResult run_realtime(const std::atomic<bool>& stop_requested);

  detail::HostCore core_;
  RosView ros_view_;  // ROS 2 view (poses, tf, chosen robots' pose topics), at the state rate
  wire::HostHandshake handshake_;
};

SimHostResult FleetHost::run_lockstep(const std::atomic<bool>& stop_requested) {
  dds::WaitSet waitset(core_.participant);
  waitset.attach_status(core_.node.action_reader(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(core_.node.clock_reader(), DDS_DATA_AVAILABLE_STATUS, 2);
  core_.publish_clock(core_.finished_total);
  handshake_.announced(core_.tick, core_.wall_s());
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal", false);
    if (handshake_.timed_out(core_.wall_s())) return finish(false, core_.silent_monitor(), false);
    waitset.wait(std::chrono::milliseconds(20));
    if (auto answer = core_.node.take_monitor_clock(); answer && core_.stop_of_this_run(*answer)) {
      handshake_.on_answer(*answer);
    }
    core_.read_windows();
    if (handshake_.stop()) {
      // The final states wait for the windows the stop counts (bounded by the timeout above).
      if (handshake_.stop_settled(core_.windows.total())) return finish(true, "", true);
      continue;
    }
    if (handshake_.may_step(core_.run_id, core_.windows.total())) {
      if (!core_.paced(stop_requested)) continue;  // the loop's top returns
      advance();
      handshake_.announced(core_.tick, core_.wall_s());
    } else if (handshake_.should_reannounce(core_.wall_s())) {
      core_.publish_clock(core_.finished_total);
      handshake_.reannounced(core_.wall_s());
    }
  }
}

SimHostResult FleetHost::run_realtime(const std::atomic<bool>& stop_requested) {
  using SteadyClock = detail::HostCore::SteadyClock;
  const auto period = std::chrono::duration_cast<SteadyClock::duration>(
      std::chrono::duration<double>(core_.opt.sim.control_period_s));
  auto next = SteadyClock::now();
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal", false);
    core_.read_windows();
    if (auto c = core_.node.take_monitor_clock(); c && c->stop && core_.stop_of_this_run(*c)) {
      return finish(true, "", true);
    }
    advance();
    next += period;
    std::this_thread::sleep_until(next);
  }
}

}  // namespace

struct SimHost::Impl {
  std::unique_ptr<detail::HostLoop> loop;
};

SimHost::SimHost(const dds::Participant& participant, const dds::QosProfile& qos,
                 const grid::Grid& grid, const agent::RobotModel& model,
                 const std::vector<agent::Pose2D>& starts, const SimHostOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (options.shards > 1) {
    impl_->loop = detail::make_sharded_host(participant, qos, grid, model, starts, options);
  } else {
    impl_->loop = std::make_unique<FleetHost>(participant, qos, grid, model, starts, options);
  }
}

SimHost::~SimHost() = default;

SimHostResult SimHost::run(const std::atomic<bool>& stop_requested) {
  return impl_->loop->run(stop_requested);
}

}  // namespace smart::sim
