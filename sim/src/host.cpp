#include "smart/sim/host.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "smart/agent/agent.hpp"
#include "smart/agent/fleet_link.hpp"
#include "smart/common/memory.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/writer.hpp"
#include "smart/sim/ros_view.hpp"
#include "smart/sim/sim_robot.hpp"

namespace smart::sim {

std::vector<agent::Pose2D> start_poses(const grid::Grid& grid, double cell_m,
                                       const std::vector<grid::Cell>& starts, double yaw) {
  std::vector<agent::Pose2D> out;
  for (const auto& c : starts) {
    const auto p = grid.to_world(grid::HalfCell::of(c), cell_m);
    out.push_back({p.x_m, p.y_m, yaw});
  }
  return out;
}

struct SimHost::Impl {
  const dds::Participant& participant;
  SimHostOptions opt;
  World world;
  agent::FleetLink link;
  // ROS 2 view (poses, tf, chosen robots' pose topics), at the state rate.
  RosView ros_view;
  std::vector<std::unique_ptr<SimRobot>> backends;
  std::vector<std::unique_ptr<agent::Agent>> agents;
  std::vector<int64_t> reported_finished, reported_executing;
  std::vector<uint32_t> window_end;     // per robot, end of the latest window received
  std::vector<uint32_t> total_actions;  // per robot, from its windows
  uint64_t window_end_total = 0;
  uint64_t run_id = 0;
  uint64_t finished_total = 0;  // sum over robots of finished_seq + 1, as reported
  uint64_t rejected_windows = 0;

  Impl(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
       const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
       const SimHostOptions& o)
      : participant(p),
        opt(o),
        world(grid, model, o.sim, starts),
        link(p, qos),
        ros_view(p, qos, starts.size(), o.ros_pose_robots) {
    const std::size_t n = starts.size();
    for (uint32_t i = 0; i < n; ++i) {
      backends.push_back(std::make_unique<SimRobot>(world, i));
      agents.push_back(std::make_unique<agent::Agent>(
          agent::AgentConfig{i, model, o.sim.control_period_s, o.pose_timeout_s}, *backends[i],
          *backends[i]));
      agents.back()->activate();
    }
    for (const uint32_t e : o.external_robots) {
      if (e >= n) {
        throw std::invalid_argument("external robot " + std::to_string(e) + " but the sim has " +
                                    std::to_string(n) + " robots");
      }
      world.set_external(e, true);
      agents[e]->deactivate();
    }
    ros_view.publish_map(grid, o.sim.cell_m);
    reported_finished.assign(n, -1);
    reported_executing.assign(n, -1);
    window_end.assign(n, 0);
    total_actions.assign(n, 0);
  }

  void apply_windows() {
    link.take_windows([&](const agent::ReceivedWindow& w) {
      if (w.robot_id >= agents.size()) {
        if (rejected_windows++ == 0) {
          spdlog::error(
              "sim host: window for robot {} but this host has {} robots; check "
              "--agents on both sides",
              w.robot_id, agents.size());
        }
        return;
      }
      if (w.run_id < run_id) return;  // history of an earlier run
      if (w.run_id > run_id) {
        run_id = w.run_id;
        std::fill(window_end.begin(), window_end.end(), 0);
        window_end_total = 0;
      }
      if (!world.external(w.robot_id)) agents[w.robot_id]->on_window(w.run_id, w.actions);
      total_actions[w.robot_id] = w.total_actions;
      const uint32_t end = w.actions.empty() ? window_end[w.robot_id] : w.end_seq;
      if (end > window_end[w.robot_id]) {
        window_end_total += end - window_end[w.robot_id];
        window_end[w.robot_id] = end;
      }
    });
  }

  void track_external_robots() {
    link.take_states([&](const smart_msg_RobotState& s) {
      if (s.robot_id < agents.size() && world.external(s.robot_id)) {
        world.set_external_pose(s.robot_id, {s.pose.x_m, s.pose.y_m, s.pose.yaw_rad});
      }
    });
  }

  void publish_progress() {
    for (uint32_t i = 0; i < agents.size(); ++i) {
      if (world.external(i)) continue;
      const auto& a = *agents[i];
      if (a.run_id() == 0) continue;
      if (a.finished_seq() != reported_finished[i] || a.executing_seq() != reported_executing[i]) {
        if (a.finished_seq() > reported_finished[i]) {
          finished_total += static_cast<uint64_t>(a.finished_seq() - reported_finished[i]);
        }
        link.publish_progress(i, a.run_id(), a.finished_seq(), a.executing_seq());
        reported_finished[i] = a.finished_seq();
        reported_executing[i] = a.executing_seq();
      }
    }
  }

  void publish_states() {
    ros_view.publish(world);
    for (uint32_t i = 0; i < agents.size(); ++i) {
      if (world.external(i)) continue;
      const auto s = agent::make_robot_state(i, run_id, world.time_s(), world.pose(i),
                                             world.wheel_speeds(i), agents[i]->queue_length());
      link.publish_state(s);
    }
  }

  void publish_clock(uint64_t tick) {
    link.publish_clock(smart_msg_Clock{agent::kSimClockSource, run_id, tick, world.time_s(),
                                       finished_total, false});
  }

  ContactStats last_status{};
  double wall_start_s = 0;
  void publish_status(bool force, double wall_s) {
    const auto& c = world.contacts();
    if (!force && c.robot_robot_events == last_status.robot_robot_events &&
        c.robot_wall_events == last_status.robot_wall_events &&
        c.min_gap_m == last_status.min_gap_m) {
      return;
    }
    last_status = c;
    link.publish_sim_status(smart_msg_SimStatus{
        agent::kSimClockSource, run_id, world.time_s(), static_cast<uint32_t>(agents.size()),
        c.robot_robot_events, c.robot_wall_events, c.min_gap_m, wall_s, common::peak_rss_mb()});
  }

  double awake_robot_ticks = 0, active_system_ticks = 0;
  void step_all() {
    track_external_robots();
    for (auto& a : agents) a->step(world.time_s());
    world.step();
    awake_robot_ticks += static_cast<double>(world.awake_robots());
    active_system_ticks += static_cast<double>(world.active_systems());
  }
};

SimHost::SimHost(const dds::Participant& participant, const dds::QosProfile& qos,
                 const grid::Grid& grid, const agent::RobotModel& model,
                 const std::vector<agent::Pose2D>& starts, const SimHostOptions& options)
    : impl_(std::make_unique<Impl>(participant, qos, grid, model, starts, options)) {}

SimHost::~SimHost() = default;

SimHostResult SimHost::run(const std::atomic<bool>& stop_requested) {
  auto& I = *impl_;
  using Clock = std::chrono::steady_clock;
  const auto wall0 = Clock::now();
  SimHostResult r;
  dds::WaitSet waitset(I.participant);
  waitset.attach_status(I.link.action_reader(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(I.link.clock_reader(), DDS_DATA_AVAILABLE_STATUS, 2);
  const auto period = std::chrono::duration<double>(I.opt.sim.control_period_s);
  const auto state_every = std::max<uint64_t>(
      1, static_cast<uint64_t>(1.0 / (I.opt.state_rate_hz * I.opt.sim.control_period_s) + 0.5));
  uint64_t tick = 0;
  // One control period: agents and world step, then everything the period produced goes out.
  auto advance = [&] {
    I.step_all();
    ++tick;
    I.publish_progress();
    if (tick % state_every == 0) I.publish_states();
    I.publish_status(false, std::chrono::duration<double>(Clock::now() - wall0).count());
    I.publish_clock(tick);
  };
  auto wall_s = [&] { return std::chrono::duration<double>(Clock::now() - wall0).count(); };
  auto finish = [&](bool ok, std::string error) {
    I.publish_status(true, wall_s());
    r.ok = ok;
    r.error = std::move(error);
    r.ticks = tick;
    r.sim_time_s = I.world.time_s();
    r.wall_time_s = std::chrono::duration<double>(Clock::now() - wall0).count();
    r.contacts = I.world.contacts();
    const double ticks = static_cast<double>(std::max<uint64_t>(tick, 1));
    r.mean_awake_robots = I.awake_robot_ticks / ticks;
    r.mean_active_systems = I.active_system_ticks / ticks;
    for (auto& a : I.agents) a->deactivate();
    return r;
  };

  if (I.opt.clock == ClockMode::kLockstep) {
    I.publish_clock(0);
    for (;;) {
      // Wait for the monitor's answer to `tick` and the windows it announces.
      const auto deadline = Clock::now() + std::chrono::duration<double>(I.opt.timeout_s);
      std::optional<smart_msg_Clock> answer;
      auto last_publish = Clock::now();
      for (;;) {
        if (stop_requested.load()) return finish(false, "stopped by signal");
        if (Clock::now() > deadline) {
          return finish(false, "no answer from the monitor for " + std::to_string(I.opt.timeout_s) +
                                   " s at tick " + std::to_string(tick) +
                                   "; is `smart monitor` running on "
                                   "domain " +
                                   std::to_string(I.participant.domain_id()) +
                                   " with the same --qos and --network?");
        }
        waitset.wait(std::chrono::milliseconds(20));
        if (auto c = I.link.take_monitor_clock()) {
          if (c->stop) {
            r.stopped_by_monitor = true;
            return finish(true, "");
          }
          if (c->tick == tick) answer = c;
        }
        I.apply_windows();
        if (answer && I.window_end_total == answer->sync_total && I.run_id == answer->run_id) {
          break;
        }
        // Until the monitor has matched, re-announce the tick (a late joiner missed it).
        if (!answer && Clock::now() - last_publish > std::chrono::milliseconds(500)) {
          I.publish_clock(tick);
          last_publish = Clock::now();
        }
      }
      advance();
    }
  }

  auto next = Clock::now();
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal");
    I.apply_windows();
    if (auto c = I.link.take_monitor_clock(); c && c->stop) {
      r.stopped_by_monitor = true;
      return finish(true, "");
    }
    advance();
    next += std::chrono::duration_cast<Clock::duration>(period);
    std::this_thread::sleep_until(next);
  }
}

}  // namespace smart::sim
