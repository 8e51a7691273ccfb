#include "smart/sim/host.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <thread>

#include "smart/agent/agent_node.hpp"
#include "smart/common/memory.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/sim/ros_view.hpp"
#include "smart/wire/convert.hpp"
#include "smart/wire/lockstep.hpp"
#include "smart/wire/validate.hpp"

namespace smart::sim {

namespace {
using SteadyClock = std::chrono::steady_clock;
}  // namespace

struct SimHost::Impl {
  const dds::Participant& participant;
  SimHostOptions opt;
  Fleet fleet;
  wire::Bounds bounds;
  agent::AgentNode node;  // drops windows that fail the wire checks (robot ids, NaN, off-map)
  RosView ros_view;       // ROS 2 view (poses, tf, chosen robots' pose topics), at the state rate
  dds::WireWriter<smart_msg_Clock> clock_out;
  dds::WireWriter<smart_msg_SimStatus> status_out;
  dds::WireReader<smart_msg_RobotState> states_in;  // external robots' poses
  wire::HostHandshake handshake;
  wire::SyncCounter windows;    // per robot, the end of the latest window received
  uint64_t finished_total = 0;  // actions reported finished (sum over robots)
  uint64_t run_id = 0;
  uint64_t tick = 0;
  uint64_t state_every = 1;
  wire::Rejections rejected_states;  // external robots' states
  ContactStats last_status{};
  const SteadyClock::time_point wall0 = SteadyClock::now();

  Impl(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
       const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
       const SimHostOptions& o)
      : participant(p),
        opt(o),
        fleet(grid, model, o.sim, starts, o.pose_timeout_s),
        bounds(wire::bounds_of(grid, o.sim.cell_m)),
        node(p, qos, starts.size(), bounds),
        ros_view(p, qos, starts.size(), o.ros_pose_robots),
        clock_out(p, qos),
        status_out(p, qos),
        states_in(p, qos),
        handshake(o.timeout_s, dds::kClockReannounceS),
        windows(starts.size()) {
    node.set_link(qos.link);  // windows and progress travel over the modelled link
    for (const uint32_t e : o.external_robots) fleet.set_external(e);
    for (uint32_t i = 0; i < fleet.robots(); ++i) {
      if (!fleet.external(i)) node.host(fleet.agent(i));
    }
    ros_view.publish_map(grid, o.sim.cell_m);
    // 0 Hz: no periodic states (states.csv stays empty); the final states still go out, so the
    // monitor can verify every robot at its goal.
    state_every =
        o.state_rate_hz <= 0
            ? 0
            : std::max<uint64_t>(
                  1, static_cast<uint64_t>(1.0 / (o.state_rate_hz * o.sim.control_period_s) + 0.5));
  }

  double wall_s() const {
    return std::chrono::duration<double>(SteadyClock::now() - wall0).count();
  }

  // Windows of every robot count for the handshake, driven here or not.
  bool accept_window(const agent::WindowInfo& w) {
    if (w.run_id < run_id) return false;  // history of an earlier run
    if (w.run_id > run_id) {
      run_id = w.run_id;
      windows.reset();
    }
    if (!w.empty) windows.raise(w.robot_id, w.end_seq);
    return true;
  }

  // A stop ends only the run this host executes (any answer that is not a stop passes).
  bool stop_of_this_run(const wire::Tick& answer) const {
    return !answer.stop || run_id == 0 || answer.run_id == run_id;
  }

  void read_windows() {
    node.take_windows([this](const agent::WindowInfo& w) { return accept_window(w); },
                      fleet.world().time_s());
  }

  void track_external_robots() {
    states_in.take_each([&](const smart_msg_RobotState& s) {
      if (auto why = wire::check_state(s, fleet.robots(), bounds); !why.empty()) {
        if (rejected_states.count("state", why)) spdlog::warn("sim host: state rejected: {}", why);
        return;
      }
      if (fleet.external(s.robot_id)) {
        fleet.world().set_external_pose(s.robot_id, {s.pose.x_m, s.pose.y_m, s.pose.yaw_rad});
      }
    });
  }

  // One control period; then everything it produced goes out.
  void advance() {
    track_external_robots();
    fleet.step();
    ++tick;
    finished_total += node.publish_progress(fleet.world().time_s());
    if (state_every > 0 && tick % state_every == 0) publish_states();
    publish_status(false);
    publish_clock();
  }

  void publish_states() {
    const World& world = fleet.world();
    ros_view.publish(world);
    for (uint32_t i = 0; i < fleet.robots(); ++i) {
      if (fleet.external(i)) continue;
      node.publish_state(i, run_id, world.time_s(), world.pose(i), world.wheel_speeds(i));
    }
  }

  void publish_clock() {
    clock_out.write(wire::to_wire({run_id, tick, fleet.world().time_s(), finished_total, false},
                                  dds::kSimClockSource));
  }

  void publish_status(bool force) {
    const auto& c = fleet.world().contacts();
    if (!force && c.robot_robot_events == last_status.robot_robot_events &&
        c.robot_wall_events == last_status.robot_wall_events &&
        c.min_gap_m == last_status.min_gap_m) {
      return;
    }
    last_status = c;
    status_out.write(smart_msg_SimStatus{
        dds::kSimClockSource, run_id, fleet.world().time_s(), static_cast<uint32_t>(fleet.robots()),
        c.robot_robot_events, c.robot_wall_events, c.min_gap_m, wall_s(), common::peak_rss_mb(),
        static_cast<int32_t>(c.first_pair_a), static_cast<int32_t>(c.first_pair_b)});
  }

  SimHostResult finish(bool ok, std::string error, bool by_monitor) {
    publish_states();  // the monitor judges the robots' final poses (success means success)
    publish_status(true);
    fleet.deactivate();
    const auto s = fleet.stats();
    SimHostResult r;
    r.ok = ok;
    r.error = std::move(error);
    r.stopped_by_monitor = by_monitor;
    r.ticks = tick;
    r.sim_time_s = fleet.world().time_s();
    r.wall_time_s = wall_s();
    r.contacts = fleet.world().contacts();
    r.mean_awake_robots = s.mean_awake_robots;
    r.mean_active_systems = s.mean_active_systems;
    r.rejected_samples = node.rejections().counts();
    for (const auto& [topic, reasons] : rejected_states.counts())
      r.rejected_samples[topic] = reasons;
    return r;
  }

  std::string silent_monitor() const {
    return "no answer from the monitor for " + std::to_string(opt.timeout_s) + " s at tick " +
           std::to_string(tick) + "; is `smart monitor` running on domain " +
           std::to_string(participant.domain_id()) + " with the same --qos and --network?";
  }

  SimHostResult run_lockstep(const std::atomic<bool>& stop_requested);
  SimHostResult run_realtime(const std::atomic<bool>& stop_requested);
};

SimHostResult SimHost::Impl::run_lockstep(const std::atomic<bool>& stop_requested) {
  dds::WaitSet waitset(participant);
  waitset.attach_status(node.action_reader(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(node.clock_reader(), DDS_DATA_AVAILABLE_STATUS, 2);
  publish_clock();
  handshake.announced(tick, wall_s());
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal", false);
    if (handshake.timed_out(wall_s())) return finish(false, silent_monitor(), false);
    waitset.wait(std::chrono::milliseconds(20));
    if (auto answer = node.take_monitor_clock(); answer && stop_of_this_run(*answer)) {
      handshake.on_answer(*answer);
    }
    if (handshake.stop()) return finish(true, "", true);
    read_windows();
    if (handshake.may_step(run_id, windows.total())) {
      advance();
      handshake.announced(tick, wall_s());
    } else if (handshake.should_reannounce(wall_s())) {
      publish_clock();
      handshake.reannounced(wall_s());
    }
  }
}

SimHostResult SimHost::Impl::run_realtime(const std::atomic<bool>& stop_requested) {
  const auto period = std::chrono::duration_cast<SteadyClock::duration>(
      std::chrono::duration<double>(opt.sim.control_period_s));
  auto next = SteadyClock::now();
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal", false);
    read_windows();
    if (auto c = node.take_monitor_clock(); c && c->stop && stop_of_this_run(*c)) {
      return finish(true, "", true);
    }
    advance();
    next += period;
    std::this_thread::sleep_until(next);
  }
}

SimHost::SimHost(const dds::Participant& participant, const dds::QosProfile& qos,
                 const grid::Grid& grid, const agent::RobotModel& model,
                 const std::vector<agent::Pose2D>& starts, const SimHostOptions& options)
    : impl_(std::make_unique<Impl>(participant, qos, grid, model, starts, options)) {}

SimHost::~SimHost() = default;

SimHostResult SimHost::run(const std::atomic<bool>& stop_requested) {
  return impl_->opt.clock == ClockMode::kLockstep ? impl_->run_lockstep(stop_requested)
                                                  : impl_->run_realtime(stop_requested);
}

}  // namespace smart::sim
