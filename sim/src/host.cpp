#include "smart/sim/host.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <thread>

#include "shard_host.hpp"
#include "smart/agent/agent_node.hpp"
#include "smart/common/memory.hpp"
#include "smart/convert/convert.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/sim/pacer.hpp"
#include "smart/sim/ros_view.hpp"
#include "smart/sim/shard.hpp"
#include "smart/wire/lockstep.hpp"

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
  Pacer pacer;                // lock-step: periods no faster than opt.real_time_factor x real time
  wire::SyncCounter windows;  // per robot, the end of the latest window received
  uint64_t finished_total = 0;  // actions reported finished (sum over robots)
  uint64_t run_id = 0;
  uint64_t tick = 0;
  uint64_t state_every = 1;
  wire::Rejections rejected_states;  // external robots' states
  ContactStats last_status{};
  const SteadyClock::time_point wall0 = SteadyClock::now();
  // Sharded runs (options.shards > 1).
  std::optional<ShardMap> shard_map;
  std::optional<FleetShard> shard;
  std::optional<detail::ShardPeer> peer;
  bool applied = false;                     // the other shards' exchanges of `tick` are applied
  std::vector<smart_msg_Progress> relayed;  // progress of this period for other homes
  detail::Exchange mine;                    // this shard's latest exchange
  uint64_t handovers_in = 0;
  uint64_t announced_total = 0;  // the lead's last tick: the fleet's finished actions

  // A shard simulates about its share of the fleet: automatic threads count that share.
  static SimConfig fleet_config(const SimHostOptions& o, std::size_t robots) {
    SimConfig c = o.sim;
    c.threads = sim_threads(c.threads, robots / std::max<uint32_t>(1, o.shards));
    return c;
  }

  Impl(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
       const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
       const SimHostOptions& o)
      : participant(p),
        opt(o),
        fleet(grid, model, fleet_config(o, starts.size()), starts, o.pose_timeout_s),
        bounds(wire::bounds_of(grid, o.sim.cell_m)),
        node(p, qos, starts.size(), bounds),
        ros_view(p, qos, starts.size(), o.ros_pose_robots),
        clock_out(p, qos),
        status_out(p, qos),
        states_in(p, qos),
        handshake(o.timeout_s, dds::kClockReannounceS),
        pacer(o.clock == ClockMode::kLockstep ? o.real_time_factor : 0, o.sim.control_period_s),
        windows(starts.size()) {
    node.set_link(qos.link);  // windows and progress travel over the modelled link
    for (const uint32_t e : o.external_robots) fleet.set_external(e);
    if (o.shards > 1) start_shard(p, qos, grid, model, starts);
    for (uint32_t i = 0; i < fleet.robots(); ++i) {
      if (!fleet.external(i) && (!shard || shard->simulates(i))) node.host(fleet.agent(i));
    }
    if (!sharded()) ros_view.publish_map(grid, o.sim.cell_m);
    // 0 Hz: no periodic states (states.csv stays empty); the final states still go out, so the
    // monitor can verify every robot at its goal.
    state_every =
        o.state_rate_hz <= 0
            ? 0
            : std::max<uint64_t>(
                  1, static_cast<uint64_t>(1.0 / (o.state_rate_hz * o.sim.control_period_s) + 0.5));
  }

  bool sharded() const { return shard.has_value(); }
  bool lead() const { return !sharded() || opt.shard == 0; }
  bool home_here(uint32_t robot) const { return !sharded() || shard->home(robot) == opt.shard; }

  void start_shard(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
                   const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts) {
    if (opt.clock != ClockMode::kLockstep || !opt.external_robots.empty() ||
        qos.link.to_host.active() || qos.link.to_monitor.active() || opt.shard >= opt.shards ||
        opt.shards > dds::kMaxShards) {
      throw std::invalid_argument(
          "shard " + std::to_string(opt.shard) + "/" + std::to_string(opt.shards) +
          ": a sharded sim runs in lock-step, without external robots or a link model (--qos "
          "lan or wifi), with at most " +
          std::to_string(dds::kMaxShards) + " shards numbered from 0");
    }
    shard_map.emplace(grid, opt.sim, model, opt.shards, starts);
    shard.emplace(fleet, *shard_map, opt.shard);
    peer.emplace(p, qos, opt.shard, opt.shards, starts.size(), bounds);
    node.set_relay([this](const smart_msg_Progress& pr) {
      if (home_here(pr.robot_id)) return false;
      relayed.push_back(pr);
      return true;
    });
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

  // Sharded: robots homed elsewhere go into `away` for their home to publish.
  void publish_states(std::vector<smart_msg_RobotState>* away = nullptr) {
    const World& world = fleet.world();
    if (!sharded()) ros_view.publish(world);
    for (uint32_t i = 0; i < fleet.robots(); ++i) {
      if (fleet.external(i) || (sharded() && !shard->simulates(i))) continue;
      if (home_here(i)) {
        node.publish_state(i, run_id, world.time_s(), world.pose(i), world.wheel_speeds(i));
      } else if (away) {
        away->push_back(wire::robot_state(i, run_id, world.time_s(), world.pose(i),
                                          world.wheel_speeds(i), fleet.agent(i).queue_length()));
      }
    }
    node.flush_states();
  }

  void publish_clock() {
    clock_out.write(wire::to_wire({run_id, tick, fleet.world().time_s(), finished_total, false},
                                  dds::kSimClockSource));
  }

  void publish_clock_again() {
    clock_out.write(wire::to_wire({run_id, tick, fleet.world().time_s(), announced_total, false},
                                  dds::kSimClockSource));
  }

  void publish_status(bool force) {
    const auto c = sharded() ? fleet_contacts(false) : fleet.world().contacts();
    if (!force && c.robot_robot_events == last_status.robot_robot_events &&
        c.robot_wall_events == last_status.robot_wall_events &&
        c.min_gap_m == last_status.min_gap_m) {
      return;
    }
    last_status = c;
    write_status(c, fleet_rss_mb(false));
  }

  // The fleet's status: this host's, or (sharded, from the lead) every shard's.
  void write_status(const ContactStats& c, double rss_mb) {
    status_out.write(smart_msg_SimStatus{
        dds::kSimClockSource, run_id, fleet.world().time_s(), static_cast<uint32_t>(fleet.robots()),
        c.robot_robot_events, c.robot_wall_events, c.min_gap_m, wall_s(), rss_mb,
        static_cast<int32_t>(c.first_pair_a), static_cast<int32_t>(c.first_pair_b)});
  }

  SimHostResult finish(bool ok, std::string error, bool by_monitor) {
    if (sharded()) {
      finish_shard();
    } else {
      publish_states();  // the monitor judges the robots' final poses (success means success)
      publish_status(true);
    }
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
    r.handovers_in = handovers_in;
    r.rejected_samples = node.rejections().counts();
    if (peer) {
      for (const auto& [topic, reasons] : peer->rejections().counts()) {
        r.rejected_samples[topic] = reasons;
      }
    }
    for (const auto& [topic, reasons] : rejected_states.counts())
      r.rejected_samples[topic] = reasons;
    return r;
  }

  std::string silent_monitor() const {
    return "no answer from the monitor for " + std::to_string(opt.timeout_s) + " s at tick " +
           std::to_string(tick) + "; is `smart monitor` running on domain " +
           std::to_string(participant.domain_id()) + " with the same --qos and --network?";
  }

  // Waits until the pacer lets the next period start (false: a stop was requested meanwhile).
  bool paced(const std::atomic<bool>& stop_requested) {
    for (double w = pacer.wait_s(wall_s()); w > 0; w = pacer.wait_s(wall_s())) {
      if (stop_requested.load()) return false;
      std::this_thread::sleep_for(std::chrono::duration<double>(std::min(w, 0.05)));
    }
    pacer.started(wall_s());
    return true;
  }

  SimHostResult run_lockstep(const std::atomic<bool>& stop_requested);
  SimHostResult run_sharded(const std::atomic<bool>& stop_requested);
  ContactStats fleet_contacts(bool last) const;
  double fleet_rss_mb(bool last) const;
  detail::Exchange exchange(bool last);
  void advance_shard();
  void relay_home(const detail::Exchange& e);
  void apply_exchanges();
  void finish_shard();
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
      if (!paced(stop_requested)) continue;  // the loop's top returns
      advance();
      handshake.announced(tick, wall_s());
    } else if (handshake.should_reannounce(wall_s())) {
      publish_clock();
      handshake.reannounced(wall_s());
    }
  }
}

// ---- Sharded runs (sim/shard.hpp) ----

// The fleet's contact counts, summed over the shards' exchanges of this period (or their last).
ContactStats SimHost::Impl::fleet_contacts(bool last) const {
  ContactStats c = fleet.world().contacts();
  const auto others = last ? peer->last() : peer->of(tick);
  for (const detail::Exchange* e : others) {
    c.robot_robot_events += e->contacts.robot_robot_events;
    c.robot_wall_events += e->contacts.robot_wall_events;
    c.min_gap_m = std::min(c.min_gap_m, e->contacts.min_gap_m);
    if (c.first_pair_a < 0) {
      c.first_pair_a = e->contacts.first_pair_a;
      c.first_pair_b = e->contacts.first_pair_b;
    }
  }
  return c;
}

// Peak memory of the whole sim: the shards' sum.
double SimHost::Impl::fleet_rss_mb(bool last) const {
  double mb = common::peak_rss_mb();
  if (sharded()) {
    for (const detail::Exchange* e : last ? peer->last() : peer->of(tick)) mb += e->peak_rss_mb;
  }
  return mb;
}

detail::Exchange SimHost::Impl::exchange(bool last) {
  detail::Exchange e;
  e.shard = opt.shard;
  e.shards = opt.shards;
  e.run_id = run_id;
  e.tick = tick;
  e.last = last;
  e.progress = std::move(relayed);
  relayed.clear();
  e.finished_total = finished_total;
  e.contacts = fleet.world().contacts();
  e.peak_rss_mb = common::peak_rss_mb();
  return e;
}

void SimHost::Impl::advance_shard() {
  fleet.step();
  ++tick;
  finished_total += node.publish_progress(fleet.world().time_s());
  detail::Exchange e = exchange(false);
  if (state_every > 0 && tick % state_every == 0) publish_states(&e.states);
  e.outbox = shard->after_step([this](uint32_t r) { return node.reported(r); });
  for (const auto& h : e.outbox.handovers) node.unhost(h.robot);
  peer->publish(e);
  mine = std::move(e);
  applied = false;
}

// Progress and states that another shard reports for robots homed here go out from here.
void SimHost::Impl::relay_home(const detail::Exchange& e) {
  for (const auto& p : e.progress) {
    if (home_here(p.robot_id)) node.write_relayed(p);
  }
  for (const auto& st : e.states) {
    if (home_here(st.robot_id)) node.write_relayed(st);
  }
}

// Every shard's exchange of this period is in: robots handed over are adopted, the neighbours'
// robots shown as ghosts; the lead announces the tick with the fleet's finished actions.
void SimHost::Impl::apply_exchanges() {
  std::vector<const ShardOutbox*> outboxes;
  uint64_t total = mine.finished_total;
  for (const detail::Exchange* e : peer->of(tick)) {
    outboxes.push_back(&e->outbox);
    total += e->finished_total;
  }
  for (const auto& h : shard->before_step(outboxes)) {
    node.host(fleet.agent(h.robot), h.reported_finished, h.reported_executing);
    ++handovers_in;
  }
  applied = true;
  if (lead()) {
    publish_status(false);
    announced_total = total;
    publish_clock_again();
    handshake.announced(tick, wall_s());
  }
  peer->forget_before(tick);
}

SimHostResult SimHost::Impl::run_sharded(const std::atomic<bool>& stop_requested) {
  dds::WaitSet waitset(participant);
  waitset.attach_status(node.action_reader(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(node.clock_reader(), DDS_DATA_AVAILABLE_STATUS, 2);
  waitset.attach_status(peer->reader(), DDS_DATA_AVAILABLE_STATUS, 3);
  mine = exchange(false);
  mine.outbox = shard->initial_outbox();
  peer->publish(mine);
  handshake.announced(tick, wall_s());
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal", false);
    if (handshake.timed_out(wall_s())) {
      return finish(
          false,
          applied ? silent_monitor()
                  : "shard " + std::to_string(opt.shard) + ": no exchange from shard(s) " +
                        peer->missing(tick) + " for period " + std::to_string(tick) + " within " +
                        std::to_string(opt.timeout_s) + " s; is every `smart sim --shard I/" +
                        std::to_string(opt.shards) + "` of the run up?",
          false);
    }
    waitset.wait(std::chrono::milliseconds(20));
    peer->take([this](const detail::Exchange& e) { relay_home(e); });
    if (!applied && peer->complete(tick)) apply_exchanges();
    if (auto answer = node.take_monitor_clock(); answer && stop_of_this_run(*answer)) {
      handshake.on_answer(*answer);
    }
    if (handshake.stop()) return finish(true, "", true);
    read_windows();
    if (applied && handshake.may_step(run_id, windows.total())) {
      if (!paced(stop_requested)) continue;
      advance_shard();
      if (!lead()) handshake.announced(tick, wall_s());
    } else if (lead() && applied && handshake.should_reannounce(wall_s())) {
      publish_clock_again();
      handshake.reannounced(wall_s());
    }
  }
}

// The end: every shard sends the states of its robots homed elsewhere in its last exchange and
// waits (up to 2 s) for the others' last, so that every robot's final pose goes out from its
// home; the lead's status then has the whole fleet's contacts.
void SimHost::Impl::finish_shard() {
  detail::Exchange e = exchange(true);
  publish_states(&e.states);
  peer->publish(e);
  const auto until = SteadyClock::now() + std::chrono::seconds(2);
  while (!peer->last_complete() && SteadyClock::now() < until) {
    peer->take([this](const detail::Exchange& x) { relay_home(x); });
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!peer->last_complete()) {
    spdlog::warn("sim shard {}: no final exchange from every shard; final poses may be missing",
                 opt.shard);
  }
  if (lead()) write_status(fleet_contacts(true), fleet_rss_mb(true));
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
  if (impl_->sharded()) return impl_->run_sharded(stop_requested);
  return impl_->opt.clock == ClockMode::kLockstep ? impl_->run_lockstep(stop_requested)
                                                  : impl_->run_realtime(stop_requested);
}

}  // namespace smart::sim
