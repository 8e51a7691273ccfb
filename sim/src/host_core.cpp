#include "host_core.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "smart/convert/convert.hpp"

namespace smart::sim::detail {

namespace {
// A shard simulates about its share of the fleet: automatic threads count that share.
SimConfig fleet_config(const SimHostOptions& o, std::size_t robots) {
  SimConfig c = o.sim;
  c.threads = sim_threads(c.threads, robots / std::max<uint32_t>(1, o.shards));
  return c;
}
}  // namespace

HostCore::HostCore(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
                   const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
                   const SimHostOptions& o)
    : participant(p),
      opt(o),
      fleet(grid, model, fleet_config(o, starts.size()), starts, o.pose_timeout_s),
      bounds(wire::bounds_of(grid, o.sim.cell_m)),
      node(p, qos, starts.size(), bounds),
      clock_out(p, qos),
      status_out(p, qos),
      from_agents(dds::WriterAdmission::per_robot(p, {"agent"})),
      states_in(p, qos, *from_agents),
      pacer(o.clock == ClockMode::kLockstep ? o.real_time_factor : 0, o.sim.control_period_s),
      windows(starts.size()) {
  node.set_link(qos.link);  // windows and progress travel over the modelled link
  for (const uint32_t e : o.external_robots) fleet.set_external(e);
  // 0 Hz: no periodic states (states.csv stays empty); the final states still go out, so the
  // monitor can verify every robot at its goal.
  state_every = o.state_rate_hz <= 0
                    ? 0
                    : std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(
                                                1.0 / (o.state_rate_hz * o.sim.control_period_s))));
}

void HostCore::host_robots(const RobotFilter& steps) {
  for (uint32_t i = 0; i < fleet.robots(); ++i) {
    if (!fleet.external(i) && (!steps || steps(i))) node.host(fleet.agent(i));
  }
}

bool HostCore::accept_window(const agent::WindowInfo& w) {
  if (w.run_id < run_id) return false;  // history of an earlier run
  if (w.run_id > run_id) {
    run_id = w.run_id;
    windows.reset();
  }
  if (!w.empty) windows.raise(w.robot_id, w.end_seq);
  return true;
}

void HostCore::read_windows(const agent::AgentNode::Unhosted& unhosted) {
  node.take_windows([this](const agent::WindowInfo& w) { return accept_window(w); },
                    fleet.world().time_s(), unhosted);
}

bool HostCore::stop_of_this_run(const wire::Tick& answer) const {
  return !answer.stop || run_id == 0 || answer.run_id == run_id;
}

void HostCore::track_external_robots() {
  for (const auto& [writer, n] : from_agents->take_refused()) {
    if (rejected_states.count("state", dds::kNotRunMember, {}, n)) {
      spdlog::warn("sim host: {} state samples refused: {}", n, dds::kNotRunMember);
    }
  }
  for (const auto& [writer, n] : from_agents->take_misspoken()) {
    const auto speaks = from_agents->speaks(writer);
    const auto why = speaks ? dds::speaks_only(*speaks) : std::string("for another robot");
    if (rejected_states.count("state", why, {}, n))
      spdlog::warn("sim host: state refused: {}", why);
  }
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

void HostCore::step(const agent::AgentNode::ProgressFilter& write_here) {
  fleet.step();
  ++tick;
  finished_total += node.publish_progress(fleet.world().time_s(), write_here);
}

void HostCore::publish_states(const RobotFilter& steps, const RobotFilter& home,
                              std::vector<smart_msg_RobotState>* away) {
  const World& world = fleet.world();
  for (uint32_t i = 0; i < fleet.robots(); ++i) {
    if (fleet.external(i) || (steps && !steps(i))) continue;
    if (!home || home(i)) {
      node.publish_state(i, run_id, world.time_s(), world.pose(i), world.wheel_speeds(i));
    } else if (away) {
      away->push_back(wire::robot_state(i, run_id, world.time_s(), world.pose(i),
                                        world.wheel_speeds(i), fleet.agent(i).queue_length()));
    }
  }
  node.flush_states();
}

void HostCore::publish_clock(uint64_t finished_total_announced) {
  clock_out.write(
      wire::to_wire({run_id, tick, fleet.world().time_s(), finished_total_announced, false},
                    dds::kSimClockSource));
}

void HostCore::publish_status(const ContactStats& c, const std::function<double()>& rss_mb,
                              bool force) {
  if (!force && c.robot_robot_events == last_status.robot_robot_events &&
      c.robot_wall_events == last_status.robot_wall_events &&
      c.min_gap_m == last_status.min_gap_m) {
    return;
  }
  last_status = c;
  write_status(c, rss_mb());
}

void HostCore::write_status(const ContactStats& c, double rss_mb) {
  status_out.write(smart_msg_SimStatus{
      dds::kSimClockSource, run_id, fleet.world().time_s(), static_cast<uint32_t>(fleet.robots()),
      c.robot_robot_events, c.robot_wall_events, c.min_gap_m, wall_s(), rss_mb,
      static_cast<int32_t>(c.first_pair_a), static_cast<int32_t>(c.first_pair_b)});
}

double HostCore::wall_s() const {
  return std::chrono::duration<double>(SteadyClock::now() - wall0).count();
}

std::string HostCore::silent_monitor() const {
  return "no answer from the monitor for " + std::to_string(opt.timeout_s) + " s at tick " +
         std::to_string(tick) + "; is `smart monitor` running on domain " +
         std::to_string(participant.domain_id()) + " with the same --qos and --network?";
}

bool HostCore::paced(const std::atomic<bool>& stop_requested) {
  for (double w = pacer.wait_s(wall_s()); w > 0; w = pacer.wait_s(wall_s())) {
    if (stop_requested.load()) return false;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::min(w, 0.05)));
  }
  pacer.started(wall_s());
  return true;
}

SimHostResult HostCore::result(bool ok, std::string error, bool by_monitor) {
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
  for (const auto& [topic, reasons] : rejected_states.counts()) {
    r.rejected_samples[topic] = reasons;
  }
  return r;
}

}  // namespace smart::sim::detail
