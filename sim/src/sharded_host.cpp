#include "sharded_host.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <stdexcept>
#include <thread>
#include <utility>

#include "shard_host.hpp"
#include "smart/common/memory.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/sim/shard.hpp"
#include "smart/sim/shard_barrier.hpp"
#include "smart/wire/lockstep.hpp"

namespace smart::sim::detail {

namespace {

const SimHostOptions& shardable(const SimHostOptions& o, const dds::QosProfile& qos) {
  if (o.clock != ClockMode::kLockstep || !o.external_robots.empty() || qos.link.to_host.active() ||
      qos.link.to_monitor.active() || o.shard >= o.shards || o.shards > dds::kMaxShards) {
    throw std::invalid_argument(
        "shard " + std::to_string(o.shard) + "/" + std::to_string(o.shards) +
        ": a sharded sim runs in lock-step, without external robots or a link model (--qos "
        "lan or wifi), with at most " +
        std::to_string(dds::kMaxShards) + " shards numbered from 0");
  }
  return o;
}

class ShardedHost final : public HostLoop {
 public:
  ShardedHost(const dds::Participant& p, const dds::QosProfile& qos, const grid::Grid& grid,
              const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
              const SimHostOptions& o)
      : core_(p, qos, grid, model, starts, shardable(o, qos)),
        map_(grid, o.sim, model, o.shards, starts),
        shard_(core_.fleet, map_, o.shard),
        peer_(p, qos, o.shard, o.shards, starts.size(), core_.bounds),
        // Start-up waits the monitor's join window: shards build their worlds and take the
        // first windows at their pace.
        barrier_(o.shard, o.shards, o.timeout_s, dds::kClockReannounceS,
                 wire::kJoinTimeouts * o.timeout_s) {
    core_.host_robots(steps());
  }

  SimHostResult run(const std::atomic<bool>& stop_requested) override;

 private:
  HostCore::RobotFilter steps() const {
    return [this](uint32_t r) { return shard_.simulates(r); };
  }
  HostCore::RobotFilter home() const {
    return [this](uint32_t r) { return home_here(r); };
  }
  bool home_here(uint32_t robot) const { return shard_.home(robot) == core_.opt.shard; }

  void read_windows();
  void receive();
  Exchange exchange(bool last);
  void advance();
  void relay_home(const Exchange& e);
  void apply_exchanges();
  ContactStats fleet_contacts(bool last) const;
  double fleet_rss_mb(bool last) const;
  std::string timeout_message(const ShardTimeout& t) const;
  std::string missing_shards(const ShardTimeout& t) const;
  std::string discovered_shards() const;
  void note_stop() const;
  void repeat_if_waiting();
  SimHostResult finish(bool ok, std::string error, bool by_monitor);

  HostCore core_;
  ShardMap map_;
  FleetShard shard_;
  ShardPeer peer_;
  ShardBarrier barrier_;
  std::vector<smart_msg_Progress> relayed_;  // progress of this period for other homes
  // Windows of robots simulated elsewhere, the newest per robot (run, actions): given to the
  // robot's agent when it is handed over to this shard.
  std::map<uint32_t, std::pair<uint64_t, std::vector<agent::AgentAction>>> parked_;
  uint64_t handovers_in_ = 0;
};

void ShardedHost::read_windows() {
  core_.read_windows([this](uint32_t robot, uint64_t run, std::vector<agent::AgentAction> w) {
    parked_[robot] = {run, std::move(w)};
  });
}

// Exchanges that arrived: the progress and states of robots homed here go out at once; the
// barrier counts the period's.
void ShardedHost::receive() {
  peer_.take([this](const Exchange& e) {
    relay_home(e);
    if (!e.last) barrier_.received(e.shard, e.tick, e.finished_total);
  });
}

Exchange ShardedHost::exchange(bool last) {
  Exchange e;
  e.shard = core_.opt.shard;
  e.shards = core_.opt.shards;
  e.run_id = core_.run_id;
  e.tick = core_.tick;
  e.last = last;
  e.progress = std::move(relayed_);
  relayed_.clear();
  e.finished_total = core_.finished_total;
  e.contacts = core_.fleet.world().contacts();
  e.peak_rss_mb = common::peak_rss_mb();
  return e;
}

// One period: progress of robots homed elsewhere rides in this period's exchange.
void ShardedHost::advance() {
  core_.step([this](const smart_msg_Progress& p) {
    if (home_here(p.robot_id)) return true;
    relayed_.push_back(p);
    return false;
  });
  Exchange e = exchange(false);
  if (core_.states_due()) core_.publish_states(steps(), home(), &e.states);
  e.outbox = shard_.after_step([this](uint32_t r) { return core_.node.reported(r); });
  for (const auto& h : e.outbox.handovers) core_.node.unhost(h.robot);
  peer_.publish(e);
  barrier_.sent(core_.tick, core_.finished_total, core_.wall_s());
}

// Progress and states that another shard reports for robots homed here go out from here.
void ShardedHost::relay_home(const Exchange& e) {
  for (const auto& p : e.progress) {
    if (home_here(p.robot_id)) core_.node.write(p);
  }
  for (const auto& st : e.states) {
    if (home_here(st.robot_id)) core_.node.write(st);
  }
}

// Every shard's exchange of this period is in: robots handed over are adopted (with the windows
// kept for them), the neighbours' robots shown as ghosts; the lead announces the tick with the
// fleet's finished actions.
void ShardedHost::apply_exchanges() {
  std::vector<const ShardOutbox*> outboxes;
  for (const Exchange* e : peer_.of(core_.tick)) outboxes.push_back(&e->outbox);
  for (const auto& h : shard_.before_step(outboxes)) {
    agent::Agent& agent = core_.fleet.agent(h.robot);
    core_.node.host(agent, h.reported_finished, h.reported_executing);
    if (auto it = parked_.find(h.robot); it != parked_.end()) {
      agent.on_window(it->second.first, it->second.second);  // idempotent if it knew it already
      parked_.erase(it);
    }
    ++handovers_in_;
  }
  barrier_.apply(core_.wall_s());
  if (barrier_.lead()) {
    core_.publish_status(
        fleet_contacts(false), [this] { return fleet_rss_mb(false); }, false);
    core_.publish_clock(barrier_.announced_total());
  }
  peer_.forget_before(core_.tick);
}

// The fleet's contact counts, summed over the shards' exchanges of this period (or their last).
ContactStats ShardedHost::fleet_contacts(bool last) const {
  ContactStats c = core_.fleet.world().contacts();
  for (const Exchange* e : last ? peer_.last() : peer_.of(core_.tick)) {
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
double ShardedHost::fleet_rss_mb(bool last) const {
  double mb = common::peak_rss_mb();
  for (const Exchange* e : last ? peer_.last() : peer_.of(core_.tick)) mb += e->peak_rss_mb;
  return mb;
}

std::string ShardedHost::timeout_message(const ShardTimeout& t) const {
  if (t.waiting == ShardTimeout::Waiting::kMonitor) return core_.silent_monitor();
  return "shard " + std::to_string(core_.opt.shard) + ": no exchange from " + missing_shards(t) +
         " within " + std::to_string(t.waited_s) + " s " + discovered_shards() +
         "; is every `smart sim --shard I/" + std::to_string(core_.opt.shards) + "` of the run up?";
}

std::string ShardedHost::missing_shards(const ShardTimeout& t) const {
  std::string missing;
  for (const uint32_t s : t.missing) missing += (missing.empty() ? "" : ", ") + std::to_string(s);
  return "shard(s) " + missing + " for period " + std::to_string(t.tick);
}

// Whether the missing shards were ever discovered: not running, or up and silent.
std::string ShardedHost::discovered_shards() const {
  const std::size_t others = core_.opt.shards - 1;
  const std::size_t seen = std::min(peer_.writers_discovered(), others);
  return "(" + std::to_string(seen) + " of the " + std::to_string(others) +
         " other shards' exchange writers discovered" +
         (seen < others ? ": a shard not discovered is not running, or on another domain, "
                          "network or --run"
                        : ": the missing shard is up but has not sent this period (stalled or "
                          "starved of CPU)") +
         ")";
}

// The monitor stops the run; when that stop comes while this shard waits (the monitor gave up
// on the fleet: no tick for its timeout), the log says what for, so a lost run shows where the
// fleet stood without a debugger.
void ShardedHost::note_stop() const {
  const ShardTimeout w = barrier_.waiting();
  const std::string shard =
      "sim shard " + std::to_string(core_.opt.shard) + "/" + std::to_string(core_.opt.shards);
  const std::string windows = "; windows received: " + std::to_string(core_.windows.total());
  if (w.waiting == ShardTimeout::Waiting::kShards) {
    spdlog::warn("{}: stopped by the monitor while waiting for the exchange of {} {}{}", shard,
                 missing_shards(w), discovered_shards(), windows);
  } else if (w.waiting == ShardTimeout::Waiting::kMonitor) {
    spdlog::warn("{}: stopped by the monitor while waiting for its answer to tick {}{}", shard,
                 w.tick, windows);
  }
}

SimHostResult ShardedHost::run(const std::atomic<bool>& stop_requested) {
  dds::WaitSet waitset(core_.participant);
  waitset.attach_status(core_.node.action_reader(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(core_.node.clock_reader(), DDS_DATA_AVAILABLE_STATUS, 2);
  waitset.attach_status(peer_.reader(), DDS_DATA_AVAILABLE_STATUS, 3);
  Exchange first = exchange(false);
  first.outbox = shard_.initial_outbox();
  peer_.publish(first);
  barrier_.sent(0, core_.finished_total, core_.wall_s());
  for (;;) {
    if (stop_requested.load()) return finish(false, "stopped by signal", false);
    if (const auto t = barrier_.timed_out(core_.wall_s());
        t.waiting != ShardTimeout::Waiting::kNothing) {
      return finish(false, timeout_message(t), false);
    }
    waitset.wait(std::chrono::milliseconds(20));
    receive();
    if (barrier_.ready()) apply_exchanges();
    if (auto answer = core_.node.take_monitor_clock(); answer && core_.stop_of_this_run(*answer)) {
      barrier_.on_answer(*answer);
    }
    if (barrier_.stop()) {
      note_stop();
      return finish(true, "", true);
    }
    read_windows();
    if (barrier_.may_step(core_.run_id, core_.windows.total())) {
      if (!core_.paced(stop_requested)) continue;  // the loop's top returns
      advance();
    } else {
      repeat_if_waiting();
    }
  }
}

// Waiting without a step: the lead announces its tick again (a monitor that joined late missed
// it), and every shard sends its last exchanges again (one lost on its way to a shard).
void ShardedHost::repeat_if_waiting() {
  const double now_s = core_.wall_s();
  if (barrier_.should_reannounce(now_s)) {
    core_.publish_clock(barrier_.announced_total());
    barrier_.reannounced(now_s);
  }
  if (barrier_.should_repeat(now_s)) {
    peer_.repeat();
    barrier_.repeated(now_s);
  }
}

// The end: every shard sends the states of its robots homed elsewhere in its last exchange and
// waits (up to 2 s) for the others' last, so that every robot's final pose goes out from its
// home; the lead's status then has the whole fleet's contacts.
SimHostResult ShardedHost::finish(bool ok, std::string error, bool by_monitor) {
  Exchange e = exchange(true);
  core_.publish_states(steps(), home(), &e.states);
  peer_.publish(e);
  const auto until = HostCore::SteadyClock::now() + std::chrono::seconds(2);
  while (!peer_.last_complete() && HostCore::SteadyClock::now() < until) {
    peer_.take([this](const Exchange& x) { relay_home(x); });
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!peer_.last_complete()) {
    spdlog::warn("sim shard {}: no final exchange from every shard; final poses may be missing",
                 core_.opt.shard);
  }
  if (barrier_.lead()) core_.write_status(fleet_contacts(true), fleet_rss_mb(true));
  SimHostResult r = core_.result(ok, std::move(error), by_monitor);
  r.handovers_in = handovers_in_;
  for (const auto& [topic, reasons] : peer_.rejections().counts()) {
    r.rejected_samples[topic] = reasons;
  }
  return r;
}

}  // namespace

std::unique_ptr<HostLoop> make_sharded_host(const dds::Participant& participant,
                                            const dds::QosProfile& qos, const grid::Grid& grid,
                                            const agent::RobotModel& model,
                                            const std::vector<agent::Pose2D>& starts,
                                            const SimHostOptions& options) {
  return std::make_unique<ShardedHost>(participant, qos, grid, model, starts, options);
}

}  // namespace smart::sim::detail
